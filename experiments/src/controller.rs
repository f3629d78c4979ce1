//! What this project's changes to the position controller add (issue 15 item 5):
//! Test 1's rows and Test 5 on the calibrated robots with the controller as the
//! dissertation describes it (eqs. 4-8, `ilmr_vm::Controller::DISSERTATION`), with
//! the commanded curvature fed back as c_now, and as this project runs it
//! (`ilmr_vm::Controller::PROJECT`: that and the look-ahead floor of half a turning
//! radius), over the same seeds, so that each difference is the controller's alone.

use ilmr_vm::Controller;

use crate::stats::Spread;
use crate::test1_turn::{self as t1, Errors, SPECS};
use crate::{seeds, test5_short_task as t5};

/// The variants compared, in the report's order: the dissertation's, with one of
/// this project's changes, and this project's (both).
pub const VARIANTS: [(&str, Controller); 3] = [
    ("the dissertation's controller", Controller::DISSERTATION),
    (
        "with the commanded c_now only",
        Controller {
            lookahead_floor: false,
            commanded_curvature: true,
        },
    ),
    ("this project's controller", Controller::PROJECT),
];

/// One measure under each of [`VARIANTS`], in its order.
#[derive(Debug, Clone)]
pub struct Pair {
    pub what: String,
    /// The dissertation's measured figure it stands beside, metres.
    pub table: f64,
    pub by: Vec<Spread>,
}

impl Pair {
    /// The dissertation's variant and this project's.
    pub fn dissertation(&self) -> &Spread {
        &self.by[0]
    }

    pub fn project(&self) -> &Spread {
        &self.by[VARIANTS.len() - 1]
    }
}

#[derive(Debug, Clone)]
pub struct Comparison {
    /// Test 1's replicas per row, and Test 5's seeds.
    pub replicas: usize,
    pub seeds: usize,
    pub rows: Vec<Pair>,
}

fn pair(
    what: String,
    table: f64,
    by: impl Fn(usize) -> Result<Spread, String>,
) -> Result<Pair, String> {
    Ok(Pair {
        what,
        table,
        by: (0..VARIANTS.len()).map(by).collect::<Result<_, _>>()?,
    })
}

/// Test 1 with `replicas` replicas per row, Test 5 over `n` seeds, both variants.
pub fn run(replicas: usize, n: usize) -> Result<Comparison, String> {
    let mut rows = Vec::new();
    for spec in SPECS {
        let sweeps = VARIANTS
            .iter()
            .map(|(_, c)| t1::sweep_controlled(spec, replicas, &Errors::default(), *c))
            .collect::<Result<Vec<_>, _>>()?;
        let label = sweeps[0].label();
        let d = spec.dissertation;
        rows.push(pair(format!("Test 1, {label}, maximum"), d.max, |i| {
            Ok(sweeps[i].max())
        })?);
        rows.push(pair(format!("Test 1, {label}, mean"), d.mean, |i| {
            Ok(sweeps[i].mean())
        })?);
    }
    let short = VARIANTS
        .iter()
        .map(|(_, c)| {
            seeds::first(n)
                .map(|s| t5::run_controlled(crate::predictions::PROFILE, s, *c))
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<Vec<_>, _>>()?;
    let of = |i: usize, f: fn(&t5::Test5) -> f64| {
        Spread::of(&short[i].iter().map(f).collect::<Vec<_>>())
    };
    rows.push(pair(
        "Test 5, largest distance from the route".into(),
        t5::FIGURE_53,
        |i| Ok(of(i, |r| r.max_error)),
    )?);
    rows.push(pair(
        "Test 5, distance from the start at the end".into(),
        t5::FIGURE_53,
        |i| Ok(of(i, |r| r.home)),
    )?);
    Ok(Comparison {
        replicas,
        seeds: n,
        rows,
    })
}
