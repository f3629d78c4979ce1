//! Reverse turns end within `WITHIN_DEG` of the planned heading (issue 15 item
//! 4), on both simulated robots, from rest and linked after a reversing
//! straight, at curvatures within the robot's and beyond it (Figure 20 reverses
//! at c = 1, four times Workpartner's 0.25 1/m: such a turn is driven at the
//! robot's own curvature, on a longer arc, through the same angle).
//!
//! The planned heading is the start's turned by the angle: a turn linked after
//! `goahead(-2)` is planned on from the straight's end, on its line, not from
//! wherever the robot's heading swings while it tracks that line. Measured from
//! the robot's heading at the link instead, Workpartner seemed up to 3.35
//! degrees out (basic, seed 2), its articulated steering 2.7 degrees off the
//! line at that moment; from the line it ends within 1.3 degrees.
//!
//! Over seeds 1-20, on the `basic` errors and on the `calibrated` ones
//! `ilmrc run` has by default. Followed by position alone, the calibrated
//! Workpartner ended its arcs up to 5.3 degrees either way of the heading
//! (`turn(d=-135,c=0.6)` from rest 4.16 short on seed 1), its own estimate
//! saying so: its controller corrects every few centimetres of a navigation
//! fix or of a curvature the steering's play falls short of over a 2 m
//! look-ahead, and reaches the arc's end point at whatever angle that
//! leaves. A reversing turn now ends on its heading (`ilmr_motion::controller::
//! HeadingEnd`); what is left is the robot stopping late by its actuators'
//! dead time, about a degree past.

use ilmr_experiments::harness::{self, moro_with, shipped, workpartner_with};
use ilmr_sim::SimProfile;

/// Degrees: the heading the turn plans, against where the robot ends.
const WITHIN_DEG: f64 = 3.0;

/// Issue 15 item 4: seeds 1-20.
const SEEDS: std::ops::RangeInclusive<u64> = 1..=20;

/// The true heading the robot ends with, less the one it started the task
/// with, radians: the straight before the turn keeps the start's heading.
fn turned(robot: &str, profile: SimProfile, seed: u64, lead_in: &str, d: f64, c: f64) -> f64 {
    let w = shipped("empty").expect("the empty world");
    let r = match robot {
        "moro" => moro_with(w, seed, profile),
        _ => workpartner_with(w, seed, profile),
    }
    .expect("the robot starts");
    let text = format!("speed(-0.3)\n{lead_in}t=turn(d={d},c={c})\nwait(t)\n");
    let module = harness::compile("reverse.ilmr", &text, r.model()).expect("compiles");
    let mut vm = harness::vm(module, r).expect("the VM starts");
    let start = vm.hal().sim().true_pose().h;
    let out = harness::run(&mut vm, 120.0);
    assert!(out.finished, "{robot} seed {seed}: {text} did not finish");
    let end = vm.hal().sim().true_pose().h;
    ilmr_geometry::angle_diff(end, start)
}

#[test]
fn reverse_turns_end_within_three_degrees_of_the_planned_heading() {
    let mut worst: f64 = 0.0;
    for profile in [SimProfile::Basic, SimProfile::Calibrated] {
        for robot in ["moro", "workpartner"] {
            for seed in SEEDS {
                for lead_in in ["", "goahead(-2)\n"] {
                    for (d, c) in [(90.0, 0.25), (-90.0, 1.0), (90.0, 1.0), (-135.0, 0.6)] {
                        let got = turned(robot, profile, seed, lead_in, d, c).to_degrees();
                        // Reversing, the heading changes by -d.
                        let off = got + d;
                        println!(
                            "{robot} {profile:?} seed {seed} {lead_in:?} d={d} c={c}: turned {got:.2} deg, {off:+.2} off"
                        );
                        assert!(
                            off.abs() < WITHIN_DEG,
                            "{robot} {profile:?} seed {seed}, {lead_in:?} turn(d={d},c={c}) reversing turned {got:.2} deg"
                        );
                        worst = worst.max(off.abs());
                    }
                }
            }
        }
    }
    println!("worst {worst:.2} deg");
}
