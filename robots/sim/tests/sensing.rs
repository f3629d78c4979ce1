mod common;

use common::{open_floor, run, sim};
use ilmr_sim::{EventKind, MovementMode, Pose, RobotConfig, Simulator};

fn error(s: &Simulator) -> f64 {
    let (t, e) = (s.true_pose(), s.snapshot().pose);
    (t.x - e.x).hypot(t.y - e.y)
}

/// MoRo straight ahead at 0.5 m/s for 20 s with the given mean slip.
fn moro_drift(slip_mean: f64) -> f64 {
    let mut cfg = RobotConfig::moro();
    cfg.slip.mean = slip_mean;
    let mut s = sim(cfg, open_floor(), 21);
    assert!(s.set_speed(0.5).is_ok());
    run(&mut s, 2000);
    error(&s)
}

#[test]
fn odometry_drift_grows_with_slip() {
    let none = moro_drift(0.0);
    let some = moro_drift(0.02);
    let more = moro_drift(0.05);
    assert!(none < 0.02, "without slip the estimate stays close: {none}");
    assert!(
        some > 0.1 && more > 2.0 * some,
        "drift {none} < {some} < {more}"
    );
    // About 5 % of the 9.9 m driven.
    assert!((more - 0.05 * 9.9).abs() < 0.1, "{more}");
}

#[test]
fn odometry_bias_makes_the_estimate_drift() {
    let mut s = sim(RobotConfig::moro(), open_floor(), 21);
    s.faults.odometry_scale_error = 0.03;
    assert!(s.set_speed(0.5).is_ok());
    run(&mut s, 2000);
    assert!(error(&s) > 0.2, "{}", error(&s));
    // Pulses over-count by 3 %.
    let odo = s.snapshot().odometry;
    assert_eq!(odo.pulses.len(), 3);
    assert!((odo.distance / s.true_pose().x - 1.03).abs() < 0.005);
}

/// Workpartner rolking (8 % slip) on a circle for 30 s.
fn workpartner_rolking(nav: bool, frozen: bool) -> Simulator {
    let mut cfg = RobotConfig::workpartner();
    if !nav {
        cfg.nav = None;
    }
    let mut s = sim(cfg, open_floor(), 8);
    assert!(s.set_movement_mode(MovementMode::Rolking).is_ok());
    assert!(s.set_setpoints(0.3, 0.1).is_ok());
    s.faults.nav_fix_frozen = frozen;
    run(&mut s, 3000);
    s
}

#[test]
fn navigation_fix_pulls_the_dead_reckoning_back() {
    let blind = workpartner_rolking(false, false);
    assert!(
        error(&blind) > 0.4,
        "odometry alone drifts: {}",
        error(&blind)
    );

    let mut s = workpartner_rolking(true, false);
    // t = 30.0 s: a fix just arrived and the estimate sits on it.
    let fix = s
        .snapshot()
        .nav_fix
        .unwrap_or_else(|| panic!("fixes at 2 Hz"));
    assert_eq!((fix.seq, fix.time), (60, 30.0));
    assert_eq!(s.snapshot().pose, fix.pose);
    assert!(error(&s) < 0.08, "{}", error(&s));
    // Between fixes the 10 Hz dead reckoning moves the estimate on.
    let mut seen = vec![s.snapshot().pose];
    for _ in 0..4 {
        run(&mut s, 10);
        seen.push(s.snapshot().pose);
    }
    assert!(
        seen.windows(2).all(|w| w[0] != w[1]),
        "dead reckoning at 10 Hz"
    );
    assert!(error(&s) < 0.1);

    let frozen = workpartner_rolking(true, true);
    assert!(
        error(&frozen) > 5.0,
        "a frozen fix holds the estimate back: {}",
        error(&frozen)
    );
}

#[test]
fn locate_sets_the_reported_frame() {
    let mut s = sim(RobotConfig::workpartner(), open_floor(), 2);
    assert!(
        s.locate(Pose::new(10.0, 5.0, std::f64::consts::FRAC_PI_2))
            .is_ok()
    );
    assert!(s.set_speed(0.4).is_ok());
    run(&mut s, 1000);
    // The robot drove along world +x, which is user +y after the locate.
    let e = s.snapshot().pose;
    let t = s.true_pose();
    assert!(
        (e.x - 10.0).abs() < 0.1 && (e.y - 5.0 - t.x).abs() < 0.1,
        "{e:?} vs {t:?}"
    );
    assert!((e.h - std::f64::consts::FRAC_PI_2).abs() < 0.05);
    let fix = s.snapshot().nav_fix.map(|f| f.pose).unwrap_or_default();
    assert!(
        (fix.y - 5.0 - t.x).abs() < 0.1,
        "fixes are reported in the user frame too"
    );
}

#[test]
fn gyro_heading_follows_the_turn_with_small_drift() {
    let mut s = sim(RobotConfig::moro(), open_floor(), 4);
    assert!(s.set_setpoints(0.3, 0.5).is_ok());
    run(&mut s, 1000);
    let g = s
        .snapshot()
        .gyro
        .unwrap_or_else(|| panic!("MoRo has a gyro"));
    let err = ilmr_sim::geometry::wrap_angle(g.heading - s.true_pose().h);
    assert!(err.abs() < 0.01, "gyro error {err}");
    assert!((g.rate - 0.15).abs() < 0.03, "turn rate {}", g.rate);
    // Standing still for 10 minutes: the drift stays small but is not zero.
    let mut still = sim(RobotConfig::moro(), open_floor(), 4);
    run(&mut still, 60_000);
    let h = still.snapshot().gyro.map_or(0.0, |g| g.heading);
    assert!(h != 0.0 && h.abs() < 0.05, "{h}");
}

const PLATES: &str = r#"
name = "plates"
bounds = { min = [-5.0, -5.0], max = [20.0, 5.0] }
start = { x = 0.0, y = 0.0 }

[[plate]]
position = [2.0, 0.12]

[[plate]]
position = [4.0, -0.2]

[[plate]]
position = [6.0, 0.6]
"#;

#[test]
fn plates_fire_under_the_sensor_with_their_lateral_offset() {
    let mut s = sim(RobotConfig::moro(), common::world(PLATES), 9);
    assert!(s.set_speed(0.4).is_ok());
    run(&mut s, 2500);
    let plates: Vec<_> = s
        .drain_events()
        .into_iter()
        .filter_map(|e| match e.kind {
            EventKind::Plate(p) => Some(p),
            _ => None,
        })
        .collect();
    assert_eq!(
        plates.iter().map(|p| p.plate).collect::<Vec<_>>(),
        vec![0, 1],
        "the far-off plate is missed"
    );
    assert!(
        (plates[0].lateral - 0.12).abs() < 0.011,
        "{}",
        plates[0].lateral
    );
    assert!(
        (plates[1].lateral + 0.2).abs() < 0.011,
        "{}",
        plates[1].lateral
    );
    // Rounded to the centimetre.
    assert!(((plates[0].lateral * 100.0) - (plates[0].lateral * 100.0).round()).abs() < 1e-9);
    // The array is 0.45 m ahead: plate 0 fired when the reference point passed 1.55 m.
    let speed_time = 1.0 + (1.55 - 0.25) / 0.4;
    assert!(
        (plates[0].time - speed_time).abs() < 0.05,
        "{}",
        plates[0].time
    );
    assert_eq!(s.snapshot().plate.map(|p| p.seq), Some(1));
}

#[test]
fn battery_drains_with_time_and_more_with_motion_and_charges_at_the_charger() {
    let mut idle = sim(RobotConfig::moro(), open_floor(), 1);
    let mut moving = sim(RobotConfig::moro(), open_floor(), 1);
    assert!(moving.set_setpoints(0.8, 0.3).is_ok());
    let v0 = idle.snapshot().battery.voltage;
    run(&mut idle, 6000);
    run(&mut moving, 6000);
    let (bi, bm) = (idle.snapshot().battery, moving.snapshot().battery);
    assert!(bi.voltage < v0 && bi.charge < 1.0);
    assert!(
        bm.charge < bi.charge,
        "moving drains more: {} vs {}",
        bm.charge,
        bi.charge
    );
    // 40 W for a minute from 960 Wh.
    assert!(((1.0 - bi.charge) - 40.0 / 60.0 / 960.0).abs() < 1e-9);

    let mut dead = sim(RobotConfig::moro(), open_floor(), 1);
    dead.faults.dead_battery = true;
    assert!(dead.set_speed(0.5).is_ok());
    run(&mut dead, 200);
    assert_eq!(dead.true_speed(), 0.0);
    assert_eq!(
        dead.snapshot().battery.voltage,
        RobotConfig::moro().battery.v_empty
    );

    let at_charger = common::world(
        r#"
name = "dock"
bounds = { min = [-5.0, -5.0], max = [5.0, 5.0] }
start = { x = 0.0, y = 0.0 }

[charger]
position = [0.1, 0.0]
"#,
    );
    let mut c = sim(RobotConfig::moro(), at_charger, 1);
    assert!(c.set_battery_charge(0.5).is_ok());
    run(&mut c, 1000);
    let b = c.snapshot().battery;
    assert!(b.charging && b.charge > 0.5);
}

#[test]
fn workpartner_camera_sees_the_user_and_ultrasonics_see_behind() {
    let w = common::world(
        r#"
name = "meet"
bounds = { min = [-10.0, -10.0], max = [20.0, 10.0] }
start = { x = 0.0, y = 0.0 }

[[wall]]
from = [-3.1, -5.0]
to = [-3.1, 5.0]
thickness = 0.2

[[target]]
name = "user"
colour = "yellow"
position = [8.3, 3.0]
radius = 0.3
"#,
    );
    let mut s = sim(RobotConfig::workpartner(), w, 6);
    let frame = s
        .snapshot()
        .camera
        .unwrap_or_else(|| panic!("camera frame at t = 0"));
    // Eye 0.3 m ahead: the user is 8 m ahead and 3 m left, bearing 20.6 deg.
    assert_eq!(frame.detections.len(), 1);
    let d = &frame.detections[0];
    assert_eq!(d.name, "user");
    assert!((d.bearing.to_degrees() - 3f64.atan2(8.0).to_degrees()).abs() < 1e-6);
    let expected_px = 2.0 * (0.3 / 73f64.sqrt()).asin() / 50f64.to_radians() * 640.0;
    assert!((d.size_px - expected_px).abs() < 1e-9, "{}", d.size_px);
    // Point the head at the user: the laser pointer measures the distance.
    assert!(s.set_pan_tilt(3f64.atan2(8.0), 0.0).is_ok());
    run(&mut s, 10);
    let laser = s.snapshot().camera.and_then(|f| f.laser).unwrap_or(0.0);
    assert!((laser - (73f64.sqrt() - 0.3)).abs() < 0.05, "{laser}");
    // Rear edge at -1.1, the wall face at -3.0: 1.9 m behind.
    let us = s
        .snapshot()
        .ultrasonic
        .unwrap_or_else(|| panic!("ultrasonic"));
    for r in us.ranges {
        assert!((r - 1.9).abs() < 0.06, "{r}");
    }
}

#[test]
fn workpartner_takes_and_leaves_a_box() {
    let w = common::world(
        r#"
name = "box"
bounds = { min = [-10.0, -10.0], max = [20.0, 10.0] }
start = { x = 0.0, y = 0.0 }

[[pickup_box]]
id = "crate"
center = [1.6, 0.0]
size = [0.4, 0.4]
colour = "red"
"#,
    );
    let mut s = sim(RobotConfig::workpartner(), w, 6);
    assert_eq!(s.take_box().ok().as_deref(), Some("crate"));
    assert_eq!(s.snapshot().carrying.as_deref(), Some("crate"));
    assert!(s.take_box().is_err());
    assert!(s.set_speed(0.4).is_ok());
    run(&mut s, 500);
    assert!(!s.in_contact(), "a carried box is no obstacle");
    assert!(s.set_speed(0.0).is_ok());
    run(&mut s, 200);
    assert_eq!(s.leave_box().ok().as_deref(), Some("crate"));
    assert!(s.snapshot().carrying.is_none());
    let kinds: Vec<_> = s.drain_events().into_iter().map(|e| e.kind).collect();
    assert_eq!(
        kinds,
        vec![
            EventKind::BoxTaken("crate".into()),
            EventKind::BoxLeft("crate".into())
        ]
    );
}
