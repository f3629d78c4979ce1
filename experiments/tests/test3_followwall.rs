//! Test 3 (Table 12): `followwall(left,1.0)` reaches the distance within 3 m from 0.4,
//! 1.0 and 1.2 m off it, without touching the wall, and runs until it is broken.

use ilmr_experiments::test3_followwall::{BAR_AT_3M, BAR_END, OFFSETS, OVERSHOOT_SLACK, run};

#[test]
fn followwall_reaches_the_distance_within_three_metres() {
    let t = run().expect("test 3 runs");
    assert_eq!(t.follows.len(), OFFSETS.len());
    for r in &t.follows {
        println!(
            "followwall(left,1.0) from {} m off: overshoot {:.4} m (Table 12: {} m), \
             error after 3 m {:.4} m, at the end {:.4} m",
            r.off, r.overshoot, r.table, r.at_3m, r.at_end
        );
        assert_eq!(r.contacts, 0);
        assert!(!r.finished, "followwall runs until it is broken");
        assert!(
            r.overshoot <= r.table + OVERSHOOT_SLACK,
            "overshoot {}",
            r.overshoot
        );
        assert!(r.at_3m <= BAR_AT_3M, "error after 3 m {}", r.at_3m);
        assert!(r.at_end <= BAR_END, "error at the end {}", r.at_end);
    }
}
