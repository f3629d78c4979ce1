//! Test 4 of section 5.6.3: `obsavoid(on)` then a `goahead` with an
//! obstacle on the path, in a kinematic closed loop; and the transitions of
//! the Figure 35 state machine in each mode.

mod common;

use common::{MORO, Sim};
use ilmr_motion::controller::{has_arrived, stop_in};
use ilmr_motion::obstacle::{
    AreaParams, AvoidMode, AvoidParams, AvoidState, Avoider, Observation, SideParams,
};
use ilmr_motion::path::straight;
use ilmr_motion::{Direction, Path, Pose};
use nalgebra::Point2;

const DT: f64 = common::DT;

fn params() -> AvoidParams {
    AvoidParams {
        area: AreaParams {
            max_curvature: MORO.max_curvature,
            robot_width: 0.6,
            front_offset: 0.9,
        },
        side: SideParams {
            robot_width: 0.6,
            robot_length: 1.2,
            front_offset: 0.9,
            margin: 0.1,
            max_offset: 2.0,
        },
        security_wait: 1.0,
        spacing: 0.05,
    }
}

/// A 0.4 m box of scan points centred on (x, y).
fn box_at(x: f64, y: f64) -> Vec<Point2<f64>> {
    let mut pts = vec![];
    for i in 0..=8 {
        let t = -0.2 + 0.05 * i as f64;
        pts.extend([
            Point2::new(x + t, y - 0.2),
            Point2::new(x + t, y + 0.2),
            Point2::new(x - 0.2, y + t),
            Point2::new(x + 0.2, y + t),
        ]);
    }
    pts
}

struct Drive {
    states: Vec<AvoidState>,
    trace: Vec<Pose>,
    arrived: bool,
}

/// goahead(7) at 0.4 m/s with the avoider in `mode`: the robot follows the
/// detour while OBS_CONTROL is set, the reference otherwise, and stands
/// while blocked.
fn drive(mode: AvoidMode, map: &[Point2<f64>]) -> Drive {
    let start = Pose::new(0.0, 0.0, 0.0);
    // Long enough after the obstacle for the controller to bring the robot
    // back onto its route before the command ends.
    let reference = straight(start, 7.0, 0.05).expect("valid");
    let mut sim = Sim::new(MORO, start);
    let mut avoider = Avoider::new(mode, params());
    let (mut k, mut k_detour) = (0usize, 0usize);
    let mut detour: Option<Path> = None;
    let mut out = Drive {
        states: vec![],
        trace: vec![],
        arrived: false,
    };
    for _ in 0..6000 {
        k = reference.closest_index(&sim.pose.position(), k, 3.0);
        if has_arrived(&reference, k, &sim.pose, 0.0, 0.01) {
            out.arrived = true;
            break;
        }
        let decision = avoider.step(&Observation {
            pose: sim.pose,
            direction: Direction::Forward,
            curvature: sim.commanded,
            speed: 0.4,
            reference: &reference,
            k,
            points: map,
            dt: DT,
        });
        let state = decision.state;
        if let Some(d) = decision.detour
            && detour.as_ref() != Some(d)
        {
            detour = Some(d.clone());
            k_detour = 0;
        }
        if out.states.last() != Some(&state) {
            out.states.push(state);
        }
        let (target, path, kk) = match (decision.halt, decision.obs_control, detour.as_ref()) {
            (true, _, _) => (0.0, &reference, k),
            (false, true, Some(d)) => (0.4, d, k_detour),
            _ => (0.4, &reference, k),
        };
        let stop = if decision.halt {
            Some(0.0)
        } else {
            stop_in(&reference, k, &sim.pose, 0.0, false)
        };
        let (nk, _) = sim.tick(path, kk, target, stop);
        if decision.obs_control {
            k_detour = nk;
        } else {
            detour = None;
        }
        out.trace.push(sim.pose);
    }
    out
}

fn clearance(trace: &[Pose], obstacle: &[Point2<f64>]) -> f64 {
    trace
        .iter()
        .flat_map(|p| obstacle.iter().map(move |o| (o - p.position()).norm()))
        .fold(f64::MAX, f64::min)
}

#[test]
fn obsavoid_on_passes_the_obstacle_and_returns_to_the_path() {
    let obstacle = box_at(3.0, 0.05);
    let run = drive(AvoidMode::On, &obstacle);
    assert!(run.arrived, "goahead(7) finished");
    assert_eq!(
        run.states,
        vec![
            AvoidState::Normal,
            AvoidState::Avoiding,
            AvoidState::Returning,
            AvoidState::Normal
        ]
    );
    let c = clearance(&run.trace, &obstacle);
    let aside = run.trace.iter().map(|p| p.y.abs()).fold(0.0, f64::max);
    // The detour goes right (the box sits slightly left); the return
    // overshoots to the left, as the controller does on lateral steps.
    let overshoot = run.trace.iter().map(|p| p.y).fold(0.0, f64::max);
    let end = run.trace.last().expect("moved");
    println!(
        "obstacle test: clearance {c:.3} m, widest {aside:.3} m off the path, \
         return overshoot {overshoot:.3} m, end y {:.4} m",
        end.y
    );
    assert!(
        c > 0.3,
        "the robot's centre line kept {c} m from the obstacle"
    );
    assert!(overshoot < 0.35, "return overshoot {overshoot}");
    assert!(
        end.y.abs() < 0.1,
        "back near the path at the end: {}",
        end.y
    );
}

#[test]
fn obsavoid_stop_halts_in_front_of_the_obstacle() {
    let obstacle = box_at(3.0, 0.0);
    let run = drive(AvoidMode::Stop, &obstacle);
    assert!(!run.arrived);
    assert_eq!(run.states, vec![AvoidState::Normal, AvoidState::Blocked]);
    let front = run.trace.last().expect("moved").x + 0.9;
    assert!(front < 2.8, "front at {front}");
}

#[test]
fn obsavoid_off_ignores_obstacles() {
    let obstacle = box_at(3.0, 0.0);
    let run = drive(AvoidMode::Off, &obstacle);
    assert!(run.arrived);
    assert_eq!(run.states, vec![AvoidState::Normal]);
}

#[test]
fn no_way_round_blocks_and_a_removed_obstacle_releases_after_the_security_wait() {
    let reference = straight(Pose::new(0.0, 0.0, 0.0), 5.0, 0.05).expect("valid");
    let mut walls: Vec<Point2<f64>> = box_at(2.0, 0.0);
    for i in 0..50 {
        walls.push(Point2::new(i as f64 * 0.1, 0.7));
        walls.push(Point2::new(i as f64 * 0.1, -0.7));
    }
    let mut av = Avoider::new(AvoidMode::On, params());
    let obs = |points: &'static [Point2<f64>]| Observation {
        pose: Pose::new(0.0, 0.0, 0.0),
        direction: Direction::Forward,
        curvature: 0.0,
        speed: 0.4,
        reference: &reference,
        k: 0,
        points,
        dt: 0.1,
    };
    let walls: &'static [Point2<f64>] = Box::leak(walls.into_boxed_slice());
    let d = av.step(&obs(walls));
    assert_eq!(d.state, AvoidState::Blocked);
    assert!(d.halt && !d.obs_control);
    // The obstacle is taken away; the robot waits bs_security seconds.
    for _ in 0..9 {
        assert_eq!(av.step(&obs(&[])).state, AvoidState::Blocked);
    }
    assert_eq!(av.step(&obs(&[])).state, AvoidState::Normal);
}

#[test]
fn switching_obsavoid_off_drops_the_detour() {
    let reference = straight(Pose::new(0.0, 0.0, 0.0), 5.0, 0.05).expect("valid");
    let obstacle = box_at(2.6, 0.0);
    let mut av = Avoider::new(AvoidMode::On, params());
    let o = Observation {
        pose: Pose::new(0.0, 0.0, 0.0),
        direction: Direction::Forward,
        curvature: 0.0,
        speed: 0.4,
        reference: &reference,
        k: 0,
        points: &obstacle,
        dt: 0.01,
    };
    let d = av.step(&o);
    assert_eq!(d.state, AvoidState::Avoiding);
    assert!(d.obs_control && d.detour.is_some());
    av.set_mode(AvoidMode::Off);
    assert_eq!(av.state(), AvoidState::Normal);
    assert_eq!(av.step(&o).state, AvoidState::Normal);
}
