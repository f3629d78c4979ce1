//! Test 4: obstacle avoidance.

use super::fmt::{contacts, f, n};
use super::picture;
use crate::test4_obstacle::*;

fn on(a: &Avoid) -> String {
    format!(
        "widest {} m off the line, footprint {} m from the box at the closest, ends at ({}, {}) after {} s, {}",
        f(a.aside, 3),
        f(a.clearance, 3),
        f(a.end.x, 3),
        f(a.end.y, 3),
        f(a.time, 1),
        contacts(a.contacts)
    )
}

fn stop(a: &Avoid) -> String {
    format!(
        "front stops at x = {} m (box face at {} m), goahead {}, {}",
        f(a.front, 3),
        n(BOX.0 - BOX.2),
        if a.finished { "ends" } else { "does not end" },
        contacts(a.contacts)
    )
}

fn off(a: &Avoid) -> String {
    let held = if a.held {
        "the VM's supervisor (issue 7, `obstacle_near`) holds the robot"
    } else {
        "the VM's supervisor does not hold the robot"
    };
    format!(
        "the avoider ignores it; {held} with its front at x = {} m, {} m before the box, {}",
        f(a.front, 3),
        f(BOX.0 - BOX.2 - a.front, 2),
        contacts(a.contacts)
    )
}

pub fn section(t: &Test4) -> String {
    let row =
        |mode: Mode, dissertation: &str, measured: &dyn Fn(&Avoid) -> String, asserted: &str| {
            let cell = t.mode(mode).map_or("not run".into(), measured);
            format!(
                "| {} | {dissertation} | {cell} | {asserted} |\n",
                mode.name()
            )
        };
    format!(
        "## Test 4: obstacle avoidance (Figure 50)

World `{WORLD}` (a {} m box centred {} m ahead, {} cm left of the line), MoRo, seed
{SEED}, 0.3 m/s: `obsavoid(mode)`, `goahead(5)`. The dissertation tested
`obsavoid(on)` (Table 9, Figure 50); the rows `stop` and `off` are this project's own
checks of the other modes, with nothing of the dissertation's to compare.

| mode | dissertation | this simulator | asserted |
| --- | --- | --- | --- |
{}{}{}
{}",
        n(2.0 * BOX.2),
        n(BOX.0),
        n(BOX.1 * 100.0),
        row(
            Mode::On,
            "passes the obstacle and returns to the path",
            &on,
            &format!(
                "went round (> {} m), no contact, end within {} m of (5, 0)",
                n(ASIDE),
                n(END_WITHIN)
            )
        ),
        row(
            Mode::Stop,
            "not tested: the project's own row (Table 9 runs `obsavoid(on)` only)",
            &stop,
            "stands, no contact"
        ),
        row(
            Mode::Off,
            "not tested: the project's own row",
            &off,
            "held, no contact"
        ),
        picture(
            4,
            "Test 4: the box and the paths of obsavoid(on), (stop) and (off)"
        ),
    )
}
