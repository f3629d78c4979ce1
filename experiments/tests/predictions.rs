//! Tests 2-7 and Figure 20 on the calibrated model (fitted to Table 10 alone), over
//! the first `seeds::for_tests()` seeds (`ILMR_EXPERIMENTS=full`: all 20), each
//! asserted against the dissertation's figure with the tolerance it states, never
//! against what the simulator gave last.

use ilmr_experiments::predictions;
use ilmr_experiments::seeds::{self, FULL};
use ilmr_experiments::{
    fig20_fetch_boxes as f20, test2_turn_left as t2, test5_short_task as t5, test6_loop as t6,
};

const _: () = assert!(FULL >= 20);

#[test]
fn table_11_turn_left_is_no_worse_than_moro_and_never_touches() {
    let p = predictions::test2(seeds::for_tests()).expect("test 2 runs");
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
    for f in predictions::test3(seeds::for_tests()).expect("test 3 runs") {
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
fn figure_50_obstacle_avoidance_goes_round_on_every_seed() {
    // Section 5.6.3: avoidance "was tested successfully with MoRo several times";
    // the model must pass the box on every seed without touching it.
    let p = predictions::test4(seeds::for_tests()).expect("test 4 runs");
    println!("{p:?}");
    assert_eq!(p.round, p.runs, "every seed goes round and back");
    assert_eq!(p.contacts, 0);
    assert!(p.clearance.min > 0.0, "{:?}", p.clearance);
}

#[test]
fn figure_53_back_at_the_start_within_the_dissertations_error() {
    let n = seeds::for_tests();
    let p = predictions::test5(n).expect("test 5 runs");
    println!(
        "max error {:?}\nhome {:?}\nlink {:?}",
        p.max_error, p.home, p.link_gap
    );
    assert_eq!(p.finished, n);
    // Figure 53's 0.07 m was the largest error of MoRo's three runs: no seed of the
    // model may exceed it.
    assert!(p.max_error.max <= t5::FIGURE_53, "{:.4}", p.max_error.max);
    assert!(p.home.max <= t5::FIGURE_53, "{:.4}", p.home.max);
    // Figure 55: "about 0.1 second to link"; no seed may take longer.
    assert!(p.link_gap.max <= t5::LINK_BAR, "{:.3}", p.link_gap.max);
}

#[test]
fn figure_57_the_loop_drives_more_than_200_m_on_every_seed() {
    let p = predictions::test6(seeds::for_tests()).expect("test 6 runs");
    println!("{p:?}");
    assert_eq!(p.done, p.runs, "the loop driven out on every seed");
    // Section 5.6.5: "the total distance Workpartner travelled was more than 200 m".
    assert!(p.driven.min > t6::DRIVEN_BAR, "{:?}", p.driven);
    assert_eq!(p.contacts, 0);
}

#[test]
fn figure_59_the_way_out_is_learnt_on_every_seed() {
    // Section 5.6.6: "the task execution was successful".
    let p = predictions::test7(seeds::for_tests()).expect("test 7 runs");
    println!("{p:?}");
    assert_eq!(p.out, p.runs, "out into the lobby on every seed");
    assert_eq!(p.contacts, 0);
}

#[test]
fn figure_59_path_1_is_driven_again_on_every_seed() {
    // Section 5.6.6: "the path was learnt and could be driven next time with the
    // command followpath(path-1)".
    let p = predictions::test7(seeds::for_tests()).expect("test 7 runs");
    assert_eq!(p.replayed, p.runs, "path_1 driven again on every seed");
}

#[test]
fn figure_20_never_touches_anything() {
    let p = predictions::fig20(seeds::for_tests()).expect("Figure 20 runs");
    println!("{p:?}");
    assert_eq!(p.contacts, 0);
}

#[test]
fn figure_20_box_at_is_the_box_on_every_search() {
    // Section 4.4: findtarget searches "the same as it is with the sensor-command"
    // and ends when it finds the object; issued in the hall, it must go on until
    // the store room's box is in view, not end on a wall or the cupboard.
    let p = predictions::fig20(seeds::for_tests()).expect("Figure 20 runs");
    println!("box_at off {:?}, {} searches", p.box_off, p.found);
    // Both trips of every seed find the box before `approach` may use it.
    assert_eq!(p.found, p.runs * 2, "searches ended");
    assert!(
        p.box_off.max <= f20::BOX_CALIBRATED_WITHIN,
        "{:.3} m from the box",
        p.box_off.max
    );
}

#[test]
fn figure_20_fetches_both_loads_and_comes_home_on_every_seed() {
    // Section 4.1 gives the task, not a run; the corrected figure must do what it
    // describes on every seed.
    let p = predictions::fig20(seeds::for_tests()).expect("Figure 20 runs");
    assert_eq!(p.home, p.runs);
}
