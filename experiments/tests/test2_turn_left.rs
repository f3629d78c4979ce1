//! Test 2 (Table 11): `turn(left)` follows the left wall to the corner, then turns; a
//! linked `goahead(1.5)` takes MoRo up the side corridor.

use ilmr_experiments::test2_turn_left::{BAR_X, BAR_Y, CORNER_X, END_Y, SIDE_EAST_X, run};

#[test]
fn turn_left_follows_the_wall_to_the_corner_then_turns() {
    let t = run().expect("test 2 runs");
    let end = t.end;
    println!(
        "turn(left) in the corridor: y deviation before the corner {:.4} m, \
         x deviation heading north {:.4} m, end ({:.3}, {:.3}, {:.1} deg)",
        t.y_deviation,
        t.x_deviation,
        end.x,
        end.y,
        end.h.to_degrees()
    );
    assert!(t.finished, "turn(left) and goahead(1.5) finished");
    assert_eq!(t.turn_how.as_deref(), Some("completed"));
    assert_eq!(t.contacts, 0, "touched a wall");
    assert!(!t.turned_early, "the turn began before the corner");
    assert!(t.north > 0, "never headed north");
    assert!(t.y_deviation <= BAR_Y, "y deviation {}", t.y_deviation);
    assert!(t.x_deviation <= BAR_X, "x deviation {}", t.x_deviation);
    assert!(
        (CORNER_X..SIDE_EAST_X).contains(&end.x),
        "ended in the side corridor: {end:?}"
    );
    assert!(end.y > END_Y, "went up the side corridor: {end:?}");
}
