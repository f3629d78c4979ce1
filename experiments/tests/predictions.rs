//! Tables 11 and 12 and Figure 53 as predictions of the calibrated model (fitted to
//! Table 10 alone), over 20 seeds, asserted against the dissertation's figures with
//! the tolerance each states.

use ilmr_experiments::predictions::{self, SEEDS};
use ilmr_experiments::{test2_turn_left as t2, test5_short_task as t5};

const _: () = assert!(SEEDS >= 20);

#[test]
fn table_11_turn_left_is_no_worse_than_moro_and_never_touches() {
    let p = predictions::test2().expect("test 2 runs");
    println!("x {:?}\ny {:?}\nclean {} of {}", p.x, p.y, p.clean, p.runs);
    assert_eq!(
        p.clean, p.runs,
        "every turn(left) completes without a contact"
    );
    // The real MoRo's 0.04 m and 0.01 m are upper bounds for the model: it lacks
    // whatever made the real corridor's runs wander (docs/experiments.md says what).
    assert!(p.x.mean <= t2::TABLE_11_X, "x {:.4}", p.x.mean);
    assert!(p.y.mean <= t2::TABLE_11_Y, "y {:.4}", p.y.mean);
}

#[test]
fn table_12_followwall_overshoot_within_a_factor_of_two() {
    // Table 12 was measured on the dissertation's qnx-simulator, whose followwall
    // settled 2-5 cm past the goal distance; the calibrated model is another robot,
    // so within a factor of two (100 %) of each row, and never touching the wall.
    for f in predictions::test3().expect("test 3 runs") {
        println!("from {} m: {:?}", f.off, f.overshoot);
        let e = f.overshoot.relative_error(f.table);
        assert!(
            e.abs() <= 1.0,
            "from {} m: {:.4} vs {}",
            f.off,
            f.overshoot.mean,
            f.table
        );
        assert_eq!(f.contacts, 0, "from {} m", f.off);
    }
}

#[test]
fn figure_53_back_at_the_start_within_the_dissertations_error() {
    let p = predictions::test5().expect("test 5 runs");
    println!("max error {:?}\nhome {:?}", p.max_error, p.home);
    assert_eq!(p.finished, SEEDS);
    // Figure 53's 0.07 m was the largest error of MoRo's three runs: no seed of the
    // model may exceed it.
    assert!(p.max_error.max <= t5::FIGURE_53, "{:.4}", p.max_error.max);
    assert!(p.home.max <= t5::FIGURE_53, "{:.4}", p.home.max);
}
