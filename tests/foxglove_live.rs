//! `ilmrc run --foxglove`: the live view, watched by clients this project did not write
//! (Foxglove's `@foxglove/ws-protocol` with `protobufjs`, in `tests/foxglove/`, which
//! `tests/all.sh` installs with `npm ci`), and by a viewer that stops reading.

mod support;

use std::io::{BufRead, BufReader, Read};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("ilmr-foxglove-{}-{name}", std::process::id()))
}

/// A realtime run with the live view on a free loopback port: the child and the
/// view's address, read from its stderr (the rest of stderr is kept by a thread).
fn live_run(args: &[&str]) -> (Child, String, std::thread::JoinHandle<String>) {
    let mut all = vec!["run", "--realtime", "--foxglove=127.0.0.1:0"];
    all.extend_from_slice(args);
    viewed(&all)
}

/// `ilmrc ARGS` (which include `--foxglove=127.0.0.1:0`): the child and the view's
/// address, from the first line of its stderr.
fn viewed(args: &[&str]) -> (Child, String, std::thread::JoinHandle<String>) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(args)
        .current_dir(support::root())
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("ilmrc runs");
    let mut err = BufReader::new(child.stderr.take().expect("stderr"));
    let mut line = String::new();
    err.read_line(&mut line).expect("stderr line");
    let url = line
        .split_whitespace()
        .find(|w| w.starts_with("ws://"))
        .unwrap_or_else(|| panic!("no address in `{line}`"))
        .to_string();
    let rest = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = err.read_to_string(&mut text);
        text
    });
    (child, url, rest)
}

/// Waits for the run, at most `limit` (a guard against a hang, not a timing).
fn finish(mut child: Child, limit: Duration) -> (i32, String) {
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("wait") {
            let mut out = String::new();
            if let Some(mut o) = child.stdout.take() {
                let _ = o.read_to_string(&mut out);
            }
            return (status.code().unwrap_or(-1), out);
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("ilmrc did not end within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn trace_poses(path: &PathBuf) -> Vec<(f64, f64, f64)> {
    std::fs::read_to_string(path)
        .expect("trace")
        .lines()
        .map(|l| serde_json::from_str::<Value>(l).expect("JSON"))
        .filter(|v| v["event"] == "pose")
        .map(|v| {
            let n = |k: &str| v[k].as_f64().expect("a number");
            (n("t"), n("x"), n("y"))
        })
        .collect()
}

#[test]
fn foxgloves_client_sees_the_channels_and_the_poses_of_the_trace() {
    let trace = scratch("watched.jsonl");
    let (child, url, stderr) = live_run(&[
        "--max-time",
        "4",
        "--trace",
        trace.to_str().unwrap(),
        "examples/short_task.ilmr",
    ]);
    let watch = Command::new("node")
        .arg(support::root().join("tests/foxglove/watch.mjs"))
        .args([&url, "20", "/pose", "/world", "/commands"])
        .output()
        .expect("node runs");
    let (code, summary) = finish(child, Duration::from_secs(60));
    let stderr = stderr.join().unwrap_or_default();
    assert_eq!(code, 5, "stopped at --max-time: {summary}{stderr}");
    let seen: Value = serde_json::from_slice(&watch.stdout).unwrap_or_else(|e| {
        panic!(
            "watch.mjs printed no JSON ({e}); tests/all.sh installs its packages (npm ci):\n{}",
            String::from_utf8_lossy(&watch.stderr)
        )
    });
    // What a stock `@foxglove/ws-protocol` client offers: the protocol's first name.
    assert_eq!(seen["protocol"], "foxglove.websocket.v1");
    assert_eq!(seen["serverInfo"]["name"], "ilmrc");
    assert_eq!(
        seen["serverInfo"]["capabilities"],
        serde_json::json!(["time"])
    );
    let mut channels: Vec<String> = seen["channels"]
        .as_array()
        .expect("channels")
        .iter()
        .map(|c| {
            format!(
                "{} {}",
                c["topic"].as_str().unwrap(),
                c["schemaName"].as_str().unwrap()
            )
        })
        .collect();
    channels.sort();
    assert_eq!(
        channels,
        [
            "/commands foxglove.Log",
            "/motion motion.Motion",
            "/paths foxglove.SceneUpdate",
            "/pose foxglove.PoseInFrame",
            "/scan foxglove.LaserScan",
            "/tf foxglove.FrameTransforms",
            "/trajectory foxglove.SceneUpdate",
            "/variables variable.Variable",
            "/world foxglove.SceneUpdate",
        ]
    );
    // The world was published before the viewer came: it is sent again on subscribing.
    assert_eq!(seen["messages"]["/world"][0]["entities"][0], "office");

    let traced = trace_poses(&trace);
    let _ = std::fs::remove_file(&trace);
    let poses = seen["messages"]["/pose"].as_array().expect("poses");
    assert!(poses.len() >= 10, "{} poses seen", poses.len());
    for p in poses {
        let (t, x, y) = (
            p["logTime"].as_f64().unwrap(),
            p["x"].as_f64().unwrap(),
            p["y"].as_f64().unwrap(),
        );
        assert_eq!(p["frame"], "world");
        let same = traced
            .iter()
            .find(|q| (q.0 - t).abs() < 1e-6)
            .unwrap_or_else(|| panic!("no traced pose at t={t}"));
        // The trace gives four decimals.
        assert!(
            (same.1 - x).abs() < 6e-5 && (same.2 - y).abs() < 6e-5,
            "live ({t}, {x}, {y}), trace {same:?}"
        );
    }
    let last = poses.last().unwrap()["logTime"].as_f64().unwrap();
    assert!(last > 3.9, "the viewer saw the run to its end ({last} s)");
    let time = seen["time"].as_f64().expect("the server's clock");
    assert!(
        (time * 1e-9 - 4.0).abs() < 0.02,
        "sim time as the clock: {time}"
    );
    let commands = seen["messages"]["/commands"].as_array().expect("logs");
    let end = commands.last().expect("the run's end is told");
    assert_eq!(
        end["message"],
        "max-time: stopped at --max-time 4, 3 statement(s) live"
    );
}

/// A viewer that subscribes to everything and never reads again
/// (`tests/foxglove/stalled_viewer.py`), in a network namespace of its own whose TCP
/// send buffers are 8 KB at most: the server's socket to it fills within a second and
/// its backlog in the SDK overflows, which must not slow the run's tick.
#[test]
fn a_viewer_that_stops_reading_does_not_slow_the_run() {
    let ilmrc = env!("CARGO_BIN_EXE_ilmrc");
    let viewer = support::root().join("tests/foxglove/stalled_viewer.py");
    let script = format!(
        "ip link set lo up && sysctl -qw net.ipv4.tcp_wmem='4096 4096 8192' && \
         exec python3 {} {ilmrc} --realtime --max-time 6 --pose-every 1 examples/way_out.ilmr",
        viewer.display()
    );
    let out = Command::new("unshare")
        .args(["-n", "bash", "-c", &script])
        .current_dir(support::root())
        .env("NO_COLOR", "1")
        .output()
        .expect("unshare runs");
    let seen: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "stalled_viewer.py printed no JSON ({e}); it needs root or CAP_SYS_ADMIN (unshare -n):\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    let summary = seen["stdout"].as_str().unwrap();
    assert_eq!(seen["exit"], 5, "{seen:#}");
    assert!(summary.contains("overruns        0"), "{summary}");
    // The server's socket to the viewer was full: the viewer really stalled it.
    let queued = seen["send_queue"].as_u64().unwrap();
    assert!(
        queued >= 4096,
        "send queue {queued} bytes: the viewer never stalled"
    );
    // 6 s of realtime from before subscribing, and at most STOP_WAIT (1 s) spent on a
    // viewer that holds its connection open.
    let took = seen["took"].as_f64().unwrap();
    assert!(took < 10.0, "the run took {took} s with a stalled viewer");
    // What the SDK dropped for it is counted, and said: all it was published but what
    // its backlog (1,024) and the two sockets' buffers (at most 12 KB, a message being
    // 30 bytes or more) held.
    let stderr = seen["stderr"].as_str().unwrap();
    let count = |after: &str| -> u64 {
        stderr
            .split(after)
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("no `{after}` count:\n{stderr}"))
    };
    let (missed, of) = (count("viewer 1 fell behind the run: "), count(" of the "));
    assert!(missed > 0 && missed <= of, "{stderr}");
    assert!(
        missed + 1024 + 12 * 1024 / 30 >= of,
        "the viewer missed only {missed} of {of}:\n{stderr}"
    );
}

/// Foxglove's client, for `seconds`, on `topics`, offering the SDK's name for the
/// protocol.
fn watch(url: &str, seconds: u32, topics: &[&str]) -> Value {
    let out = Command::new("node")
        .env("FOXGLOVE_PROTOCOLS", "foxglove.sdk.v1")
        .arg(support::root().join("tests/foxglove/watch.mjs"))
        .arg(url)
        .arg(seconds.to_string())
        .args(topics)
        .output()
        .expect("node runs");
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "watch.mjs printed no JSON ({e}):\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    })
}

/// `serve` (and so `shell`, which runs the same engine) publishes its robot: the task
/// it was started with drives, and a viewer sees it move over the world.
#[test]
fn serve_shows_its_robot_live() {
    let (mut child, url, _stderr) = viewed(&[
        "serve",
        "--no-tls",
        "--listen",
        "127.0.0.1:0",
        "--foxglove=127.0.0.1:0",
        "--task",
        "examples/short_task.ilmr",
    ]);
    let seen = watch(&url, 3, &["/pose", "/world", "/scan"]);
    let _ = child.kill();
    let _ = child.wait();
    assert_eq!(seen["protocol"], "foxglove.sdk.v1");
    assert_eq!(seen["messages"]["/world"][0]["entities"][0], "office");
    let poses = seen["messages"]["/pose"].as_array().expect("poses");
    assert!(poses.len() >= 10, "{} poses in 3 s at 10 Hz", poses.len());
    let x = |p: &Value| p["x"].as_f64().unwrap();
    assert!(
        x(poses.last().unwrap()) > x(&poses[0]) + 0.2,
        "the robot drives: {poses:?}"
    );
    assert!(!seen["messages"]["/scan"].as_array().unwrap().is_empty());
}

#[test]
fn the_shell_takes_the_live_view_too() {
    let (code, out, err) = support::ilmrc(&["shell", "--foxglove=127.0.0.1:0"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        err.starts_with("foxglove: live view on ws://127.0.0.1:"),
        "{err}"
    );
}

/// `sim --ros2` (the simulated robot as a ROS 2 robot, no VM) publishes its true pose
/// and scans. DDS runs in a network namespace of its own, as every DDS test here does,
/// and the viewer with it.
#[test]
fn sim_shows_its_robot_live() {
    let ilmrc = env!("CARGO_BIN_EXE_ilmrc");
    let watcher = support::root().join("tests/foxglove/watch.mjs");
    let script = format!(
        "ip link set lo up multicast on && ip route add 224.0.0.0/4 dev lo && \
         ({ilmrc} sim --ros2 --duration 3 --foxglove=127.0.0.1:8765 >/dev/null 2>&1 &) && \
         for i in $(seq 100); do (echo > /dev/tcp/127.0.0.1/8765) 2>/dev/null && break; sleep 0.05; done && \
         exec node {} ws://127.0.0.1:8765 10 /pose /scan /world",
        watcher.display()
    );
    let out = Command::new("unshare")
        .args(["-n", "bash", "-c", &script])
        .current_dir(support::root())
        .output()
        .expect("unshare runs");
    let seen: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "no JSON from the watcher ({e}); it needs root (unshare -n):\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    assert_eq!(seen["messages"]["/world"][0]["entities"][0], "office");
    let poses = seen["messages"]["/pose"].as_array().expect("poses");
    assert!(poses.len() >= 10, "{} poses", poses.len());
    assert!(!seen["messages"]["/scan"].as_array().unwrap().is_empty());
}

#[test]
fn the_live_view_listens_on_loopback_only() {
    let (code, out, err) = support::ilmrc(&[
        "run",
        "--foxglove=0.0.0.0:8765",
        "--max-time",
        "1",
        "examples/short_task.ilmr",
    ]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.contains("listens on loopback only") && err.contains("ssh -L"),
        "{err}"
    );
    let (code, _, err) = support::ilmrc(&[
        "run",
        "--foxglove=nowhere",
        "--max-time",
        "1",
        "examples/short_task.ilmr",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("is not HOST:PORT"), "{err}");
}
