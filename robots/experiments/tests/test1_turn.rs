//! Test 1 (Table 10): every trial completes its turn; the worst trial of each sweep
//! stays within the bar.

use ilmr_experiments::test1_turn::{MORO_C04, MORO_C06, Spec, WORKPARTNER_C025, sweep};

fn check(spec: &'static Spec) {
    let s = sweep(spec).expect("the sweep runs");
    for t in &s.trials {
        let r = 1.0 / spec.c;
        println!(
            "turn(d=90,c={}) v={}: max deviation {:.4} m, end ({:.3}, {:.3}) vs ({r:.3}, {r:.3})",
            spec.c, t.v, t.max_deviation, t.end.x, t.end.y
        );
        assert!(t.finished, "turn c={} v={} finished", spec.c, t.v);
        assert_eq!(
            t.how.as_deref(),
            Some("completed"),
            "c={} v={}",
            spec.c,
            t.v
        );
    }
    let worst = s.worst();
    let (mean, std) = s.mean_std();
    println!(
        "{}: {} trials, max {worst:.4} m, mean of maxima {mean:.4} m, std {std:.4} m",
        s.label(),
        s.trials.len()
    );
    assert!(worst <= spec.bar, "worst {worst}, bar {}", spec.bar);
}

#[test]
fn moro_turn_c06_within_table_10() {
    check(&MORO_C06);
}

#[test]
fn moro_turn_c04_within_table_10() {
    check(&MORO_C04);
}

#[test]
fn workpartner_turn_c025_within_table_10() {
    check(&WORKPARTNER_C025);
}
