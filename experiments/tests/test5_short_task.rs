//! Test 5 (Figures 52-55): linked commands do not stop between them, and the robot
//! comes back to its start by `use(goalpos)` and reversed commands.

use ilmr_experiments::test5_short_task::{DIP_BAR, FIGURE_53, LINK_BAR, LINKS, run};

#[test]
fn figure_52_links_without_stopping_and_returns_to_the_start() {
    let t = run().expect("test 5 runs");
    println!(
        "Figure 52: max position error {:.4} m, {} links, longest link {:.2} s, \
         lowest speed between linked commands {:.3} m/s, back {:.4} m from the start",
        t.max_error, t.links, t.link_gap, t.dip, t.home
    );
    assert!(t.finished, "the task finished");
    assert_eq!(t.links, LINKS, "two links out, two back");
    // Linking happens within one tick: the end of the first command and the start
    // of the next share a time stamp.
    assert!(
        t.link_gap <= LINK_BAR + 1e-9,
        "linking took {} s",
        t.link_gap
    );
    assert!(
        t.dip >= DIP_BAR,
        "the speed dipped to {} between linked commands",
        t.dip
    );
    assert!(
        t.max_error <= FIGURE_53,
        "max position error {}",
        t.max_error
    );
    assert!(t.home <= FIGURE_53, "ended {} m from the start", t.home);
}
