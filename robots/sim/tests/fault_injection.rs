//! Each injected fault does to the simulated sensors and actuators exactly
//! what `ilmr_sim::faults` says, from its start to its end and not outside,
//! and a run with the same seed and faults is bit-identical.

mod common;

use common::{DT, open_floor, run, sim};
use ilmr_hal::{AsyncOp, Hal, HalError, ManipTask, OpStatus};
use ilmr_sim::faults::{flag, random_plan};
use ilmr_sim::geometry::SolidRef;
use ilmr_sim::{RobotConfig, RobotKind, SimRobot, Simulator, World};

fn faulted(faults: &[&str]) -> World {
    let mut w = open_floor();
    for f in faults {
        w.faults
            .push(flag::parse(f).unwrap_or_else(|e| panic!("{f}: {e}")));
    }
    w
}

/// Steps to `t` seconds, calling `each` after every step.
fn until(s: &mut Simulator, t: f64, mut each: impl FnMut(&Simulator)) {
    while s.time() < t - 1e-9 {
        run(s, 1);
        each(s);
    }
}

#[test]
fn scanner_dropout_stops_scans_on_its_window_only() {
    let mut s = sim(RobotConfig::moro(), faulted(&["scanner_dropout@1+1"]), 1);
    let mut arrived = vec![0.0];
    let mut seq = 0;
    until(&mut s, 3.0, |s| {
        let scan = s.snapshot().scan.unwrap_or_else(|| panic!("a scan"));
        if scan.seq != seq {
            seq = scan.seq;
            arrived.push(scan.time);
        }
    });
    assert_eq!(
        arrived,
        vec![0.0, 0.25, 0.5, 0.75, 2.0, 2.25, 2.5, 2.75, 3.0]
    );
}

#[test]
fn odometry_slip_moves_the_ground_less_than_the_wheels_count() {
    let mut clean = sim(RobotConfig::moro(), open_floor(), 2);
    let mut slipping = sim(RobotConfig::moro(), faulted(&["odometry_slip@1+2:0.4"]), 2);
    for s in [&mut clean, &mut slipping] {
        assert!(s.set_speed(0.5).is_ok());
        run(s, 99);
    }
    // The step ending at 1.0 s is the first to slip.
    assert_eq!(clean.true_pose(), slipping.true_pose(), "identical before");
    let (x1, o1) = (
        slipping.true_pose().x,
        slipping.snapshot().odometry.distance,
    );
    run(&mut slipping, 200);
    let ground = slipping.true_pose().x - x1;
    let wheels = slipping.snapshot().odometry.distance - o1;
    let lost = 1.0 - ground / wheels;
    assert!((0.35..0.45).contains(&lost), "lost {lost}");
    let (x3, o3) = (
        slipping.true_pose().x,
        slipping.snapshot().odometry.distance,
    );
    run(&mut slipping, 100);
    let ratio = (slipping.true_pose().x - x3) / (slipping.snapshot().odometry.distance - o3);
    assert!(ratio > 0.9, "grip is back after 3 s: {ratio}");
}

#[test]
fn odometry_bias_scales_the_counts_on_its_window() {
    let mut clean = sim(RobotConfig::moro(), open_floor(), 3);
    let mut biased = sim(RobotConfig::moro(), faulted(&["odometry_bias@1+1:0.1"]), 3);
    let mut steps = Vec::new();
    for s in [&mut clean, &mut biased] {
        assert!(s.set_speed(0.5).is_ok());
        let mut d = Vec::new();
        for _ in 0..3 {
            let before = s.snapshot().odometry.distance;
            run(s, 100);
            d.push(s.snapshot().odometry.distance - before);
        }
        steps.push(d);
    }
    assert_eq!(
        clean.true_pose(),
        biased.true_pose(),
        "the ground is not biased"
    );
    let (c, b) = (&steps[0], &steps[1]);
    assert!((b[0] - c[0]).abs() < 1e-3, "{b:?} vs {c:?}");
    assert!((b[1] / c[1] - 1.1).abs() < 0.01, "{b:?} vs {c:?}");
    assert!((b[2] - c[2]).abs() < 2e-3, "{b:?} vs {c:?}");
}

#[test]
fn odometry_dropout_freezes_the_reading_and_the_estimate() {
    let mut s = sim(RobotConfig::moro(), faulted(&["odometry_dropout@1+1"]), 4);
    assert!(s.set_speed(0.5).is_ok());
    run(&mut s, 100);
    let held = s.snapshot();
    assert_eq!(held.odometry_time, 0.99);
    until(&mut s, 1.99, |s| {
        let now = s.snapshot();
        assert_eq!(now.odometry, held.odometry);
        assert_eq!(now.odometry_time, 0.99);
        assert_eq!(now.pose, held.pose, "the estimate stands still");
    });
    run(&mut s, 1);
    let back = s.snapshot();
    assert_eq!(back.odometry_time, 2.0);
    let error = back.pose.x - s.true_pose().x;
    assert!(error.abs() < 0.05, "caught up in one step: {error}");
}

#[test]
fn a_frozen_navigation_fix_keeps_its_stamp() {
    let mut s = sim(RobotConfig::workpartner(), faulted(&["nav_frozen@1+1"]), 5);
    let mut fixes = Vec::new();
    let mut seq = 0;
    until(&mut s, 3.0, |s| {
        let f = s.snapshot().nav_fix.unwrap_or_else(|| panic!("a fix"));
        if f.seq != seq {
            seq = f.seq;
            fixes.push(f.time);
        }
    });
    assert_eq!(fixes, vec![0.5, 2.0, 2.5, 3.0]);
    let moro = Simulator::new(RobotConfig::moro(), faulted(&["nav_frozen"]), 5);
    assert!(
        moro.is_err_and(|e| e.to_string() == "Moro has no navigation fix"),
        "MoRo has no fix to freeze"
    );
}

#[test]
fn a_dead_battery_reads_empty_and_the_drive_rolls_to_rest() {
    let cfg = RobotConfig::moro();
    let (v_empty, decel) = (cfg.battery.v_empty, cfg.limits.max_decel);
    let mut s = sim(cfg, faulted(&["dead_battery@1+1"]), 6);
    assert!(s.set_speed(0.5).is_ok());
    run(&mut s, 99);
    assert!(s.snapshot().battery.voltage > v_empty);
    let mut last = s.true_speed();
    until(&mut s, 2.0 - DT, |s| {
        assert_eq!(s.snapshot().battery.voltage, v_empty);
        let fall = last - s.true_speed();
        assert!((-1e-12..=decel * DT + 1e-12).contains(&fall), "fell {fall}");
        last = s.true_speed();
    });
    assert_eq!(s.true_speed(), 0.0);
    run(&mut s, 1);
    assert!(
        s.snapshot().battery.voltage > v_empty,
        "power is back at 2 s"
    );
    run(&mut s, 10);
    assert!(s.true_speed() > 0.0);
}

fn workpartner(faults: &[&str]) -> SimRobot {
    SimRobot::workpartner(faulted(faults), 7).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_dead_drive_times_out_and_its_watchdog_brakes() {
    let mut r = workpartner(&["actuator_dead@1+1"]);
    assert!(r.set_motion(0.5, 0.1).is_ok());
    assert!(r.update(1.0).is_ok());
    let at_fault = r.sim().true_speed();
    let c = r.sim().true_curvature();
    assert!(matches!(r.set_motion(0.5, 0.0), Err(HalError::Timeout(_))));
    assert!(r.update(1.5).is_ok());
    let decel = r.sim().config().limits.max_decel;
    assert!((r.sim().true_speed() - (at_fault - 0.5 * decel).max(0.0)).abs() < 1e-9);
    assert_eq!(r.sim().true_curvature(), c, "the steering holds");
    assert!(r.update(2.0).is_ok());
    assert!(r.set_motion(0.5, 0.0).is_ok(), "answers again at 2 s");
}

#[test]
fn a_dead_model_actuator_times_out_and_keeps_its_value() {
    let mut r = workpartner(&["actuator_dead@1+1:brake"]);
    assert!(r.update(1.0).is_ok());
    assert!(matches!(
        r.actuator("brake", 1.0),
        Err(HalError::Timeout(_))
    ));
    assert!(r.actuator_values().is_empty());
    assert!(r.set_motion(0.3, 0.0).is_ok(), "the drive still answers");
    assert!(r.update(2.0).is_ok());
    assert!(r.actuator("brake", 1.0).is_ok());
}

#[test]
fn a_silent_manipulator_loses_answers_due_on_its_window() {
    let mut r = workpartner(&["manipulator_silent@0+5"]);
    let take = r
        .start(&AsyncOp::Manipulate(ManipTask::Take))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(r.update(10.0).is_ok());
    assert_eq!(r.poll(take).ok(), Some(OpStatus::Pending), "never answers");
    assert!(
        matches!(
            r.start(&AsyncOp::Manipulate(ManipTask::GetBall)),
            Err(HalError::Refused(_))
        ),
        "still busy"
    );
    assert!(r.cancel(take).is_ok());
    assert!(matches!(r.poll(take), Ok(OpStatus::Failed(_))));
    let ball = r
        .start(&AsyncOp::Manipulate(ManipTask::GetBall))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(r.update(12.0).is_ok());
    assert_eq!(r.poll(ball).ok(), Some(OpStatus::Done), "answers after 5 s");
}

#[test]
fn an_obstacle_appears_ahead_and_goes() {
    let mut s = sim(
        RobotConfig::moro(),
        faulted(&["obstacle_appears@1+1:1.0"]),
        8,
    );
    let post = |s: &Simulator| {
        s.scene()
            .solids()
            .iter()
            .find(|x| x.what == SolidRef::Fault(0))
            .map(|x| (x.active, x.shape.center()))
    };
    assert_eq!(post(&s).map(|p| p.0), Some(false));
    assert!(s.set_speed(0.3).is_ok());
    run(&mut s, 99);
    assert_eq!(post(&s).map(|p| p.0), Some(false));
    let pose = s.true_pose();
    run(&mut s, 1);
    let (on, center) = post(&s).unwrap_or_else(|| panic!("a post"));
    let b = &s.config().body;
    let ahead = b.length - b.rear_overhang + 1.0 + ilmr_sim::faults::DEFAULT_OBSTACLE_RADIUS;
    assert!(on && (center.x - pose.x - ahead).abs() < 1e-9 && (center.y - pose.y).abs() < 1e-9);
    // The scan at 1.0 s sees it straight ahead (beam 180).
    let scan = s.snapshot().scan.unwrap_or_else(|| panic!("a scan"));
    assert_eq!(scan.time, 1.0);
    let expect = center.x - (s.true_pose().x + scan.mount.x) - 0.25;
    assert!(
        (scan.ranges[180] - expect).abs() < 0.05,
        "{} vs {expect}",
        scan.ranges[180]
    );
    run(&mut s, 100);
    assert_eq!(post(&s).map(|p| p.0), Some(false), "gone at 2 s");
    let events: Vec<String> = s
        .drain_events()
        .iter()
        .map(|e| format!("{:?}", e.kind))
        .collect();
    assert!(
        events.contains(&"FaultBegan(\"obstacle_appears\")".to_string()),
        "{events:?}"
    );
    assert!(
        events.contains(&"FaultEnded(\"obstacle_appears\")".to_string()),
        "{events:?}"
    );
}

#[test]
fn a_random_plan_runs_bit_identically() {
    let plan = random_plan(17, 20.0, 12, RobotKind::Workpartner);
    let run_once = |seed: u64| {
        let mut w = open_floor();
        w.faults.clone_from(&plan);
        let mut r = SimRobot::workpartner(w, seed).unwrap_or_else(|e| panic!("{e}"));
        let mut log = String::new();
        for k in 1..=600 {
            let v = if (k / 200) % 2 == 0 { 0.5 } else { -0.3 };
            let _ = r.set_motion(v, 0.05);
            let _ = r.update(k as f64 * DT);
            log.push_str(&format!(
                "{:?} {:?}\n",
                r.sim().snapshot(),
                r.sim().true_pose()
            ));
        }
        log
    };
    let a = run_once(5);
    assert!(a == run_once(5), "same seed and faults, different runs");
    assert!(a != run_once(6), "another seed, the same run");
}

#[test]
fn world_files_report_bad_faults_at_their_key() {
    let base = "name = \"w\"\nbounds = { min = [0.0, 0.0], max = [9.0, 9.0] }\nstart = { x = 1.0, y = 1.0 }\n\n";
    let err = |entry: &str| {
        World::from_toml(&format!("{base}{entry}"), "w.toml")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    assert!(
        err("[[fault]]\nkind = \"smoke\"\n").starts_with(
            "w.toml:6: fault #1 kind: unknown fault `smoke`, expected one of scanner_dropout"
        ),
        "{}",
        err("[[fault]]\nkind = \"smoke\"\n")
    );
    assert_eq!(
        err("[[fault]]\nkind = \"odometry_slip\"\nstart = 2.0\nslip = 1.5\n"),
        "w.toml:8: fault #1 slip: slip must be above 0 and at most 0.9, got 1.5"
    );
    assert_eq!(
        err("[[fault]]\nkind = \"dead_battery\"\nbias = 0.1\n"),
        "w.toml:7: fault #1 bias: `dead_battery` takes no `bias`"
    );
    assert_eq!(
        err("[[fault]]\nkind = \"scanner_dropout\"\nduration = -1.0\n"),
        "w.toml:7: fault #1 duration: duration must be a positive time, got -1"
    );
    let ok = World::from_toml(
        &format!("{base}[[fault]]\nkind = \"obstacle_appears\"\nstart = 3.0\nradius = 0.4\n"),
        "w.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(ok.faults[0].to_string(), "obstacle_appears@3:1.5");
}
