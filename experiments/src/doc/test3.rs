//! Test 3: `followwall(left,1.0)`, Table 12.

use super::fmt::{f, n};
use super::picture;
use crate::test3_followwall::*;

pub fn section(t: &Test3) -> String {
    let faces: Vec<String> = t.follows.iter().map(|r| n(GOAL + r.off)).collect();
    let worlds: Vec<String> = t
        .follows
        .iter()
        .map(|r| format!("`wall_{:.1}.toml`", r.off))
        .collect();
    let mut s = format!(
        "## Test 3: `followwall(left,1.0)` (Table 12, Figure 49)

Worlds {}: a wall whose face is {} m left of the start, with a 1 m door opening;
MoRo, seed {SEED}, 0.3 m/s, {} m driven. Overshoot: how much closer than {} m the
robot came to the wall face.

| off the goal distance | dissertation overshoot | this simulator overshoot | error after 3 m | error at {} m | asserted |
| --- | --- | --- | --- | --- | --- |
",
        worlds.join(", "),
        faces.join(", "),
        n(TRAVEL),
        f(GOAL, 1),
        n(TRAVEL),
    );
    for (i, r) in t.follows.iter().enumerate() {
        let asserted = if i == 0 {
            format!(
                "overshoot <= table + {}, after 3 m <= {}, end <= {}",
                n(OVERSHOOT_SLACK),
                n(BAR_AT_3M),
                n(BAR_END)
            )
        } else {
            "same".into()
        };
        s.push_str(&format!(
            "| {} m | {} m | {} m | {} m | {} m | {asserted} |\n",
            f(r.off, 1),
            n(r.table),
            f(r.overshoot, 4),
            f(r.at_3m, 4),
            f(r.at_end, 4),
        ));
    }
    let worst_3m = t.follows.iter().map(|r| r.at_3m).fold(0.0, f64::max);
    s.push_str(&format!(
        "
The distance is reached within 3 m of travel, as in the dissertation (at most {} m
off by then); the door opening does not move the fitted wall.

{}",
        f(worst_3m, 4),
        picture(
            3,
            "Test 3: the three walls, each in the colour of its run, and the paths"
        )
    ));
    s
}
