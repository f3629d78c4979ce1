//! Test 1 (Table 10) with the calibrated error model, each row run `REPLICAS` times:
//! every trial completes its turn, and the replicas' mean maximum and mean deviation
//! come within `TOLERANCE` (30 %) of the dissertation's, except where a comment says
//! why not.

use ilmr_experiments::stats::Spread;
use ilmr_experiments::test1_turn::{
    MORO_C04, MORO_C06, REPLICAS, Spec, Sweep, TOLERANCE, WORKPARTNER_C025, sweep,
};

// Issue 15: every experiment over at least 20 seeds.
const _: () = assert!(REPLICAS >= 20);

fn run(spec: &'static Spec) -> Sweep {
    let s = sweep(spec).expect("the sweep runs");
    assert_eq!(s.replicas.len(), REPLICAS);
    for t in s.trials() {
        assert!(
            t.finished,
            "turn c={} v={} seed {} finished",
            spec.c, t.v, t.seed
        );
        assert_eq!(
            t.how.as_deref(),
            Some("completed"),
            "c={} v={} seed {}",
            spec.c,
            t.v,
            t.seed
        );
    }
    let (max, mean) = (s.max(), s.mean());
    println!(
        "{}: max {:.4} [{:.4}, {:.4}] vs {}, mean {:.4} [{:.4}, {:.4}] vs {}",
        s.label(),
        max.mean,
        max.lo,
        max.hi,
        spec.dissertation.max,
        mean.mean,
        mean.lo,
        mean.hi,
        spec.dissertation.mean
    );
    s
}

fn within(what: &str, s: &Spread, table: f64, tolerance: f64) {
    let e = s.relative_error(table);
    assert!(
        e.abs() <= tolerance,
        "{what}: {:.4} is {:+.0} % off Table 10's {table} (tolerance {:.0} %)",
        s.mean,
        100.0 * e,
        100.0 * tolerance
    );
}

#[test]
fn moro_turn_c06_reproduces_table_10_but_its_one_deviant_trial() {
    let s = run(&MORO_C06);
    within(
        "MoRo c=0.6 mean",
        &s.mean(),
        MORO_C06.dissertation.mean,
        TOLERANCE,
    );
    // Table 10's 0.08 m is one trial far from the row's others: its standard deviation
    // (0.0242) exceeds its mean (0.0225), so the other seven average 0.014 m. The
    // model, fitted to the means and to the c=0.4 row whose maximum is 0.04 m, gives
    // no such trial; the maximum is asserted only to stay below the table's (a model
    // that reached 0.08 m on average would miss every other figure of the table).
    let max = s.max();
    assert!(
        max.mean < MORO_C06.dissertation.max && max.mean > MORO_C06.dissertation.mean,
        "MoRo c=0.6 max {:.4}",
        max.mean
    );
}

#[test]
fn moro_turn_c04_reproduces_table_10() {
    let s = run(&MORO_C04);
    within(
        "MoRo c=0.4 max",
        &s.max(),
        MORO_C04.dissertation.max,
        TOLERANCE,
    );
    within(
        "MoRo c=0.4 mean",
        &s.mean(),
        MORO_C04.dissertation.mean,
        TOLERANCE,
    );
}

#[test]
fn workpartner_turn_c025_reproduces_table_10() {
    let s = run(&WORKPARTNER_C025);
    within(
        "Workpartner max",
        &s.max(),
        WORKPARTNER_C025.dissertation.max,
        TOLERANCE,
    );
    within(
        "Workpartner mean",
        &s.mean(),
        WORKPARTNER_C025.dissertation.mean,
        TOLERANCE,
    );
}
