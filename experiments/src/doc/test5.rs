//! Test 5: the short task of Figure 52.

use super::fmt::{f, n};
use super::picture;
use crate::test5_short_task::*;

pub fn section(t: &Test5) -> String {
    // A link within the tick: the end and the next start share a time stamp.
    let link = if t.link_gap < 0.01 - 1e-9 {
        format!("within the tick ({} s)", f(t.link_gap, 2))
    } else {
        format!("{} s", f(t.link_gap, 2))
    };
    format!(
        "## Test 5: the short task of Figure 52 (Figures 53-55)

`empty`, MoRo, seed {SEED}: Figure 52 verbatim (`speed(0.4) goahead(1.2)
turn(d=90,c=0.5) m=goahead(0.7) wait(m) speed(-0.4) use(goalpos) goahead(-0.7)
turn(d=90,c=0.5) goahead(-1.2)`). Position error: largest distance of the true trace
from the ideal route (1.2 m, the quarter circle of radius 2, 0.7 m).

| | dissertation | this simulator | asserted |
| --- | --- | --- | --- |
| max position error | {} m | {} m | <= {} m |
| links | between each pair | {} (2 out, 2 back) | {LINKS} |
| time to link | about 0.1 s | {link} | <= {} s |
| stop between linked commands | none | lowest speed {} m/s between cruising and braking | >= {} m/s |
| back at the start | yes | {} m from it | <= {} m |
| completes | yes | {} | yes |

The picture's lower panels are Figure 54: the speed, and the curvature, over time;
the circles and crosses on the map (and the ticks below) are where each movement
command started and ended.

{}",
        n(FIGURE_53),
        f(t.max_error, 4),
        n(FIGURE_53),
        t.links,
        n(LINK_BAR),
        f(t.dip, 3),
        n(DIP_BAR),
        f(t.home, 4),
        n(FIGURE_53),
        if t.finished { "yes" } else { "no" },
        picture(5, "Test 5: the route out and back over the ideal one; speed and curvature over time"),
    )
}
