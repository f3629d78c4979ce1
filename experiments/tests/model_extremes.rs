//! A robot model may put every parameter at either end of its range and a
//! task still runs in bounded time and memory (issue 12: `stop_margin 1e6`
//! ran on at 795 MB, `1e308` crashed the VM's safety sweep). The largest
//! braking distance a model admits (10 m/s, 0.01 m/s^2, a 10 m margin) is
//! the sweep's worst case.

mod experiment;

use experiment::{compile, run, shipped, vm};
use ilmr_model::{PARAMETER_SPECS, RobotModel, Valid};
use ilmr_sim::{RobotKind, SimRobot};
use std::time::{Duration, Instant};

const TASK: &str = "obsavoid(off)\ngoahead(3)\nturn(left)\ngoahead(-1)\n";

fn runs_within_bounds(model: RobotModel, what: &str) {
    let started = Instant::now();
    let module = compile("extremes", TASK, &model);
    // Open floor, where even a 20 m robot fits; a robot that cannot start
    // must say why.
    let robot = match SimRobot::new(model, RobotKind::Moro, shipped("empty"), 1) {
        Ok(r) => r,
        Err(e) => {
            assert!(!e.to_string().is_empty(), "{what}");
            return;
        }
    };
    let mut vm = vm(module, robot);
    let out = run(&mut vm, 5.0);
    assert!(!out.trace.is_empty(), "{what}: no tick ran");
    assert!(
        out.trace.iter().all(|p| p.x.is_finite() && p.y.is_finite()),
        "{what}"
    );
    // A guard against a hang, not a benchmark (debug build, shared machine).
    assert!(
        started.elapsed() < Duration::from_secs(60),
        "{what}: {:?}",
        started.elapsed()
    );
}

/// MoRo's file with `name`'s own line replaced by `name value`.
fn set(name: &str, value: f64) -> RobotModel {
    let base = include_str!("../../robots/model/models/moro.ini");
    let kept: Vec<&str> = base
        .lines()
        .filter(|l| {
            !l.to_ascii_lowercase()
                .starts_with(&format!("{} ", name.to_ascii_lowercase()))
        })
        .collect();
    let text = kept
        .join("\n")
        .replace("[END]", &format!("{name} {value}\n[END]"));
    let (model, warnings) = RobotModel::parse(&text, "moro");
    // In range, so kept (default_speed may then be clamped to max_speed).
    assert!(
        warnings.iter().all(|w| !w.message.contains("out of range")),
        "{name} {value}: {warnings:?}"
    );
    assert!(model.parameter(name).is_some(), "{name} {value}");
    model
}

#[test]
fn every_parameter_at_either_end_of_its_range_runs() {
    for spec in PARAMETER_SPECS {
        let (lo, hi) = match spec.valid {
            Valid::PositiveAtMost(max) => (max * 1e-6, max),
            Valid::Between(min, max) => (min, max),
        };
        for v in [lo, hi] {
            runs_within_bounds(set(spec.name, v), &format!("{} {v}", spec.name));
        }
    }
}

#[test]
fn the_longest_braking_distance_runs() {
    let base = include_str!("../../robots/model/models/moro.ini");
    let text = base
        .lines()
        .filter(|l| {
            ![
                "max_speed ",
                "default_speed ",
                "max_deceleration ",
                "stop_margin ",
            ]
            .iter()
            .any(|p| l.starts_with(p))
        })
        .collect::<Vec<_>>()
        .join("\n")
        .replace(
            "[END]",
            "max_speed 10\ndefault_speed 10\nmax_deceleration 0.01\nstop_margin 10\n[END]",
        );
    let (model, warnings) = RobotModel::parse(&text, "moro");
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(model.stop_margin(), 10.0);
    runs_within_bounds(model, "braking over 5 km");
}
