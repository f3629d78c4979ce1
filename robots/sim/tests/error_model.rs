//! Issue 15's error model, one error at a time on an otherwise ideal robot:
//! each does what its parameter says and nothing when it is zero, the per-run
//! errors are fixed by the seed, and a calibrated run is bit-identical per seed.

mod common;

use common::{DT, circle_fit, open_floor, run, sim, world};
use ilmr_sim::{RobotConfig, SimProfile, Simulator};

fn ideal_moro() -> RobotConfig {
    SimProfile::Ideal.apply(RobotConfig::moro())
}

fn ideal_workpartner() -> RobotConfig {
    SimProfile::Ideal.apply(RobotConfig::workpartner())
}

/// Drives a full-speed circle of curvature `c` at `v` for `seconds`; the true
/// positions after the first 5 s (the actuators have settled by then).
fn circle(
    cfg: RobotConfig,
    seed: u64,
    v: f64,
    c: f64,
    seconds: f64,
) -> (Simulator, Vec<(f64, f64)>) {
    let mut s = sim(cfg, open_floor(), seed);
    s.set_setpoints(v, c).expect("setpoints");
    let mut pts = Vec::new();
    for i in 0..(seconds / DT) as usize {
        run(&mut s, 1);
        if i as f64 * DT > 5.0 {
            let p = s.true_pose();
            pts.push((p.x, p.y));
        }
    }
    (s, pts)
}

#[test]
fn ideal_robot_drives_the_exact_circle_and_knows_where_it_is() {
    let (s, pts) = circle(ideal_moro(), 1, 0.5, 0.5, 30.0);
    let (_, _, r) = circle_fit(&pts);
    // The fit's centroid of a not quite whole circle is off by a little.
    assert!((r - 2.0).abs() < 1e-3, "radius {r}");
    let (t, e) = (s.true_pose(), s.snapshot().pose);
    // Only the pulse counters' quantisation (0.5 mm) separates them.
    assert!((t.x - e.x).hypot(t.y - e.y) < 0.01, "{t:?} vs {e:?}");
}

#[test]
fn steering_dead_time_holds_the_curvature_then_it_ramps() {
    let mut cfg = ideal_moro();
    cfg.actuator.steering_dead_time = 0.2;
    let mut s = sim(cfg.clone(), open_floor(), 1);
    s.set_setpoints(0.3, 0.5).expect("setpoints");
    run(&mut s, 20);
    assert_eq!(s.true_curvature(), 0.0, "nothing within the dead time");
    run(&mut s, 10);
    // Ten steps after the dead time at curinc 1/m per s.
    assert!(
        (s.true_curvature() - 0.1).abs() < 0.011,
        "{}",
        s.true_curvature()
    );
    // The speed has no dead time of its own here.
    assert!(s.true_speed() > 0.1);
}

#[test]
fn steering_play_leaves_the_curvature_short_by_half_the_play() {
    let mut cfg = ideal_moro();
    cfg.actuator.steering_play_deg = 2.0;
    let mut s = sim(cfg.clone(), open_floor(), 1);
    s.set_setpoints(0.3, 0.5).expect("setpoints");
    run(&mut s, 200);
    let wanted = 0.5_f64.atan2(1.0 / 0.8); // steer angle for c = 0.5, wheelbase 0.8
    let short = (wanted - 1f64.to_radians()).tan() / 0.8;
    assert!(
        (s.true_curvature() - short).abs() < 1e-9,
        "{}",
        s.true_curvature()
    );
}

#[test]
fn lateral_slip_widens_a_fast_turn_and_the_wheels_never_count_it() {
    let (exact_run, pts) = circle(ideal_moro(), 1, 1.0, 1.0, 25.0);
    let (_, _, exact) = circle_fit(&pts);
    let mut cfg = ideal_moro();
    cfg.slip.lateral = 0.05;
    let (s, pts) = circle(cfg, 1, 1.0, 1.0, 25.0);
    let (_, _, wide) = circle_fit(&pts);
    // Side slip angle 0.05 * v^2 c = 0.05 rad: the circle grows by about
    // 1 / cos(0.05) - 1, the drift outward of each step.
    assert!(
        wide > exact + 0.0008 && wide < exact * 1.01,
        "{exact} -> {wide}"
    );
    // Distance counted: only what the wheels rolled, as without side slip.
    let counted = s.snapshot().odometry.distance;
    assert_eq!(counted, exact_run.snapshot().odometry.distance);
}

#[test]
fn a_wheelbase_error_changes_the_circle_per_run_and_only_per_seed() {
    let mut cfg = ideal_moro();
    cfg.actuator.wheelbase_sigma = 0.05;
    let radius = |seed| circle_fit(&circle(cfg.clone(), seed, 0.5, 0.5, 30.0).1).2;
    let (a, b, c) = (radius(1), radius(1), radius(2));
    assert_eq!(a, b, "the same seed, the same wheelbase");
    assert!(
        (a - c).abs() > 1e-4,
        "another seed, another wheelbase: {a} {c}"
    );
    assert!((a - 2.0).abs() < 0.5 && (a - 2.0).abs() > 1e-6, "{a}");
}

#[test]
fn odometry_scale_error_is_one_factor_for_the_whole_run() {
    let mut cfg = ideal_moro();
    cfg.odometry.scale_sigma = 0.02;
    let mut s = sim(cfg, open_floor(), 3);
    s.set_setpoints(0.5, 0.0).expect("setpoints");
    let mut ratios = Vec::new();
    for _ in 0..4 {
        run(&mut s, 500);
        ratios.push(s.snapshot().odometry.distance / s.true_pose().x);
    }
    let e = ratios[0] - 1.0;
    assert!(e.abs() > 1e-4 && e.abs() < 0.1, "scale error {e}");
    for r in &ratios {
        // Constant up to the counters' 0.5 mm quantisation.
        assert!((r - ratios[0]).abs() < 2e-4, "{ratios:?}");
    }
}

#[test]
fn a_track_error_turns_the_wheels_heading_but_not_the_gyros() {
    let mut cfg = ideal_workpartner();
    cfg.odometry.track_sigma = 0.05;
    cfg.nav = None; // heading from the wheels alone
    let (s, _) = circle(cfg.clone(), 4, 0.4, 0.2, 20.0);
    let turned = s.true_pose().h - s.snapshot().pose.h;
    assert!(
        ilmr_sim::geometry::wrap_angle(turned).abs() > 0.01,
        "the wheels' heading drifts: {turned}"
    );
    let mut moro = ideal_moro();
    moro.odometry.track_sigma = 0.05;
    let (s, _) = circle(moro, 4, 0.4, 0.2, 20.0);
    let off = ilmr_sim::geometry::wrap_angle(s.true_pose().h - s.snapshot().pose.h);
    assert!(
        off.abs() < 1e-9,
        "MoRo's heading is its ideal gyro's: {off}"
    );
}

#[test]
fn gyro_turn_on_bias_differs_per_seed_and_drifts_the_heading() {
    let mut cfg = ideal_moro();
    if let Some(g) = &mut cfg.gyro {
        g.bias_sigma = 1e-3;
    }
    let drift = |seed| {
        let mut s = sim(cfg.clone(), open_floor(), seed);
        run(&mut s, 1000);
        s.snapshot().gyro.expect("gyro").heading
    };
    let (a, b) = (drift(1), drift(2));
    assert!(a != 0.0 && b != 0.0 && a != b, "{a} {b}");
    // 10 s at a bias of order 1e-3 rad/s.
    assert!(a.abs() < 0.05 && b.abs() < 0.05, "{a} {b}");
}

#[test]
fn correlated_slip_drifts_the_odometry_further_than_white_slip() {
    let spread = |tau: f64| {
        let mut cfg = ideal_moro();
        cfg.slip.sigma = 0.02;
        cfg.slip.mean = 0.05;
        cfg.slip.correlation_time = tau;
        let errs: Vec<f64> = (0..20)
            .map(|seed| {
                let mut s = sim(cfg.clone(), open_floor(), seed);
                s.set_setpoints(0.5, 0.0).expect("setpoints");
                run(&mut s, 1000);
                s.snapshot().odometry.distance - s.true_pose().x
            })
            .collect();
        let m = errs.iter().sum::<f64>() / errs.len() as f64;
        (errs.iter().map(|e| (e - m).powi(2)).sum::<f64>() / errs.len() as f64).sqrt()
    };
    let (white, red) = (spread(0.0), spread(2.0));
    // White slip averages away over 1000 steps; slip that lasts 2 s does not.
    assert!(red > 5.0 * white, "white {white}, correlated {red}");
}

const WALL: &str = r#"
name = "wall"
bounds = { min = [-20.0, -20.0], max = [20.0, 20.0] }
start = { x = 0.0, y = 0.0 }

[[wall]]
id = "w"
from = [6.0, -10.0]
to = [6.0, 10.0]
"#;

const POST: &str = r#"
[[obstacle]]
shape = "box"
center = [3.0, 0.0]
size = [0.4, 0.4]
"#;

#[test]
fn scanner_dropouts_and_mixed_pixels_at_their_rates() {
    let mut cfg = ideal_moro();
    let wall_with_post = format!("{WALL}{POST}");
    let clean = sim(cfg.clone(), world(&wall_with_post), 1)
        .snapshot()
        .scan
        .expect("scan");
    cfg.scanner.dropout = 0.2;
    cfg.scanner.mixed_pixel = 1.0;
    let mut dropped = 0;
    let mut hits = 0;
    let mut between = 0;
    for seed in 0..20 {
        let scan = sim(cfg.clone(), world(&wall_with_post), seed)
            .snapshot()
            .scan
            .expect("scan");
        for (i, (&r, &c)) in scan.ranges.iter().zip(&clean.ranges).enumerate() {
            if c < clean.max_range {
                hits += 1;
                if r == scan.max_range {
                    dropped += 1;
                }
            }
            let edge = [i.wrapping_sub(1), i + 1]
                .iter()
                .filter_map(|&j| clean.ranges.get(j))
                .any(|&n| n - c > 0.1 && n < clean.max_range);
            if r < scan.max_range && (r - c).abs() > 1e-9 {
                assert!(edge, "beam {i} moved off an edge: {c} -> {r}");
                between += 1;
            }
        }
    }
    let rate = dropped as f64 / hits as f64;
    assert!((rate - 0.2).abs() < 0.02, "dropout rate {rate}");
    // The post's two edges give two beams each scan, about 80 % kept.
    assert!(
        (20..=40).contains(&between),
        "{between} mixed pixels in 20 scans"
    );
}

#[test]
fn a_scan_swept_while_driving_at_a_wall_is_skewed() {
    let mut cfg = ideal_moro();
    cfg.scanner.rate_hz = 100.0; // a scan on every step
    cfg.scanner.sweep_time = 0.01;
    let mut s = sim(cfg.clone(), world(WALL), 1);
    s.set_setpoints(1.0, 0.0).expect("setpoints");
    run(&mut s, 300);
    let moving = s.snapshot().scan.expect("scan");
    let truth = s.true_pose();
    let still = ilmr_sim::sensors::cast_scan(s.scene(), &cfg.scanner, truth);
    // Reading 0 (right) was taken 0.01 s earlier, 1 cm further back; the last
    // reading at the end. Beams at +/-45 degrees meet the wall at x = 6. Each
    // eighth of the sweep is cast from the time of its middle beam.
    let per_part = 361usize.div_ceil(ilmr_sim::sensors::SKEW_PARTS);
    let back = |time_of: f64| 1.0 * 0.01 * (1.0 - time_of / 360.0) / 45f64.to_radians().cos();
    for i in [90, 270] {
        let start = i / per_part * per_part;
        let middle = start as f64 + (per_part.min(361 - start) - 1) as f64 / 2.0;
        let d = moving.ranges[i] - still[i];
        assert!(
            (d - back(middle)).abs() < 1e-6,
            "beam {i}: {d} vs {}",
            back(middle)
        );
        // Within an eighth of the sweep of the beam's own time.
        assert!((d - back(i as f64)).abs() < 0.001, "beam {i}");
    }
}

#[test]
fn navigation_fixes_err_by_their_sigma_and_correlate() {
    let mut cfg = ideal_workpartner();
    let stats = |cfg: &RobotConfig| {
        let mut s = sim(cfg.clone(), open_floor(), 2);
        let mut errs = Vec::new();
        let mut last = u64::MAX;
        for _ in 0..40_000 {
            run(&mut s, 1);
            if let Some(f) = s.snapshot().nav_fix
                && f.seq != last
            {
                last = f.seq;
                errs.push(f.pose.x - s.true_pose().x);
            }
        }
        let n = errs.len() as f64;
        let var = errs.iter().map(|e| e * e).sum::<f64>() / n;
        let lag = errs.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / n / var;
        (var.sqrt(), lag)
    };
    let n = cfg.nav.as_mut().expect("nav");
    n.sigma_xy = 0.1;
    n.correlation_time = 0.0;
    let (sigma, lag) = stats(&cfg);
    assert!(
        (sigma - 0.1).abs() < 0.01 && lag.abs() < 0.1,
        "{sigma} {lag}"
    );
    cfg.nav.as_mut().expect("nav").correlation_time = 2.0;
    let (sigma, lag) = stats(&cfg);
    // exp(-0.5 / 2) = 0.78 between fixes 0.5 s apart.
    assert!(
        (sigma - 0.1).abs() < 0.03 && (lag - 0.78).abs() < 0.1,
        "{sigma} {lag}"
    );
}

#[test]
fn a_calibrated_run_is_bit_identical_per_seed() {
    let go = |seed| {
        let mut s = sim(
            SimProfile::Calibrated.apply(RobotConfig::workpartner()),
            common::shipped("yard"),
            seed,
        );
        let mut out = Vec::new();
        for i in 0..1500 {
            let c = if i < 700 { 0.2 } else { -0.25 };
            s.set_setpoints(0.5, c).expect("setpoints");
            run(&mut s, 1);
            let (p, e) = (s.true_pose(), s.snapshot());
            out.push((
                p.x.to_bits(),
                p.y.to_bits(),
                p.h.to_bits(),
                e.pose.x.to_bits(),
            ));
            if let Some(scan) = &e.scan {
                out.push((
                    scan.seq,
                    scan.ranges[100].to_bits(),
                    scan.ranges[260].to_bits(),
                    0,
                ));
            }
        }
        out
    };
    assert!(go(7) == go(7), "seed 7 twice differs");
    assert!(go(7) != go(8), "seeds 7 and 8 agree");
}

#[test]
fn the_error_parameters_are_checked() {
    let mut cfg = RobotConfig::moro();
    cfg.actuator.steering_dead_time = 2.0;
    assert!(Simulator::new(cfg, open_floor(), 1).is_err());
    let mut cfg = RobotConfig::moro();
    cfg.scanner.dropout = 1.5;
    let e = Simulator::new(cfg, open_floor(), 1)
        .err()
        .map(|e| e.to_string());
    assert!(e.is_some_and(|e| e.contains("scanner.dropout")));
    let mut cfg = RobotConfig::moro();
    cfg.slip.lateral = f64::NAN;
    assert!(Simulator::new(cfg, open_floor(), 1).is_err());
}
