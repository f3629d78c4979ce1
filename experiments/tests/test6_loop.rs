//! Test 6 (Figures 56-57): Workpartner drives the taught path back and forth twice,
//! more than 200 m, without contact.

use ilmr_experiments::test6_loop::{DRIVEN_BAR, FOLLOWPATHS, LOOPS, MEASURED_X, OFF_BAR, run};

#[test]
fn figure_56_drives_the_taught_path_back_and_forth_twice() {
    let t = run().expect("test 6 runs");
    println!(
        "test 6: {} in {:.1} s, {:.1} m driven, {} followpaths completed, \
         cnt = {}, at most {:.3} m off the taught path between x = {} and {} m, \
         taught path {} points, contacts {}",
        if t.finished {
            "completed"
        } else {
            "NOT completed"
        },
        t.time,
        t.driven,
        t.followpaths,
        t.cnt,
        t.off,
        MEASURED_X.0,
        MEASURED_X.1,
        t.taught.len(),
        t.contacts
    );
    assert!(t.taught_finished, "teaching run ends");
    assert!(t.finished, "the loop ends");
    assert_eq!(t.cnt, LOOPS);
    assert_eq!(t.followpaths, FOLLOWPATHS, "forwards and backwards, twice");
    assert_eq!(t.turn2_how.as_deref(), Some("completed"));
    assert!(t.driven > DRIVEN_BAR, "more than 200 m: {}", t.driven);
    assert_eq!(t.contacts, 0);
    assert!(t.off < OFF_BAR, "on the taught path: {}", t.off);
}
