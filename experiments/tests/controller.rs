//! The position controller as the dissertation describes it beside this project's,
//! on the calibrated robots over the same seeds (`seeds::for_tests()` of them; Test
//! 1 with as many replicas): the honest form of "better than the seed".

use ilmr_experiments::controller::{self, VARIANTS};
use ilmr_experiments::seeds;

#[test]
fn this_projects_controller_is_better_than_the_dissertations_on_every_figure() {
    let n = seeds::for_tests();
    let c = controller::run(n, n).expect("the comparison runs");
    for r in &c.rows {
        println!(
            "{}: {}",
            r.what,
            r.by.iter()
                .map(|s| format!("{:.4} [{:.4}, {:.4}]", s.mean, s.lo, s.hi))
                .collect::<Vec<_>>()
                .join(" / ")
        );
        assert_eq!(r.by.len(), VARIANTS.len());
        // Better with the 95 % intervals apart, not by the means alone.
        assert!(
            r.project().hi < r.dissertation().lo,
            "{}: {:?} vs {:?}",
            r.what,
            r.project(),
            r.dissertation()
        );
    }
    // The look-ahead floor is Workpartner's: with the commanded c_now alone its turn
    // is worse than with the floor too, and MoRo's (floor below its shortest
    // look-ahead) are the same.
    for r in &c.rows {
        let commanded_only = &r.by[1];
        if r.what.contains("Workpartner") {
            assert!(
                r.project().mean < commanded_only.mean,
                "{}: {:?} vs {:?}",
                r.what,
                r.project(),
                commanded_only
            );
        } else {
            assert_eq!(r.project(), commanded_only, "{}", r.what);
        }
    }
}
