//! Test 5 of section 5.6.4 (Figure 52): consecutive movement commands are
//! linked when about 0.5 m remain, so the robot does not stop between them;
//! `use(goalpos)` plans from the previous goal.

mod common;

use common::{DT, MORO, Sim};
use ilmr_motion::controller::{has_arrived, link_distance, stop_in};
use ilmr_motion::path::{TurnSpec, straight, turn};
use ilmr_motion::{Direction, Path, Pose};

type Command = Box<dyn Fn(Pose) -> Path>;

fn goahead(d: f64) -> Command {
    Box::new(move |from| straight(from, d, 0.05).expect("valid straight"))
}

fn turn_cmd(deg: f64, c: f64, direction: Direction) -> Command {
    Box::new(move |from| {
        turn(from, &TurnSpec::degrees(deg, c), direction, 0.05).expect("valid turn")
    })
}

struct Outcome {
    speeds: Vec<f64>,
    trace: Vec<Pose>,
    links: usize,
    final_pose: Pose,
}

/// Runs the commands one after another from `start`, each planned from the
/// previous goal pose (the ideal route). With `link`, a queued command is
/// joined when the remaining length falls to the link distance.
fn run(sim: &mut Sim, commands: &[Command], start: Pose, target: f64, link: bool) -> Outcome {
    let mut goal = start;
    let mut queue = commands.iter();
    let first = queue.next().expect("one command");
    let mut path = first(goal);
    goal = path.end_pose();
    let mut next: Option<Path> = queue.next().map(|c| c(goal));
    let mut k = 0;
    let mut out = Outcome {
        speeds: vec![],
        trace: vec![],
        links: 0,
        final_pose: start,
    };
    for _ in 0..20_000 {
        let here = sim.pose.position();
        if let Some(n) = next.as_ref() {
            let remaining = path.remaining_from(k, &here);
            let ends_here = has_arrived(&path, k, &sim.pose, 0.0, 0.005);
            if (link && remaining <= link_distance(sim.speed, &sim.robot.limits, DT)) || ends_here {
                path = if link {
                    out.links += 1;
                    path.link(k, n).expect("next starts at the previous goal")
                } else {
                    n.clone()
                };
                k = 0;
                goal = path.end_pose();
                next = queue.next().map(|c| c(goal));
            }
        } else if has_arrived(&path, k, &sim.pose, 0.0, 0.005) {
            break;
        }
        let stop = stop_in(&path, k, &sim.pose, 0.0, link && next.is_some());
        let (nk, _) = sim.tick(&path, k, target, stop);
        k = nk;
        out.speeds.push(sim.speed);
        out.trace.push(sim.pose);
    }
    out.final_pose = sim.pose;
    out
}

/// The ideal route of a command list, for measuring position errors.
fn route(commands: &[Command], start: Pose) -> Path {
    let mut it = commands.iter();
    let mut path = (it.next().expect("one command"))(start);
    for c in it {
        let next = c(path.end_pose());
        path = path.concat(&next, 1e-6).expect("commands meet");
    }
    path
}

fn figure_52_forward() -> Vec<Command> {
    vec![
        goahead(1.2),
        turn_cmd(90.0, 0.5, Direction::Forward),
        goahead(0.7),
    ]
}

#[test]
fn linked_commands_do_not_stop_between_them() {
    let start = Pose::new(0.0, 0.0, 0.0);
    let mut sim = Sim::new(MORO, start);
    let out = run(&mut sim, &figure_52_forward(), start, 0.4, true);
    assert_eq!(out.links, 2);
    // From reaching cruise speed until the final braking, the speed never
    // dips: the joints are driven through at 0.4 m/s.
    let cruise = out
        .speeds
        .iter()
        .position(|v| *v >= 0.4 - 1e-9)
        .expect("reaches speed");
    let braking = out
        .speeds
        .iter()
        .rposition(|v| *v >= 0.4 - 1e-9)
        .expect("cruises");
    let dip = out.speeds[cruise..=braking]
        .iter()
        .cloned()
        .fold(f64::MAX, f64::min);
    println!("linked: lowest speed between the first and last cruise sample {dip:.3} m/s");
    assert!(dip >= 0.4 - 1e-9, "speed dipped to {dip}");
    let ideal = route(&figure_52_forward(), start);
    let worst = out
        .trace
        .iter()
        .map(|p| ideal.distance_to(&p.position()))
        .fold(0.0, f64::max);
    println!("linked Figure 52 forward part: max position error {worst:.4} m");
    assert!(worst <= 0.07, "max position error {worst}");
    assert!((out.final_pose.position() - ideal.end_pose().position()).norm() < 0.05);
}

#[test]
fn without_linking_the_robot_stops_at_each_joint() {
    let start = Pose::new(0.0, 0.0, 0.0);
    let mut sim = Sim::new(MORO, start);
    let out = run(&mut sim, &figure_52_forward(), start, 0.4, false);
    let cruise = out
        .speeds
        .iter()
        .position(|v| *v >= 0.4 - 1e-9)
        .expect("reaches speed");
    let braking = out
        .speeds
        .iter()
        .rposition(|v| *v >= 0.4 - 1e-9)
        .expect("cruises");
    let dip = out.speeds[cruise..=braking]
        .iter()
        .cloned()
        .fold(f64::MAX, f64::min);
    assert!(dip < 0.1, "expected a stop between commands, lowest {dip}");
}

#[test]
fn use_goalpos_drives_back_to_the_start() {
    // wait(m) prevents linking the reversing half onto the forward half;
    // use(goalpos) plans it from the previous goal, not where the robot
    // actually stopped.
    let start = Pose::new(0.0, 0.0, 0.0);
    let mut sim = Sim::new(MORO, start);
    let forward = run(&mut sim, &figure_52_forward(), start, 0.4, true);
    let goalpos = route(&figure_52_forward(), start).end_pose();
    let back: Vec<Command> = vec![
        goahead(-0.7),
        turn_cmd(90.0, 0.5, Direction::Backward),
        goahead(-1.2),
    ];
    let out = run(&mut sim, &back, goalpos, 0.4, true);
    assert_eq!(out.links, 2);
    assert!(out.speeds.iter().all(|v| *v <= 0.0), "reverses all the way");
    let ideal = route(&back, goalpos);
    assert!((ideal.end_pose().position() - start.position()).norm() < 1e-9);
    let worst = out
        .trace
        .iter()
        .map(|p| ideal.distance_to(&p.position()))
        .fold(0.0, f64::max);
    println!(
        "Figure 52 back to the start: max position error {worst:.4} m, final error {:.4} m",
        (out.final_pose.position() - start.position()).norm()
    );
    assert!(worst <= 0.07, "max position error {worst}");
    assert!(forward.links == 2);
}
