//! Test 6: the loop of Figure 56.

use super::fmt::{contacts, f, how, n};
use super::picture;
use crate::test6_loop::*;

pub fn section(t: &Test6) -> String {
    let completes = if t.finished {
        format!("yes, `cnt` = {} after {} s", n(t.cnt), f(t.time, 0))
    } else {
        format!(
            "no: still running after {} s, `cnt` = {}",
            f(t.time, 0),
            n(t.cnt)
        )
    };
    let (x0, x1) = MEASURED_X;
    format!(
        "## Test 6: the loop of Figure 56 (Figure 57)

`{WORLD}` (open ground, a few trees well off the path), Workpartner, seed {SEED}.
PATH is taught first, as the dissertation's was: a run with `locate(0,0,0)`,
`record(PATH)`, `goahead(25)`, `turn(d=10,c=0.1)`, `goahead(27)` at 0.4 m/s records
{} points of the estimated pose (2 Hz navigation fixes, 10 Hz dead reckoning). Then
`examples/loop.ilmr` with TURN1/TURN2 from `examples/skills/turns.ilms`, verbatim, runs
with that path.

| | dissertation | this simulator | asserted |
| --- | --- | --- | --- |
| completes | yes | {completes}; {} followpaths completed, TURN2 {} | finished, {FOLLOWPATHS} followpaths completed, TURN2 completed |
| distance driven | more than 200 m | {} m | > {} m |
| on the taught path (between {} and {} m along) | not given | at most {} m off | < {} m |
| contacts | none | {} | 0 |

Two things made the taught path drivable. A recording is dense and jittery and bends
on full lock where it was taught so; no filleted polyline through its points stays
within 0.25 1/m (`ilmr_motion::path::taught` simplifies it to within 5 cm,
Douglas-Peucker, and merges corners too crowded for a fillet). And TURN1 reverses a
quarter circle on full lock, which leaves Workpartner 4 m beside the path's end facing
across it, exactly one turning radius from the path: `followpath(PATH,BACKWARDS)` used
to plan to the path's first point and was refused (\"curvature 0.683\"). It now joins
the path where it can meet it, up to five turning radii along, backing up a little
first (the `r` manoeuvre) when no curve within the robot's curvature meets it going
on: the three-point turn a driver would make. The scripted run of `ilmrc run`
(`tests/run/fig56_loop.*`, the path as three waypoints, 52 m) completes the same way
(`tests/snapshots/run__trace_fig56_loop.snap`).

{}",
        t.taught.len(),
        t.followpaths,
        how(t.turn2_how.as_deref()),
        f(t.driven, 1),
        n(DRIVEN_BAR),
        n(x0),
        n(x1),
        f(t.off, 3),
        n(OFF_BAR),
        contacts(t.contacts),
        picture(6, "Test 6: the taught PATH and Workpartner's path back and forth along it twice"),
    )
}
