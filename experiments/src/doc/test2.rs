//! Test 2: `turn(left)` in a corridor, Table 11.

use super::fmt::{contacts, f, n};
use super::picture;
use crate::test2_turn_left::*;

pub fn section(t: &Test2) -> String {
    let start = match t.turn_start_x {
        Some(x) => format!(
            "the heading leaves east by {} degrees at x = {}",
            n(EARLY_DEG),
            f(x, 2)
        ),
        None => "never".into(),
    };
    let e = t.end;
    format!(
        "## Test 2: `turn(left)` in a corridor (Table 11, Figure 47)

World `{WORLD}` (2.4 m corridor east, a left corner at x = {} into a 2.4 m corridor
north), MoRo, seed {SEED}, 0.3 m/s: `t=turn(left)` then `goahead(1.5)`. There is no
room at the start, so the robot follows the left wall at its distance until
`turn_space_free` holds, then drives the quarter circle. y deviation: largest
|y - y0| before x = {}; x deviation: half the spread of x while heading north (within
{} degrees).

| | dissertation | this simulator | asserted |
| --- | --- | --- | --- |
| y deviation | {} m | {} m | <= {} m |
| x deviation | {} m | {} m | <= {} m |
| turn starts | at the corner | {start} | not before x = {} |
| end | up the side corridor | ({}, {}), {} degrees, {} | x in {}..{}, y > {} |

{}",
        n(CORNER_X),
        n(BEFORE_X),
        n(NORTH_DEG),
        n(TABLE_11_Y),
        f(t.y_deviation, 4),
        n(BAR_Y),
        n(TABLE_11_X),
        f(t.x_deviation, 4),
        n(BAR_X),
        n(BEFORE_X),
        f(e.x, 3),
        f(e.y, 3),
        f(e.h.to_degrees(), 1),
        contacts(t.contacts),
        n(CORNER_X),
        n(SIDE_EAST_X),
        n(END_Y),
        picture(2, "Test 2: the corridor and MoRo's path round the corner"),
    )
}
