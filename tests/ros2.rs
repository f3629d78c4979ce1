//! `ilmrc run --robot ros2` against a robot this project did not write: a ROS 2 base
//! driver on Eclipse Cyclone DDS (robots/ros2/python/cyclone_robot.py, through
//! Cyclone's Python binding), which obeys `cmd_vel`, stops on its own command timeout
//! and publishes `odom`, `scan` and `battery_state` under ROS 2's type names.
//!
//! Each test runs the robot and `ilmrc` in a network namespace of its own
//! (`unshare -n`, robots/ros2/python/netns_run.py), where loopback is the only
//! interface: DDS discovery by multicast cannot leave the machine. CI installs
//! `cyclonedds` (`.ci/run`); without it, or without the right to make a namespace,
//! these tests fail rather than pass unchecked.
//!
//! What is asserted is what the robot saw and did, from its own report: where it ended
//! (its true pose), and every twist it received.

mod support;

use std::path::PathBuf;
use std::process::Command;

use ilmr_model::RobotModel;
use serde_json::{Value, json};

/// A twist the robot received: its time (s since the robot started), linear.x,
/// angular.z.
#[derive(Debug, Clone, Copy)]
struct Received {
    t: f64,
    v: f64,
    w: f64,
}

struct Driven {
    code: Option<i64>,
    summary: String,
    stderr: String,
    /// The robot's true pose at the end: x, y (m), heading (degrees).
    pose: (f64, f64, f64),
    speed: f64,
    twists: Vec<Received>,
    trace: Vec<Value>,
}

/// The DDS tests run one at a time: each drives a robot in real time, and what they
/// assert of timing (zeros repeated, rates) must not depend on how many others share
/// the cores.
fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());
    SERIAL.lock().unwrap_or_else(|e| e.into_inner())
}

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("ilmr-ros2-{}-{name}", std::process::id()))
}

/// Runs `task` with `ilmrc run --robot ros2` against the Cyclone robot started with
/// `robot`, both in a namespace of their own.
fn drive(name: &str, task: &str, robot: &[&str], run: &[&str]) -> Driven {
    drive_beside(name, task, robot, run, None)
}

/// As [`drive`], with a program started first beside them (`background`, a command
/// line that prints a line when it is ready).
fn drive_beside(
    name: &str,
    task: &str,
    robot: &[&str],
    run: &[&str],
    background: Option<&str>,
) -> Driven {
    let root = support::root();
    let task_path = scratch(&format!("{name}.ilmr"));
    let trace_path = scratch(&format!("{name}.jsonl"));
    std::fs::write(&task_path, task).unwrap();
    let mut cmd = Command::new("unshare");
    cmd.arg("-n")
        .arg("python3")
        .arg(root.join("robots/ros2/python/netns_run.py"))
        .args(["--timeout", "60"]);
    for a in robot {
        cmd.arg(format!("--robot-arg={a}"));
    }
    if let Some(b) = background {
        cmd.args(["--background", b]);
    }
    cmd.arg("--")
        .arg(env!("CARGO_BIN_EXE_ilmrc"))
        .args(["run", "--robot", "ros2", "--ros-loopback"])
        .args(if run.contains(&"--ros-wait") {
            &[][..]
        } else {
            &["--ros-wait", "20"][..]
        })
        .arg("--trace")
        .arg(&trace_path)
        .args(run)
        .arg(&task_path)
        .env("NO_COLOR", "1");
    let out = cmd.output().expect("unshare and python3 run");
    let report: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "netns_run.py printed no report ({e}); is `cyclonedds` installed (pip install \
             cyclonedds) and may this user make a network namespace?\nstdout: {}\nstderr: {}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    let ilmrc = &report["ilmrc"];
    let robot = &report["robot"];
    assert!(
        robot.get("pose").is_some(),
        "the robot wrote no report: {robot}"
    );
    let num = |v: &Value| v.as_f64().unwrap();
    let pose = &robot["pose"];
    let trace = std::fs::read_to_string(&trace_path)
        .unwrap_or_default()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let _ = std::fs::remove_file(&task_path);
    let _ = std::fs::remove_file(&trace_path);
    Driven {
        code: ilmrc["code"].as_i64(),
        summary: ilmrc["stdout"].as_str().unwrap().to_string(),
        stderr: ilmrc["stderr"].as_str().unwrap().to_string(),
        pose: (num(&pose[0]), num(&pose[1]), num(&pose[2])),
        speed: num(&robot["speed"]),
        twists: robot["twists"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| Received {
                t: num(&t[0]),
                v: num(&t[1]),
                w: num(&t[2]),
            })
            .collect(),
        trace,
    }
}

/// Every twist within MoRo's model: the speed within `max_speed`, the turn rate
/// within what `max_curvature` allows at that speed.
fn within_the_model(d: &Driven) {
    let moro = RobotModel::builtin("moro").unwrap();
    for t in &d.twists {
        assert!(
            t.v.abs() <= moro.max_speed() + 1e-9,
            "cmd_vel {t:?} is faster than max_speed {}",
            moro.max_speed()
        );
        assert!(
            t.w.abs() <= t.v.abs() * moro.max_curvature() + 1e-9,
            "cmd_vel {t:?} turns sharper than max_curvature {}",
            moro.max_curvature()
        );
    }
}

fn faults(d: &Driven, event: &str) -> Vec<String> {
    d.trace
        .iter()
        .filter(|e| e["event"] == event)
        .map(|e| e["fault"].as_str().unwrap_or_default().to_string())
        .collect()
}

/// The zero twists the robot received in `from..to` (its own clock), and whether any
/// twist there was not zero.
fn zeros_in(d: &Driven, from: f64, to: f64) -> (Vec<f64>, bool) {
    let inside: Vec<&Received> = d
        .twists
        .iter()
        .filter(|t| t.t >= from && t.t < to)
        .collect();
    let zeros = inside
        .iter()
        .filter(|t| t.v == 0.0 && t.w == 0.0)
        .map(|t| t.t)
        .collect();
    (zeros, inside.iter().any(|t| t.v != 0.0 || t.w != 0.0))
}

/// Zero twists keep coming while the robot is halted, as often as a driver's command
/// timeout needs: no gap as long as ros2_controllers' `diff_drive_controller` waits
/// by default (`cmd_vel_timeout`, 0.5 s) before it stops the wheels itself, and on
/// average about one per keepalive (0.1 s). The bound is the driver's, not the
/// keepalive's: a process descheduled for 0.3 s on a loaded machine (seen at load
/// 14) keeps a real robot driven.
fn repeated(zeros: &[f64], from: f64, to: f64) {
    assert!(!zeros.is_empty(), "no zero twist in {from:.2}..{to:.2} s");
    let mut last = from;
    for &t in zeros.iter().chain([to].iter()) {
        assert!(
            t - last < 0.5,
            "no twist between {last:.2} and {t:.2} s while halted: {zeros:?}"
        );
        last = t;
    }
    let expected = (to - from) / 0.1;
    assert!(
        zeros.len() as f64 >= 0.5 * expected,
        "{} zero twists in {from:.2}..{to:.2} s, about {expected:.0} expected: {zeros:?}",
        zeros.len()
    );
}

#[test]
fn a_task_drives_a_cyclone_dds_robot_to_its_goal() {
    let _serial = one_at_a_time();
    let mcap = scratch("goal.mcap");
    let d = drive(
        "goal",
        "speed(0.4)\nm=gotoxy(2,1)\nwait(m)\n",
        &["--duration=60"],
        &["--max-time", "40", "--mcap", mcap.to_str().unwrap()],
    );
    assert_eq!(d.code, Some(0), "{}\n{}", d.summary, d.stderr);
    assert!(d.summary.contains("finished"), "{}", d.summary);
    // This robot publishes no tf: the operator is told how its scans are read.
    assert!(
        d.stderr.contains("no transform places the robot's scanner"),
        "{}",
        d.stderr
    );
    let (x, y, _) = d.pose;
    let miss = (x - 2.0).hypot(y - 1.0);
    assert!(
        miss < 0.10,
        "the robot ended at ({x:.3}, {y:.3}), {miss:.3} m from (2, 1)"
    );
    assert!(d.speed.abs() < 1e-9, "the robot still moves: {}", d.speed);
    within_the_model(&d);
    // The trace shows the run as a simulated one's does: poses, from the robot's own
    // odometry, ending where the robot is.
    let last = d
        .trace
        .iter()
        .rev()
        .find(|e| e["event"] == "pose")
        .expect("the trace has poses");
    let (tx, ty) = (last["x"].as_f64().unwrap(), last["y"].as_f64().unwrap());
    assert!(
        (tx - x).hypot(ty - y) < 0.02,
        "the trace ends at ({tx}, {ty}), the robot at ({x}, {y})"
    );
    assert!(
        d.trace.iter().any(|e| e["event"] == "end"),
        "the trace has the commands' ends"
    );
    recorded_as_a_bag(&mcap, (x, y));
}

/// A field run debugged offline: the run on the ROS 2 robot records what the VM
/// received (`--record-inputs`, here into the MCAP file), and `ilmrc replay --inputs`
/// runs the task again from it with no robot and no DDS, on logical time: every call
/// as the recording has it, and the trace the run wrote, line for line.
#[test]
fn a_ros_2_run_replays_offline_from_its_recorded_inputs() {
    let _serial = one_at_a_time();
    let mcap = scratch("replayed.mcap");
    let task = "speed(0.3)\nm=gotoxy(1.5,0.5)\nwait(m)\n";
    let d = drive(
        "replayed",
        task,
        &["--duration=60"],
        &[
            "--max-time",
            "40",
            "--record-inputs",
            "--mcap",
            mcap.to_str().unwrap(),
        ],
    );
    assert_eq!(d.code, Some(0), "{}\n{}", d.summary, d.stderr);
    let task_path = scratch("replayed-again.ilmr");
    let again = scratch("replayed-again.jsonl");
    std::fs::write(&task_path, task).unwrap();
    let (code, out, err) = support::ilmrc(&[
        "replay",
        "--inputs",
        mcap.to_str().unwrap(),
        task_path.to_str().unwrap(),
        "--trace",
        again.to_str().unwrap(),
    ]);
    let replayed: Vec<Value> = std::fs::read_to_string(&again)
        .unwrap_or_default()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    for p in [&mcap, &task_path, &again] {
        let _ = std::fs::remove_file(p);
    }
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains("every call to the robot was the recording's"),
        "{out}"
    );
    assert!(
        d.trace.iter().any(|e| e["event"] == "input"),
        "the run recorded its inputs"
    );
    assert_eq!(replayed.len(), d.trace.len(), "{out}");
    for (i, (a, b)) in d.trace.iter().zip(&replayed).enumerate() {
        assert_eq!(a, b, "line {} of the trace", i + 1);
    }
}

/// The MCAP file of the run, read by Foxglove's own libraries (`mcap`,
/// `mcap-ros2-support`): the robot's topics with ROS 2's schemas, every message
/// decoded, the last odometry where the robot ended.
fn recorded_as_a_bag(mcap: &std::path::Path, (x, y): (f64, f64)) {
    let out = Command::new("python3")
        .arg(support::root().join("tools/read_mcap.py"))
        .arg(mcap)
        .output()
        .unwrap();
    let _ = std::fs::remove_file(mcap);
    let topics: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "read_mcap.py failed ({e}); CI installs `mcap`, `mcap-protobuf-support` and `mcap-ros2-support`:\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    for (topic, schema) in [
        ("/cmd_vel", "geometry_msgs/msg/Twist"),
        ("/odom", "nav_msgs/msg/Odometry"),
        ("/scan", "sensor_msgs/msg/LaserScan"),
        ("/battery_state", "sensor_msgs/msg/BatteryState"),
    ] {
        let t = &topics[topic];
        assert_eq!(t["schema"], schema, "{topic}: {t}");
        assert_eq!(
            (&t["schema_encoding"], &t["message_encoding"]),
            (&json!("ros2msg"), &json!("cdr"))
        );
        assert!(
            t["count"].as_u64().unwrap() > 0 && t["decoded"] == t["count"],
            "{topic}: {t}"
        );
    }
    let last = &topics["/odom"]["last"];
    let (ox, oy) = (last["x"].as_f64().unwrap(), last["y"].as_f64().unwrap());
    assert!((ox - x).hypot(oy - y) < 0.02, "{last} vs ({x}, {y})");
    assert_eq!(topics["/scan"]["beams"], 181);
    assert!(topics["/cmd_vel"]["max_linear_x"].as_f64().unwrap() <= 0.4 + 1e-9);
    // ILMR's own channels stay, but for the scan, which the robot's topic records.
    assert_eq!(topics["/pose"]["schema"], "foxglove.PoseInFrame");
    assert_eq!(
        topics["/scan"]["schema_encoding"], "ros2msg",
        "one /scan, the robot's"
    );
}

#[test]
fn a_lost_odometry_stream_halts_the_robot_and_zero_velocity_is_repeated() {
    let _serial = one_at_a_time();
    let d = drive(
        "odom",
        "speed(0.3)\ngoahead(5)\n",
        &["--duration=60", "--odom-stop-at=4.0"],
        &["--max-time", "8"],
    );
    assert!(d.code.is_some(), "ilmrc did not end: {}", d.stderr);
    assert!(
        faults(&d, "fault").iter().any(|f| f == "odometry_lost"),
        "no odometry_lost fault in the trace: {}",
        d.summary
    );
    // The halt ramps down within max_deceleration (0.3 m/s at 0.8 m/s2: 0.4 s), after
    // odometry_timeout (0.25 s): from 5.0 s on the robot hears only zeros, and keeps
    // hearing them until ilmrc ends.
    let end = d.twists.last().unwrap().t;
    assert!(end > 6.0, "the run ended early, at {end} s");
    let (zeros, moving) = zeros_in(&d, 5.0, end + 1e-9);
    assert!(!moving, "a twist that moves after the odometry was lost");
    repeated(&zeros, 5.0, end);
    assert!(d.speed.abs() < 1e-9, "the robot still moves: {}", d.speed);
    let (x, _, _) = d.pose;
    assert!(
        x < 1.5,
        "the robot went on to x = {x:.2} m without odometry"
    );
    within_the_model(&d);
}

#[test]
fn a_scan_gap_holds_the_robot_with_repeated_zeros_and_it_goes_on_when_scans_return() {
    let _serial = one_at_a_time();
    let d = drive(
        "scan",
        "speed(0.3)\nm=gotoxy(3,0)\nwait(m)\n",
        &[
            "--duration=60",
            "--scan-stop-at=4.0",
            "--scan-resume-at=7.0",
        ],
        &["--max-time", "40"],
    );
    assert_eq!(d.code, Some(0), "{}\n{}", d.summary, d.stderr);
    assert!(
        faults(&d, "fault").iter().any(|f| f == "scanner_lost"),
        "no scanner_lost fault in the trace"
    );
    assert!(
        faults(&d, "recovered").iter().any(|f| f == "scanner_lost"),
        "the scanner_lost fault never cleared"
    );
    // Held from about 4.0 + scanner_timeout (1.0) + the ramp; scans return at 7.0.
    let (zeros, moving) = zeros_in(&d, 5.8, 7.0);
    assert!(!moving, "a twist that moves while the scanner was lost");
    repeated(&zeros, 5.8, 7.0);
    let (x, y, _) = d.pose;
    assert!(
        (x - 3.0).hypot(y) < 0.10,
        "the robot ended at ({x:.3}, {y:.3}), not at (3, 0)"
    );
    within_the_model(&d);
}

#[test]
fn the_shell_drives_a_ros_2_robot_as_run_does() {
    let _serial = one_at_a_time();
    let root = support::root();
    let task = scratch("shell.ilmr");
    std::fs::write(&task, "speed(0.4)\ngotoxy(2,1)\n").unwrap();
    // The shell takes its task, then `:status` and `:quit` from a pipe, after the
    // robot has had time to get there.
    let shell = format!(
        "(sleep 10; echo :status; echo :quit) | {} shell --robot ros2 --ros-loopback \
         --ros-namespace /s1 --task {}",
        env!("CARGO_BIN_EXE_ilmrc"),
        task.display()
    );
    let out = Command::new("unshare")
        .arg("-n")
        .arg("python3")
        .arg(root.join("robots/ros2/python/netns_run.py"))
        .args([
            "--timeout",
            "60",
            "--robot-arg=--namespace=/s1",
            "--",
            "sh",
            "-c",
        ])
        .arg(&shell)
        .current_dir(&root)
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let _ = std::fs::remove_file(&task);
    let report: Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
    let shown = report["ilmrc"]["stdout"].as_str().unwrap();
    assert_eq!(report["ilmrc"]["code"], 0, "{report}");
    assert!(
        shown.starts_with("ILMR shell: moro in ROS 2 namespace /s1"),
        "{shown}"
    );
    let pose = &report["robot"]["pose"];
    let (x, y) = (pose[0].as_f64().unwrap(), pose[1].as_f64().unwrap());
    assert!(
        (x - 2.0).hypot(y - 1.0) < 0.10,
        "the robot ended at ({x:.3}, {y:.3})\n{shown}"
    );
}

/// A Cyclone peer that publishes bad samples under the robot's namespace.
fn hostile(mode: &str) -> String {
    let script = support::root().join("robots/ros2/python/cyclone_hostile.py");
    format!("python3 {} --mode {mode}", script.display())
}

fn link_counts(summary: &str) -> &str {
    summary
        .lines()
        .find(|l| l.trim_start().starts_with("ros 2 link"))
        .unwrap_or_else(|| panic!("no link counts in the summary:\n{summary}"))
}

#[test]
fn malformed_odometry_from_another_peer_is_dropped_and_the_task_reaches_its_goal() {
    let _serial = one_at_a_time();
    let d = drive_beside(
        "malformed",
        "speed(0.4)\nm=gotoxy(2,1)\nwait(m)\n",
        &["--duration=60"],
        &["--max-time", "40"],
        Some(&hostile("malformed")),
    );
    assert_eq!(d.code, Some(0), "{}\n{}", d.summary, d.stderr);
    let (x, y, _) = d.pose;
    assert!((x - 2.0).hypot(y - 1.0) < 0.10, "ended at ({x:.3}, {y:.3})");
    let counts = link_counts(&d.summary);
    let dropped: u64 = counts
        .split("odom ")
        .nth(1)
        .and_then(|r| r.split(", ").nth(1))
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{counts}"));
    assert!(
        dropped > 100,
        "the malformed samples were not seen and dropped: {counts}"
    );
}

/// A flood on `odom` crowds the robot's own samples out of DDS's short history, so
/// the stream of usable odometry thins: the robot must then be halted by
/// `odometry_lost` rather than driven on stale poses, and however fast the flood, the
/// VM takes at most 64 samples a tick.
#[test]
fn a_flood_of_nan_odometry_is_bounded_per_tick_and_never_the_robots_pose() {
    let _serial = one_at_a_time();
    let d = drive_beside(
        "flood",
        "speed(0.4)\nm=gotoxy(2,1)\nwait(m)\n",
        &["--duration=60"],
        &["--max-time", "40"],
        Some(&hostile("nan")),
    );
    assert!(d.code.is_some(), "ilmrc did not end: {}", d.stderr);
    assert!(!d.stderr.contains("panicked"), "{}", d.stderr);
    let counts = link_counts(&d.summary);
    let unusable: u64 = counts
        .split('(')
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{counts}"));
    let most: usize = counts
        .split("at most ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{counts}"));
    assert!(unusable > 0, "the flood never reached the robot: {counts}");
    assert!(most <= 64, "more samples taken than 64 a tick: {counts}");
    assert!(
        d.trace
            .iter()
            .filter(|e| e["event"] == "pose")
            .all(|e| e["x"].as_f64().is_some_and(f64::is_finite)),
        "a NaN pose in the trace"
    );
    let (x, y, _) = d.pose;
    let reached = (x - 2.0).hypot(y - 1.0) < 0.10;
    assert!(
        reached || faults(&d, "fault").iter().any(|f| f == "odometry_lost"),
        "the robot neither reached its goal nor was halted for lost odometry: ended at \
         ({x:.3}, {y:.3})\n{}",
        d.summary
    );
    assert!(d.speed.abs() < 1e-9, "the robot still moves: {}", d.speed);
    within_the_model(&d);
}

#[test]
fn an_oversized_scan_never_becomes_the_robots_and_it_drives_on_the_real_scans() {
    let _serial = one_at_a_time();
    let d = drive_beside(
        "oversize",
        "speed(0.4)\nm=gotoxy(2,1)\nwait(m)\n",
        &["--duration=60"],
        &["--max-time", "40"],
        Some(&hostile("oversize")),
    );
    assert_eq!(d.code, Some(0), "{}\n{}", d.summary, d.stderr);
    let (x, y, _) = d.pose;
    assert!((x - 2.0).hypot(y - 1.0) < 0.10, "ended at ({x:.3}, {y:.3})");
    // Best-effort fragments of 12 MB rarely arrive whole through a 4 MB socket buffer;
    // those that do are refused (MAX_MESSAGE_BYTES, as robots/ros2/tests/hostile.rs
    // shows sample by sample). Either way none becomes the robot's scan.
    // Every scan the trace holds is the robot's (181 beams), none of the 3 million.
    let scans: Vec<&Value> = d.trace.iter().filter(|e| e["event"] == "scan").collect();
    assert!(!scans.is_empty());
    for s in scans {
        assert!(s["hits"].as_array().unwrap().len() <= 181);
    }
}

/// A second node commanding `cmd_vel` (a teleop that takes over, then lets go): ILMR
/// sees the other writer, yields the robot while it speaks (a zero twist, then
/// silence), says so, and drives on to its goal once it has been silent.
#[test]
fn a_second_driver_on_cmd_vel_is_seen_and_yielded_to_until_it_lets_go() {
    let _serial = one_at_a_time();
    let d = drive_beside(
        "second-driver",
        "speed(0.4)\nm=gotoxy(2,1)\nwait(m)\n",
        &["--duration=60"],
        &["--max-time", "40"],
        Some(&format!("{} --seconds 4", hostile("cmd_vel"))),
    );
    let others = d
        .summary
        .lines()
        .find(|l| l.trim_start().starts_with("other drivers"))
        .unwrap_or_else(|| panic!("the other writer went unseen:\n{}", d.summary));
    assert!(others.contains("from 1 other writer"), "{others}");
    assert!(!others.contains("yielded the robot 0 times"), "{others}");
    assert!(
        d.stderr.contains("another node publishes on /cmd_vel"),
        "no notice of the other driver: {}",
        d.stderr
    );
    // It let go after 4 s; the task then went on to its goal.
    let (x, y, _) = d.pose;
    assert!(
        (x - 2.0).hypot(y - 1.0) < 0.10,
        "ended at ({x:.3}, {y:.3})\n{}",
        d.summary
    );
    assert_eq!(
        d.code,
        Some(3),
        "the yield is told as a refusal: {}",
        d.summary
    );
    within_the_model(&d);
}

/// Runs `command` beside `ilmrc sim --ros2 SIM...` in a namespace of their own, with
/// DDS on loopback; returns the command's report and the simulator's stdout.
fn beside_the_simulator(sim: &[&str], command: &[&str]) -> (Value, String) {
    let root = support::root();
    let ilmrc = env!("CARGO_BIN_EXE_ilmrc");
    let background = format!("{ilmrc} sim --ros2 --ros-loopback {}", sim.join(" "));
    let out = Command::new("unshare")
        .arg("-n")
        .arg("python3")
        .arg(root.join("robots/ros2/python/netns_run.py"))
        .args([
            "--no-robot",
            "--timeout",
            "60",
            "--background",
            &background,
            "--",
        ])
        .args(command)
        .current_dir(&root)
        .env("NO_COLOR", "1")
        .output()
        .expect("unshare and python3 run");
    let report: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "netns_run.py printed no report ({e}):\nstdout: {}\nstderr: {}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    let sim_out = report["background"][0]["stdout"]
        .as_str()
        .unwrap()
        .to_string();
    (report["ilmrc"].clone(), sim_out)
}

#[test]
fn the_simulator_is_a_ros_2_robot_that_cyclone_dds_sees_at_the_models_rates() {
    let _serial = one_at_a_time();
    let (listened, sim) = beside_the_simulator(
        &["--ros-namespace", "/r1", "--clock", "--world", "office"],
        &[
            "python3",
            "robots/ros2/python/cyclone_listener.py",
            "--namespace",
            "/r1",
            "--seconds",
            "3",
        ],
    );
    assert_eq!(listened["code"], 0, "{listened}");
    assert!(sim.starts_with("ilmrc sim: moro in office"), "{sim}");
    let seen: Value = serde_json::from_str(listened["stdout"].as_str().unwrap()).unwrap();
    let moro = RobotModel::builtin("moro").unwrap();
    // Rates as Cyclone receives them, within 15 % of the model's (what a reader over
    // loopback sees of a real-time loop on a loaded machine).
    for (topic, rate) in [
        ("odom", moro.odometry_rate()),
        ("tf", moro.odometry_rate()),
        ("ground_truth", moro.odometry_rate()),
        ("scan", moro.scanner_rate()),
        ("clock", 100.0),
        ("battery_state", 1.0),
    ] {
        let got = seen[topic]["rate"].as_f64().unwrap();
        assert!(
            (got - rate).abs() <= 0.15 * rate,
            "{topic}: {got:.2} Hz where the model says {rate} Hz; {}",
            seen[topic]
        );
    }
    let odom = &seen["odom"]["last"];
    assert_eq!(
        (odom["frame"].as_str(), odom["child"].as_str()),
        (Some("odom"), Some("base_link"))
    );
    // The office run start is (8, 5, 0); a robot given no command stays there.
    let (x, y) = (odom["x"].as_f64().unwrap(), odom["y"].as_f64().unwrap());
    assert!((x - 8.0).abs() < 0.01 && (y - 5.0).abs() < 0.01, "{odom}");
    let stamp = odom["stamp"].as_f64().unwrap();
    let clock = seen["clock"]["last"]["clock"].as_f64().unwrap();
    assert!(
        stamp < 10.0 && (clock - stamp).abs() < 0.5,
        "with --clock, messages carry simulated time: odom {stamp}, clock {clock}"
    );
    let scan = &seen["scan"]["last"];
    assert_eq!(scan["beams"], 361, "MoRo's scanner: {scan}");
    let pairs = &seen["tf"]["last"]["pairs"];
    assert_eq!(
        pairs,
        &serde_json::json!([["odom", "base_link"], ["base_link", "laser"]])
    );
    let volts = seen["battery_state"]["last"]["voltage"].as_f64().unwrap();
    assert!((volts - moro.battery_full()).abs() < 0.5, "{volts}");
}

#[test]
fn ilmrc_run_drives_ilmrc_sim_in_another_process_over_dds() {
    let _serial = one_at_a_time();
    let task = scratch("sim_goal.ilmr");
    let trace = scratch("sim_goal.jsonl");
    std::fs::write(&task, "speed(0.4)\nm=gotoxy(2,1)\nwait(m)\n").unwrap();
    let (ran, _) = beside_the_simulator(
        &[
            "--ros-namespace",
            "/r2",
            "--world",
            "empty",
            "--start",
            "0,0,0",
        ],
        &[
            env!("CARGO_BIN_EXE_ilmrc"),
            "run",
            "--robot",
            "ros2",
            "--ros-loopback",
            "--ros-namespace",
            "/r2",
            "--max-time",
            "40",
            "--trace",
            trace.to_str().unwrap(),
            task.to_str().unwrap(),
        ],
    );
    let summary = ran["stdout"].as_str().unwrap();
    assert_eq!(ran["code"], 0, "{ran}");
    assert!(summary.contains("finished: no command left"), "{summary}");
    // The simulator's tf places MoRo's scanner where its body has it, and the run
    // reads the scans from there.
    let moro = RobotModel::builtin("moro").unwrap();
    let mount = ilmr_sim::config_from_model(&moro, ilmr_sim::RobotKind::Moro)
        .scanner
        .mount;
    let said = format!(
        "scanner         at ({}, {}) m on the robot, by tf",
        ilmr_vm::runtime::trace::fmt_num(mount.x),
        ilmr_vm::runtime::trace::fmt_num(mount.y)
    );
    assert!(
        mount.x > 0.1 && summary.contains(&said),
        "{said}\n{summary}"
    );
    let text = std::fs::read_to_string(&trace).unwrap();
    let _ = std::fs::remove_file(&task);
    let _ = std::fs::remove_file(&trace);
    let last: Value = text
        .lines()
        .rev()
        .map(|l| serde_json::from_str::<Value>(l).unwrap())
        .find(|e| e["event"] == "pose")
        .expect("poses in the trace");
    let (x, y) = (last["x"].as_f64().unwrap(), last["y"].as_f64().unwrap());
    assert!(
        (x - 2.0).hypot(y - 1.0) < 0.10,
        "the simulated robot's odometry ends at ({x:.3}, {y:.3}), not at (2, 1)"
    );
}

#[test]
fn a_fleet_of_a_simulated_robot_and_a_launched_ros_2_one_runs_both_tasks_to_the_end() {
    let _serial = one_at_a_time();
    let dir = scratch("fleet");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("go.ilmr"), "speed(0.4)\nm=gotoxy(2,1)\nwait(m)\n").unwrap();
    std::fs::write(
        dir.join("fleet.toml"),
        "[[robot]]\nname = \"here\"\nrobot = \"moro\"\nworld = \"empty\"\n\
         start = \"0,0,0\"\ntask = \"go.ilmr\"\n\n\
         [[robot]]\nname = \"there\"\nrobot = \"ros2\"\nmodel = \"moro\"\nloopback = true\n\
         launch = true\nworld = \"empty\"\nstart = \"0,0,0\"\ntask = \"go.ilmr\"\n",
    )
    .unwrap();
    let out = Command::new("unshare")
        .args(["-n", "sh", "-c"])
        .arg(format!(
            "ip link set lo up multicast on && ip route add 224.0.0.0/4 dev lo && \
             exec timeout 90 {} fleet {} --every 1 --max-time 60",
            env!("CARGO_BIN_EXE_ilmrc"),
            dir.join("fleet.toml").display()
        ))
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let shown = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{shown}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        shown.ends_with("fleet: every task has finished\n"),
        "{shown}"
    );
    // The last table: both robots at the goal, finished.
    let last: Vec<&str> = shown.lines().rev().skip(1).take(2).collect();
    for row in last {
        let cells: Vec<&str> = row.split_whitespace().collect();
        let (x, y): (f64, f64) = (cells[2].parse().unwrap(), cells[3].parse().unwrap());
        assert!(
            (x - 2.0).hypot(y - 1.0) < 0.10 && row.ends_with("finished"),
            "{row}\n{shown}"
        );
    }
}

/// Processes whose command line holds `needle`: pid and command line.
fn processes_with(needle: &str) -> Vec<(String, String)> {
    std::fs::read_dir("/proc")
        .unwrap()
        .filter_map(|e| {
            let path = e.ok()?.path();
            let cmdline = std::fs::read(path.join("cmdline")).ok()?;
            let pid = path.file_name()?.to_str()?.to_string();
            Some((pid, String::from_utf8_lossy(&cmdline).replace('\0', " ")))
        })
        .filter(|(_, c)| c.contains(needle) && !c.contains("unshare"))
        .collect()
}

/// Kills what is left of the processes marked `0` when a test ends, failed or not: an
/// orphan would hold the test's output open and hang the run.
struct Reaper(String);

impl Drop for Reaper {
    fn drop(&mut self) {
        for (pid, _) in processes_with(&self.0) {
            let _ = Command::new("kill").args(["-9", &pid]).status();
        }
    }
}

#[test]
fn a_fleet_killed_outright_leaves_no_simulator_running() {
    let _serial = one_at_a_time();
    use std::io::{BufRead, BufReader};
    let dir = scratch("lifeline");
    std::fs::create_dir_all(&dir).unwrap();
    let marker = format!("/lifeline{}", std::process::id());
    let _reaper = Reaper(marker.clone());
    std::fs::write(
        dir.join("fleet.toml"),
        format!(
            "[[robot]]\nname = \"a\"\nrobot = \"ros2\"\nnamespace = \"{marker}\"\n\
             loopback = true\nlaunch = true\nworld = \"empty\"\n"
        ),
    )
    .unwrap();
    let mut fleet = Command::new("unshare")
        .args(["-n", "sh", "-c"])
        .arg(format!(
            "ip link set lo up multicast on && ip route add 224.0.0.0/4 dev lo && \
             exec {} fleet {} --stay --every 0.5",
            env!("CARGO_BIN_EXE_ilmrc"),
            dir.join("fleet.toml").display()
        ))
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // The first table: the simulator is up and the robot connected.
    let mut lines = BufReader::new(fleet.stdout.take().unwrap()).lines();
    let first = lines.next().and_then(Result::ok).unwrap_or_default();
    assert!(first.starts_with("robot"), "{first}");
    assert_eq!(processes_with(&marker).len(), 1, "one simulator runs");
    // SIGKILL: no destructor, no handler runs in the fleet.
    fleet.kill().unwrap();
    fleet.wait().unwrap();
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
    while !processes_with(&marker).is_empty() {
        assert!(
            std::time::Instant::now() < deadline,
            "the simulator outlived its fleet: {:?}",
            processes_with(&marker)
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A robot model whose `[ROS2]` section renames what the simulator publishes and the
/// run reads: both sides take their names from the one model.
#[test]
fn the_models_ros2_section_names_the_topics_on_both_sides() {
    let _serial = one_at_a_time();
    let dir = scratch("model");
    std::fs::create_dir_all(&dir).unwrap();
    let moro =
        std::fs::read_to_string(support::root().join("robots/model/models/moro.ini")).unwrap();
    let renamed = moro.replace(
        "[END]",
        "[ROS2]\nnamespace /tb\ncmd_vel cmd_vel_nav\nodom wheel/odom\nscan base_scan\n[END]",
    );
    let model = dir.join("renamed.ini");
    std::fs::write(&model, renamed).unwrap();
    let task = dir.join("go.ilmr");
    std::fs::write(&task, "speed(0.4)\nm=gotoxy(2,1)\nwait(m)\n").unwrap();
    let model = model.to_str().unwrap();
    let (ran, sim) = beside_the_simulator(
        &["--robot", model, "--world", "empty", "--start", "0,0,0"],
        &[
            env!("CARGO_BIN_EXE_ilmrc"),
            "run",
            "--robot",
            "ros2",
            "--model",
            model,
            "--ros-loopback",
            "--max-time",
            "40",
            task.to_str().unwrap(),
        ],
    );
    let _ = std::fs::remove_dir_all(&dir);
    assert!(sim.contains("namespace /tb"), "{sim}");
    let summary = ran["stdout"].as_str().unwrap();
    assert_eq!(ran["code"], 0, "{ran}");
    assert!(summary.contains("ROS 2 in namespace /tb"), "{summary}");
    let at: Vec<f64> = summary
        .split("ended at (")
        .nth(1)
        .and_then(|r| r.split(')').next())
        .map(|r| {
            r.split(", ")
                .take(2)
                .filter_map(|v| v.parse().ok())
                .collect()
        })
        .unwrap_or_default();
    assert!(
        at.len() == 2 && (at[0] - 2.0).hypot(at[1] - 1.0) < 0.10,
        "{summary}"
    );
}

/// A stream that stops around the moment the task starts would never be watched by the
/// VM's supervisor (it watches a stream from its second sample): either the run does
/// not start on it, or the backend holds the robot itself.
#[test]
fn odometry_that_stops_as_the_run_starts_never_leaves_the_robot_driven_blind() {
    let _serial = one_at_a_time();
    for stop in ["0.9", "1.2", "1.5"] {
        let d = drive(
            "stopped",
            "speed(0.3)\ngoahead(2)\n",
            &["--duration=30", &format!("--odom-stop-at={stop}")],
            &["--ros-wait", "4", "--max-time", "4"],
        );
        let stop: f64 = stop.parse().unwrap();
        let moving_after = d
            .twists
            .iter()
            .filter(|t| t.t > stop + 0.25 + 0.15 && t.v != 0.0)
            .count();
        match d.code {
            Some(2) => assert!(
                d.stderr.contains("stopped while connecting"),
                "{}",
                d.stderr
            ),
            // Held by the backend, the robot stood to --max-time with goahead(2) live
            // (exit 5); locked out by the supervisor's odometry_lost, goahead(2) was
            // refused and the task ended (exit 3).
            Some(3 | 5) => assert!(
                d.summary.contains("held 1 times for a stale stream")
                    || faults(&d, "fault").iter().any(|f| f == "odometry_lost"),
                "{}",
                d.summary
            ),
            other => panic!("exit {other:?}: {}\n{}", d.summary, d.stderr),
        }
        assert_eq!(
            moving_after, 0,
            "odometry stopped at {stop} s; moving twists came after"
        );
        assert!(d.speed.abs() < 1e-9, "the robot still moves: {}", d.speed);
    }
}

#[test]
fn without_a_robot_the_run_says_what_it_waited_for_and_exits_2() {
    let _serial = one_at_a_time();
    let out = Command::new("unshare")
        .args(["-n", "sh", "-c"])
        .arg(format!(
            "ip link set lo up multicast on && ip route add 224.0.0.0/4 dev lo && \
             exec {} run --robot ros2 --ros-loopback --ros-wait 1 --ros-namespace /nobody \
             examples/short_task.ilmr",
            env!("CARGO_BIN_EXE_ilmrc")
        ))
        .current_dir(support::root())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("no odometry") && stderr.contains("/nobody/odom"),
        "{stderr}"
    );
}

#[test]
fn ros_options_are_refused_for_other_robots_and_bad_names_are_explained() {
    let (code, _, stderr) =
        support::ilmrc(&["run", "--ros-namespace", "/r1", "examples/short_task.ilmr"]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("--ros-namespace is for --robot ros2"),
        "{stderr}"
    );
    let (code, _, stderr) = support::ilmrc(&[
        "run",
        "--robot",
        "ros2",
        "--ros-namespace",
        "robot 1",
        "examples/short_task.ilmr",
    ]);
    assert_eq!(code, 2);
    assert!(stderr.contains("must start with `/`"), "{stderr}");
}
