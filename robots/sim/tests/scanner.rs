mod common;

use common::{run, sim};
use ilmr_sim::sensors::cast_scan;
use ilmr_sim::{Pose, RobotConfig};

/// A wall across the robot's way at x = 5 (face at 4.9) with a 1 m door
/// centred on the robot's line.
const DOOR_AHEAD: &str = r#"
name = "door ahead"
bounds = { min = [-20.0, -20.0], max = [20.0, 20.0] }
start = { x = 0.0, y = 0.0 }

[[wall]]
id = "w"
from = [5.0, -10.0]
to = [5.0, 10.0]
thickness = 0.2

[[door]]
wall = "w"
at = 10.0
width = 1.0
"#;

#[test]
fn scanner_sees_the_wall_at_its_range_and_the_door_gap_as_long_ranges() {
    let mut cfg = RobotConfig::moro();
    cfg.scanner.noise_sigma = 0.0;
    let w = common::world(DOOR_AHEAD);
    let s = sim(cfg.clone(), w.clone(), 1);
    let scan = s
        .snapshot()
        .scan
        .unwrap_or_else(|| panic!("a scan at t = 0"));
    assert_eq!(scan.ranges.len(), 361);
    assert!((scan.angle_increment.to_degrees() - 0.5).abs() < 1e-12);
    // Scanner origin 0.85 m ahead; the wall face is 4.05 m from it.
    let along = 4.9 - 0.85;
    for i in 0..361 {
        let b = scan.bearing(i);
        let r = scan.ranges[i];
        // Where this beam crosses the wall's near and far faces.
        let (y_near, y_far) = (along * b.tan(), (along + 0.2) * b.tan());
        if b.cos() > 0.0 && y_near.abs() < 0.5 && y_far.abs() < 0.5 {
            assert_eq!(r, scan.max_range, "beam {i} goes out through the door");
        } else if b.cos() > 1e-9 && y_near.abs() > 0.5 && y_near.abs() < 10.0 {
            assert!(
                (r - along / b.cos()).abs() < 1e-9,
                "beam {i}: {r} vs {}",
                along / b.cos()
            );
        }
    }
    assert_eq!(scan.ranges[180], scan.max_range);
    assert!((scan.ranges[200] - along / 10f64.to_radians().cos()).abs() < 1e-9);
    // Beams straight out to the sides find nothing in the open.
    assert_eq!(scan.ranges[0], scan.max_range);
    assert_eq!(scan.ranges[360], scan.max_range);
    // The free function gives the same.
    assert_eq!(
        cast_scan(s.scene(), &cfg.scanner, Pose::new(0.0, 0.0, 0.0)),
        scan.ranges
    );
}

#[test]
fn scanner_noise_is_seeded_and_small() {
    let w = common::world(DOOR_AHEAD);
    let a = sim(RobotConfig::moro(), w.clone(), 1).snapshot().scan;
    let b = sim(RobotConfig::moro(), w.clone(), 1).snapshot().scan;
    let c = sim(RobotConfig::moro(), w, 2).snapshot().scan;
    assert_eq!(a, b);
    assert_ne!(a, c);
    let r = a.map_or(0.0, |s| s.ranges[200]);
    assert!((r - 4.05 / 10f64.to_radians().cos()).abs() < 0.05);
}

#[test]
fn scans_arrive_at_the_configured_rate_from_the_true_pose() {
    let mut s = sim(RobotConfig::moro(), common::open_floor(), 1);
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..200 {
        run(&mut s, 1);
        let scan = s.snapshot().scan;
        if let Some(sc) = scan
            && Some(sc.seq) != last
        {
            last = Some(sc.seq);
            times.push(sc.time);
        }
    }
    assert_eq!(times, vec![0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0]);

    let mut cfg = RobotConfig::moro();
    cfg.scanner.rate_hz = 2.0;
    let mut s = sim(cfg, common::open_floor(), 1);
    run(&mut s, 100);
    assert_eq!(
        s.snapshot().scan.map(|sc| (sc.seq, sc.time)),
        Some((2, 1.0))
    );
    s.faults.scanner_dropout = true;
    run(&mut s, 100);
    assert_eq!(
        s.snapshot().scan.map(|sc| sc.seq),
        Some(2),
        "no new scans during a dropout"
    );
}

#[test]
fn office_scan_sees_the_bench_on_the_left_and_the_lab_wall_on_the_right() {
    let mut cfg = RobotConfig::moro();
    cfg.scanner.noise_sigma = 0.0;
    let s = sim(cfg, common::shipped("office"), 1);
    let scan = s.snapshot().scan.unwrap_or_else(|| panic!("scan"));
    // Scanner at (4.85, 6.0): bench face at y = 7.1, lab south wall face at y = 4.075.
    assert!(
        (scan.ranges[360] - 1.1).abs() < 1e-9,
        "{}",
        scan.ranges[360]
    );
    assert!((scan.ranges[0] - 1.925).abs() < 1e-9, "{}", scan.ranges[0]);
    // Ahead: the cabinet or the lab's east wall, well inside the room.
    assert!(
        scan.ranges[180] > 6.0 && scan.ranges[180] < 8.0,
        "{}",
        scan.ranges[180]
    );
}
