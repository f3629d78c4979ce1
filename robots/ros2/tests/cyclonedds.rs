//! The ROS 2 messages against a DDS implementation this project did not write: Eclipse
//! Cyclone DDS (its Python binding, `pip install cyclonedds`, which serialises with
//! Cyclone's C library). For each message Cyclone must write the very bytes we write,
//! read ours back to the same values, and we must read Cyclone's. CI installs it
//! (`.ci/run`); without it this test fails rather than passing unchecked.

use std::io::Write;
use std::process::{Command, Stdio};

use ilmr_ros2::msg::*;
use ilmr_ros2::{RosMessage, decode, encode};
use serde_json::{Value, json};

fn header(sec: i32, frame: &str) -> Header {
    Header {
        stamp: Time {
            sec,
            nanosec: 250_000_000,
        },
        frame_id: frame.into(),
    }
}

fn twist() -> Twist {
    Twist {
        linear: Vector3 {
            x: 0.4,
            y: 0.0,
            z: 0.0,
        },
        angular: Vector3 {
            x: 0.0,
            y: 0.0,
            z: -0.533,
        },
    }
}

fn odometry() -> Odometry {
    let mut covariance = Covariance::default();
    for (i, v) in covariance.0.iter_mut().enumerate() {
        *v = i as f64 / 100.0;
    }
    Odometry {
        header: header(1_700_000_000, "odom"),
        // An odd length, so that what follows needs padding to align.
        child_frame_id: "base".into(),
        pose: PoseWithCovariance {
            pose: Pose {
                position: Point {
                    x: 4.0,
                    y: 6.25,
                    z: 0.0,
                },
                orientation: Quaternion::from_yaw(1.2),
            },
            covariance,
        },
        twist: TwistWithCovariance {
            twist: twist(),
            covariance,
        },
    }
}

fn scan() -> LaserScan {
    LaserScan {
        header: header(12, "laser"),
        angle_min: -1.5707964,
        angle_max: 1.5707964,
        angle_increment: 0.017453292,
        time_increment: 0.0,
        scan_time: 0.1,
        range_min: 0.05,
        range_max: 30.0,
        ranges: (0..181).map(|i| 1.0 + i as f32 * 0.01).collect(),
        intensities: vec![],
    }
}

fn battery() -> BatteryState {
    BatteryState {
        header: header(3, "b"),
        voltage: 24.5,
        temperature: 31.0,
        current: -2.5,
        charge: 10.0,
        capacity: 20.0,
        design_capacity: 22.0,
        percentage: 0.5,
        power_supply_status: 2,
        power_supply_health: 1,
        power_supply_technology: 3,
        present: true,
        cell_voltage: vec![3.5, 3.5, 3.25],
        cell_temperature: vec![],
        location: "rear".into(),
        serial_number: "MR-1".into(),
    }
}

fn tf() -> TFMessage {
    let at = |frame: &str, child: &str, x: f64, yaw: f64| TransformStamped {
        header: header(5, frame),
        child_frame_id: child.into(),
        transform: Transform {
            translation: Vector3 { x, y: -1.5, z: 0.0 },
            rotation: Quaternion::from_yaw(yaw),
        },
    };
    TFMessage {
        transforms: vec![
            at("odom", "base_link", 2.0, 0.3),
            at("base_link", "laser", 0.45, 0.0),
        ],
    }
}

fn clock() -> Clock {
    Clock {
        clock: Time {
            sec: 12,
            nanosec: 340_000_000,
        },
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

fn unhex(text: &str) -> Vec<u8> {
    (0..text.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&text[i..i + 2], 16).unwrap())
        .collect()
}

/// JSON values alike, numbers to the last bit or two of a double: serde_json parses
/// decimals without exact rounding, and Python prints them with it.
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            (x - y).abs() <= 1e-15 * x.abs().max(1.0)
        }
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(x, y)| same(x, y))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        _ => a == b,
    }
}

fn request<M: RosMessage>(message: &M) -> Value {
    json!({
        "type": M::DDS_TYPE_NAME,
        "value": serde_json::to_value(message).unwrap(),
        "rust": hex(&encode(message)),
    })
}

#[test]
fn cyclone_dds_writes_and_reads_what_we_write_and_read() {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/python/cyclone_cdr.py");
    let requests = [
        request(&twist()),
        request(&odometry()),
        request(&scan()),
        request(&battery()),
        request(&tf()),
        request(&clock()),
    ];
    let mut child = Command::new("python3")
        .arg(script)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("python3 runs");
    {
        let mut stdin = child.stdin.take().unwrap();
        for r in &requests {
            writeln!(stdin, "{r}").unwrap();
        }
    }
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "Cyclone DDS's Python binding failed (CI installs it with `pip install cyclonedds`):\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let answers: Vec<Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(answers.len(), requests.len());
    for (r, a) in requests.iter().zip(&answers) {
        let name = r["type"].as_str().unwrap();
        assert_eq!(
            a["cyclone"], r["rust"],
            "{name}: Cyclone writes other bytes"
        );
        assert!(
            same(&a["decoded"], &r["value"]),
            "{name}: Cyclone reads other values:\n{}\n{}",
            a["decoded"],
            r["value"]
        );
    }
    let ours = |i: usize| unhex(answers[i]["cyclone"].as_str().unwrap());
    assert_eq!(decode::<Twist>(&ours(0)).unwrap(), twist());
    assert_eq!(decode::<Odometry>(&ours(1)).unwrap(), odometry());
    assert_eq!(decode::<LaserScan>(&ours(2)).unwrap(), scan());
    assert_eq!(decode::<BatteryState>(&ours(3)).unwrap(), battery());
    assert_eq!(decode::<TFMessage>(&ours(4)).unwrap(), tf());
    assert_eq!(decode::<Clock>(&ours(5)).unwrap(), clock());
}
