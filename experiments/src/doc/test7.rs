//! Test 7: the way out of the laboratory (Figures 58-59).

use super::fmt::{contacts, f, how};
use super::picture;
use crate::test7_way_out::*;

pub fn section(t: &Test7) -> String {
    let w = &t.way_out;
    let r = &t.replay;
    let completes = if w.finished {
        format!(
            "yes, in {} s, {} m, ends in the lobby at ({}, {}), {}",
            f(w.time, 1),
            f(w.driven, 1),
            f(w.end.x, 2),
            f(w.end.y, 2),
            contacts(w.contacts)
        )
    } else {
        format!("no: still running after {} s", f(w.time, 1))
    };
    let ends: Vec<String> = w
        .ends
        .iter()
        .map(|(text, h)| format!("`{text}` {}", how(h.as_deref())))
        .collect();
    format!(
        "## Test 7: the way out of the laboratory (Figures 58-59)

`{WORLD}`, MoRo, seed {SEED}: `examples/way_out.ilmr` verbatim, in the shipped office
world, whose corridors are 2 m wide as the laboratory's in Figure 59. Each `turn(left)`
is a quarter circle at 1 m radius (three quarters of full lock, which leaves the
controller steering in reserve), begun where MoRo's outline (1.2 x 0.6 m about its
rear axle, kept 0.2 m from anything, the margin round its corners as round as a
margin is) and the avoider's 0.72 m band (section 4.5.7, its own margin in it) have
room along it and on after it (section 4.5.3): out of the door it turns once the rear
axle is in the corridor, within 0.1 m of the door's line, into the west
corridor it follows the wall until the corner is passed, its leg stopping short of
the corridor's end wall rather than driving into the avoider's area.
Then `followpath(path_1)` is driven again from the start on a fresh robot (seed {}).

| | dissertation | this simulator | asserted |
| --- | --- | --- | --- |
| completes | yes | {completes} | finished, no contact, gotoxy(door) and goahead(1) completed |
| the door | found on the right | at ({}, {}), heading {} degrees (through it) | within {} m of the door's middle |
| path_1 driven again | yes | {} in {} s, at most {} m off the recording, ends {} m from its end, {} | completed, < {} m off, < {} m from the end |

How the statements ended: {}.

Under the execution rules `if` is a guard that does not hold its block back, so
`record(close)` is issued with `if(dist>5)`, right after the door was found: path_1 is
the way round the bench to where the door was seen ({} points).

The door is found by `ilmr-sim`'s scan detector (`robots/sim/src/robot/doors.rs`): a
range step up (a jamb), beams that pass behind the line between the jambs, and a step
back down, the jambs 0.8-1.2 m apart (the model's `door` object, plus the beam spacing
at that range), with at least three returns beside each jamb on one straight wall. The
old heuristic closed an opening only at a beam as near as the first jamb, which an
oblique view never gives (the far jamb is further away), so it never reported the lab
door. `gotoxy(door)` now arrives with the variable's heading, through the door:
arriving facing the door's middle from where the robot stood, MoRo reached it 38
degrees off square and the avoider (equation (12), 0.72 m wide) blocked it on the
jamb. It drives the last 1.15 m (MoRo's front, 0.95 m ahead of its rear axle, and
0.2 m) straight along that heading: ending the curve at the door itself lined the
rear axle up there with the front still turning past the line, and on seed 11 of the
calibrated MoRo the supervisor held it 0.2 m from the door's west post.

The picture is Figure 59's: the walls the scanner saw (its hits, one per 10 cm, a scan
a second) with the world drawn under them, the way out, path_1 as recorded (dashed)
and its replay.

{}",
        r.seed,
        f(w.door.0, 3),
        f(w.door.1, 3),
        f(w.door.2.to_degrees(), 1),
        DOOR_WITHIN,
        how(r.how.as_deref()),
        f(r.time, 1),
        f(r.off, 3),
        f(r.miss, 3),
        contacts(r.contacts),
        REPLAY_OFF,
        REPLAY_MISS,
        ends.join(", "),
        w.path_1.len(),
        picture(7, "Test 7: the lab, the scanner's hits, the way out, path_1 and its replay"),
    )
}
