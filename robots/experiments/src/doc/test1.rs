//! Test 1: `turn(d=90,c=..)`, Table 10.

use super::fmt::{f, list, n};
use super::picture;
use crate::settings::Settings;
use crate::test1_turn::{Robot, SEED, Sweep, Test1};

fn row(s: &Sweep) -> String {
    let d = s.spec.dissertation;
    let (mean, std) = s.mean_std();
    format!(
        "| {}, {} | {} / {} / {} | {} / {} / {} | max <= {} |\n",
        s.trials.len(),
        s.label(),
        n(d.max),
        n(d.mean),
        n(d.std),
        f(s.worst(), 4),
        f(mean, 4),
        f(std, 4),
        n(s.spec.bar)
    )
}

fn trials(s: &Sweep) -> String {
    let cells: Vec<String> = s
        .trials
        .iter()
        .map(|t| format!("{} m/s: {}", n(t.v), f(t.max_deviation, 4)))
        .collect();
    format!("| {} | {} |\n", s.label(), cells.join(", "))
}

fn of(t: &Test1, robot: Robot) -> impl Iterator<Item = &Sweep> {
    t.sweeps.iter().filter(move |s| s.spec.robot == robot)
}

pub fn section(t: &Test1, settings: &Settings) -> String {
    let speeds: Vec<String> = t
        .sweeps
        .iter()
        .map(|s| format!("- {} at {} m/s", s.label(), list(s.spec.speeds)))
        .collect();
    let moro_worst = of(t, Robot::Moro).map(Sweep::worst).fold(0.0, f64::max);
    let moro_table = of(t, Robot::Moro)
        .map(|s| s.spec.dissertation.max)
        .fold(0.0, f64::max);
    let mut s = format!(
        "## Test 1: `turn(d=90,c=..)` (Table 10, Figure 46)

`speed(v)` then `t=turn(d=90,c=c)` from (0, 0, 0) in `empty`; deviation = largest
distance of the true trace from the reference arc. Seeds {SEED}, {}, ... per trial:

{}

| trials | dissertation max / mean / std (m) | this simulator max / mean / std (m) | asserted |
| --- | --- | --- | --- |
",
        SEED + 1,
        speeds.join("\n")
    );
    for sweep in &t.sweeps {
        s.push_str(&row(sweep));
    }
    s.push_str("\nThe maximum deviation of each trial, metres:\n\n| sweep | speed: max deviation |\n| --- | --- |\n");
    for sweep in &t.sweeps {
        s.push_str(&trials(sweep));
    }
    s.push_str(&format!(
        "
MoRo in simulation follows the arc far better than the real robot ({} m at worst
against the dissertation's {} m): the simulated steering has no dead time and no
play, and MoRo's gyro keeps the estimate within millimetres over a turn.",
        f(moro_worst, 4),
        n(moro_table)
    ));
    for wp in of(t, Robot::Workpartner) {
        s.push_str(&format!(
            "\nWorkpartner's worst trial is {} m off the arc (the dissertation's: {} m). Its arc
is at its maximum curvature (c={}, {} 1/m), and its pose comes from 2 Hz navigation
fixes (2 cm noise) with dead reckoning at 10 Hz (1 % slip) between them. With the
true pose fed to the controller the trace stays within 0.01 m, so the error is the
estimate's: with a 0.6 m look-ahead a fix a few centimetres inside the arc made the
controller straighten for a second, and heading given away on an arc at full lock is
never made up: the circle driven afterwards lies outside the ideal one (0.23 m at
worst before the fix). The controller therefore looks ahead at least half the
robot's turning radius (`ControllerParams::min_lookahead_radii`, 0.5): 2 m on
Workpartner, as in Figure 32; MoRo's half radius is shorter than its 0.6 m, so its
runs are unchanged. What remains is the estimate at both ends of the arc: the path is
planned from the estimated start pose, and the robot stops where its estimate says
the arc ends. The price is a bend entered from a straight: the longer look-ahead sees
it earlier and cuts a little into it.",
            f(wp.worst(), 4),
            n(wp.spec.dissertation.max),
            n(wp.spec.c),
            n(settings.workpartner.max_curvature),
        ));
    }
    s.push_str("\n\n");
    s.push_str(&picture(
        1,
        "Test 1: every trial's true path over its ideal arc, MoRo c=0.6 and c=0.4, Workpartner c=0.25",
    ));
    s
}
