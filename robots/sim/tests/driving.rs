mod common;

use common::{DT, circle_fit, open_floor, run, sim};
use ilmr_sim::rng::Rng;
use ilmr_sim::{Contact, EventKind, MovementMode, RobotConfig, geometry::SolidRef};

/// Drives at full lock until the curvature has settled, then records the
/// reference point over `turns` whole turns and fits a circle.
fn full_lock_diameter(cfg: RobotConfig, v: f64) -> f64 {
    let max_c = cfg.limits.max_curvature;
    let mut s = sim(cfg, open_floor(), 3);
    if let Err(e) = s.set_setpoints(v, 100.0) {
        panic!("{e}");
    }
    run(&mut s, 500);
    assert!(
        (s.true_curvature() - max_c).abs() < 1e-12,
        "curvature saturates at the limit"
    );
    let period_steps = (std::f64::consts::TAU / max_c / v / DT).round() as usize;
    let mut pts = Vec::new();
    for _ in 0..period_steps {
        run(&mut s, 1);
        let p = s.true_pose();
        pts.push((p.x, p.y));
    }
    2.0 * circle_fit(&pts).2
}

#[test]
fn moro_full_lock_circle_is_1_5_m_across() {
    let d = full_lock_diameter(RobotConfig::moro(), 0.3);
    assert!((d - 1.5).abs() < 0.02, "diameter {d}");
}

#[test]
fn workpartner_minimum_turning_circle_is_8_m_across() {
    let d = full_lock_diameter(RobotConfig::workpartner(), 0.4);
    assert!((d - 8.0).abs() < 0.1, "diameter {d}");
}

#[test]
fn acceleration_and_curvature_rate_limits_hold_step_to_step() {
    for cfg in [RobotConfig::moro(), RobotConfig::workpartner()] {
        let l = cfg.limits.clone();
        let mut s = sim(cfg, open_floor(), 11);
        let mut pick = Rng::new(99);
        let (mut v, mut c) = (0.0, 0.0);
        let mut saw_reversal = false;
        for k in 0..4000 {
            if k % 150 == 0 {
                let vs = (pick.uniform() * 2.0 - 1.0) * 1.5 * l.max_speed;
                let cs = (pick.uniform() * 2.0 - 1.0) * 1.5 * l.max_curvature;
                if let Err(e) = s.set_setpoints(vs, cs) {
                    panic!("{e}");
                }
            }
            run(&mut s, 1);
            let (nv, nc) = (s.true_speed(), s.true_curvature());
            let dv = nv - v;
            let speeding_up = nv.abs() > v.abs() && nv * v >= 0.0;
            let limit = if speeding_up {
                l.max_accel
            } else {
                l.max_decel
            };
            assert!(dv.abs() <= limit * DT + 1e-12, "step {k}: dv {dv}");
            assert!(
                (nc - c).abs() <= l.curinc * DT + 1e-12,
                "step {k}: dc {}",
                nc - c
            );
            assert!(nv.abs() <= l.max_speed + 1e-12 && nc.abs() <= l.max_curvature + 1e-12);
            assert!(v * nv >= 0.0, "speed jumped across zero");
            saw_reversal |= v != 0.0 && nv == 0.0;
            let seen = s.snapshot();
            assert_eq!((seen.speed, seen.curvature), (nv, nc));
            (v, c) = (nv, nc);
        }
        assert!(saw_reversal);
    }
}

#[test]
fn workpartner_modes_limit_speed_and_parking_holds_still() {
    let mut s = sim(RobotConfig::workpartner(), open_floor(), 5);
    assert!(s.set_speed(0.6).is_ok());
    run(&mut s, 400);
    assert!((s.true_speed() - 0.6).abs() < 1e-9);
    assert!(s.set_movement_mode(MovementMode::Rolking).is_ok());
    run(&mut s, 400);
    assert!(
        (s.true_speed() - 0.3).abs() < 1e-9,
        "rolking top speed is half"
    );
    assert!(s.set_movement_mode(MovementMode::Parking).is_ok());
    run(&mut s, 200);
    assert_eq!(s.true_speed(), 0.0);
    let parked = s.true_pose();
    run(&mut s, 200);
    assert_eq!(s.true_pose(), parked);
    assert_eq!(s.snapshot().movement_mode, MovementMode::Parking);
    // MoRo has no legs.
    let mut m = sim(RobotConfig::moro(), open_floor(), 5);
    assert!(m.set_movement_mode(MovementMode::Rolking).is_err());
    assert!(m.set_body_pose(ilmr_sim::BodyPose::default()).is_err());
}

#[test]
fn body_pose_moves_toward_its_setpoint_at_a_limited_rate() {
    let mut s = sim(RobotConfig::workpartner(), open_floor(), 5);
    let target = ilmr_sim::BodyPose {
        roll: 10f64.to_radians(),
        pitch: 20f64.to_radians(),
        clearance: 0.8,
    };
    assert!(s.set_body_pose(target).is_ok());
    run(&mut s, 100);
    let p = s.snapshot().body_pose.unwrap_or_default();
    assert!((p.roll.to_degrees() - 10.0).abs() < 1e-9);
    assert!(
        (p.pitch.to_degrees() - 10.0).abs() < 1e-9,
        "10 deg/s for 1 s"
    );
    assert!((p.clearance - 0.6).abs() < 1e-9);
    run(&mut s, 300);
    assert_eq!(s.snapshot().body_pose, Some(target));
    let bad = ilmr_sim::BodyPose {
        roll: 40f64.to_radians(),
        ..target
    };
    assert!(s.set_body_pose(bad).is_err());
}

#[test]
fn driving_into_a_wall_stops_with_a_contact_and_backing_off_frees_it() {
    let w = common::world(
        r#"
name = "wall ahead"
bounds = { min = [-5.0, -5.0], max = [10.0, 5.0] }
start = { x = 0.0, y = 0.0 }

[[wall]]
from = [4.0, -3.0]
to = [4.0, 3.0]
thickness = 0.2
"#,
    );
    let mut s = sim(RobotConfig::moro(), w, 1);
    assert!(s.set_speed(0.5).is_ok());
    run(&mut s, 1500);
    assert!(s.in_contact());
    assert!(s.snapshot().blocked);
    assert_eq!(s.true_speed(), 0.0);
    // Front edge 0.95 m ahead of the reference point, wall face at 3.9 m.
    let x = s.true_pose().x;
    assert!(x < 3.9 - 0.95 && x > 3.9 - 0.95 - 0.01, "stopped at {x}");
    let events = s.drain_events();
    let contacts: Vec<_> = events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::ContactBegan(_)))
        .collect();
    assert_eq!(
        contacts.len(),
        1,
        "one contact while pressed against the wall"
    );
    assert_eq!(
        contacts[0].kind,
        EventKind::ContactBegan(Contact::Solid(SolidRef::Wall(0)))
    );
    assert!(s.set_speed(-0.3).is_ok());
    run(&mut s, 200);
    assert!(!s.in_contact());
    assert!(s.true_pose().x < x - 0.1);
    assert!(
        s.drain_events()
            .iter()
            .any(|e| e.kind == EventKind::ContactEnded)
    );
    assert_eq!(s.contact_count(), 1);
}

#[test]
fn leaving_the_bounds_is_a_contact_and_a_start_in_a_wall_is_refused() {
    let w = common::world(
        r#"
name = "small"
bounds = { min = [-2.0, -2.0], max = [2.0, 2.0] }
start = { x = 0.0, y = 0.0 }
"#,
    );
    let mut s = sim(RobotConfig::moro(), w, 1);
    assert!(s.set_speed(0.5).is_ok());
    run(&mut s, 600);
    assert!(
        s.drain_events()
            .iter()
            .any(|e| e.kind == EventKind::ContactBegan(Contact::OutOfBounds))
    );

    let inside = common::world(
        r#"
name = "stuck"
bounds = { min = [-5.0, -5.0], max = [5.0, 5.0] }
start = { x = 0.0, y = 0.0 }

[[obstacle]]
shape = "circle"
center = [0.5, 0.0]
radius = 0.2
"#,
    );
    let r = ilmr_sim::Simulator::new(RobotConfig::moro(), inside, 1);
    assert!(matches!(
        r,
        Err(ilmr_sim::SimError::StartInCollision(Contact::Solid(
            SolidRef::Obstacle(0)
        )))
    ));
}

#[test]
fn bad_inputs_are_errors_not_panics() {
    let mut s = sim(RobotConfig::moro(), open_floor(), 1);
    assert!(s.step(0.0).is_err());
    assert!(s.step(f64::NAN).is_err());
    assert!(s.set_speed(f64::INFINITY).is_err());
    assert!(s.set_curvature(f64::NAN).is_err());
    assert!(s.set_pan_tilt(0.0, 0.0).is_err(), "MoRo has no head");
    assert!(s.take_box().is_err(), "MoRo has no manipulator");
    let mut cfg = RobotConfig::moro();
    cfg.limits.curinc = -1.0;
    let r = ilmr_sim::Simulator::new(cfg, open_floor(), 1);
    assert!(matches!(r, Err(ilmr_sim::SimError::Config(m)) if m.contains("limits.curinc")));
}
