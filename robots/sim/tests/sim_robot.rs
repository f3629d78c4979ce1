//! `SimRobot` behind the HAL: lockstep with the VM's clock, the snapshot,
//! asynchronous operations that take time and can fail, refusals.

mod common;

use common::shipped;
use ilmr_hal::{AsyncOp, BodyPose, Hal, HalError, ManipTask, OpStatus, Snapshot};
use ilmr_sim::{SimRobot, TAKE_SECONDS, World};

fn tick_until(robot: &mut SimRobot, from: f64, to: f64) {
    let mut t = from;
    while t < to - 1e-9 {
        t += 0.01;
        robot.update(t).expect("update");
    }
}

fn poll_after(robot: &mut SimRobot, op: &AsyncOp, seconds: f64) -> (OpStatus, OpStatus) {
    let id = robot.start(op).expect("started");
    let t0 = robot.sim().time();
    tick_until(robot, t0, t0 + seconds - 0.05);
    let early = robot.poll(id).expect("known");
    tick_until(robot, t0 + seconds - 0.05, t0 + seconds + 0.05);
    (early, robot.poll(id).expect("known"))
}

#[test]
fn update_steps_the_simulator_in_lockstep() {
    let mut r = SimRobot::moro(shipped("empty"), 1).expect("robot");
    r.set_motion(0.5, 0.0).expect("setpoints");
    for i in 1..=100 {
        r.update(f64::from(i) * 0.01).expect("update");
        assert!((r.sim().time() - f64::from(i) * 0.01).abs() < 1e-9);
    }
    let mut snap = Snapshot::default();
    r.snapshot(&mut snap).expect("snapshot");
    assert!((snap.t - 1.0).abs() < 1e-9);
    assert!(snap.true_pose.is_some_and(|p| p.x > 0.2));
    assert!(snap.scan.as_ref().is_some_and(|s| s.ranges.len() == 361));
    assert!(snap.device("battery").is_some_and(|v| v > 20.0));
    assert!(snap.device("gyro").is_some());
}

#[test]
fn take_fails_without_a_box_in_reach_and_succeeds_in_front_of_one() {
    let mut r = SimRobot::workpartner(shipped("empty"), 1).expect("robot");
    let take = AsyncOp::Manipulate(ManipTask::Take);
    let (early, late) = poll_after(&mut r, &take, TAKE_SECONDS);
    assert_eq!(early, OpStatus::Pending);
    assert!(
        matches!(late, OpStatus::Failed(ref why) if why.contains("no box")),
        "{late:?}"
    );

    let text = r#"
name = "box"
bounds = { min = [-5.0, -5.0], max = [5.0, 5.0] }
start = { x = 0.0, y = 0.0, heading = 0.0 }
[[pickup_box]]
id = "box1"
center = [1.6, 0.0]
size = [0.4, 0.4]
"#;
    let world = World::from_toml(text, "box.toml").expect("world");
    let mut r = SimRobot::workpartner(world, 1).expect("robot");
    let (_, late) = poll_after(&mut r, &take, TAKE_SECONDS);
    assert_eq!(late, OpStatus::Done);
    assert_eq!(r.sim().snapshot().carrying.as_deref(), Some("box1"));
}

#[test]
fn moro_has_no_manipulator_or_legs_and_refusals_are_values() {
    let mut r = SimRobot::moro(shipped("empty"), 1).expect("robot");
    assert!(matches!(
        r.start(&AsyncOp::Manipulate(ManipTask::Take)),
        Err(HalError::Unsupported(_))
    ));
    assert!(matches!(
        r.start(&AsyncOp::MoveMode("rolking".into())),
        Err(HalError::Unsupported(_))
    ));
    assert!(matches!(
        r.bodypose(BodyPose::default()),
        Err(HalError::Unsupported(_))
    ));
    assert!(matches!(
        r.actuator("warp_drive", 1.0),
        Err(HalError::Unsupported(_))
    ));
    assert!(matches!(r.actuator("horn", 5.0), Err(HalError::Refused(_))));
    assert!(r.set_motion(f64::NAN, 0.0).is_err());
    assert!(r.locmode("gps").is_err());
    assert!(r.locmode("odo").is_ok());
    assert!(matches!(
        r.poll(ilmr_hal::OpId(99)),
        Err(HalError::UnknownOp(_))
    ));
    let (early, late) = poll_after(&mut r, &AsyncOp::Init(vec!["navi".into()]), 1.0);
    assert_eq!((early, late), (OpStatus::Pending, OpStatus::Done));
    assert!(r.start(&AsyncOp::Init(vec!["nothing".into()])).is_err());
}

#[test]
fn workpartner_changes_movement_mode_after_a_delay_and_brakes() {
    let mut r = SimRobot::workpartner(shipped("empty"), 1).expect("robot");
    let (early, late) = poll_after(&mut r, &AsyncOp::MoveMode("rolking".into()), 2.0);
    assert_eq!((early, late), (OpStatus::Pending, OpStatus::Done));
    assert_eq!(
        r.sim().snapshot().movement_mode,
        ilmr_sim::MovementMode::Rolking
    );
    r.actuator("brake", 1.0).expect("brake");
    r.set_motion(0.4, 0.0).expect("setpoints");
    let t = r.sim().time();
    tick_until(&mut r, t, t + 1.0);
    assert!(
        r.sim().true_speed().abs() < 1e-9,
        "the brake holds the robot"
    );
}

#[test]
fn the_camera_sees_the_user_where_the_scanner_ranges_it() {
    let text = r#"
name = "user"
bounds = { min = [-5.0, -5.0], max = [15.0, 5.0] }
start = { x = 0.0, y = 0.0, heading = 0.0 }
[[target]]
name = "someone"
colour = "yellow"
position = [5.0, 0.5]
"#;
    let world = World::from_toml(text, "user.toml").expect("world");
    let mut r = SimRobot::workpartner(world, 1).expect("robot");
    r.update(0.01).expect("update");
    let mut snap = Snapshot::default();
    r.snapshot(&mut snap).expect("snapshot");
    let user = snap
        .detections
        .iter()
        .find(|d| d.object == "user")
        .expect("the model's yellow object is seen");
    assert!(
        (user.x - 5.0).abs() < 0.15 && (user.y - 0.5).abs() < 0.15,
        "{user:?}"
    );
    assert_eq!(user.side, ilmr_hal::Side::Left);
}
