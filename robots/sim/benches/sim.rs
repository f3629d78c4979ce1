//! One 10 ms step (with a scan due) and one full 361-beam scan, in the office and
//! among 100,000 walls. The whole run of a task (VM and simulator) is the
//! experiments' bench, above both.

use ilmr_sim::sensors::cast_scan;
use ilmr_sim::{Pose, RobotConfig, Simulator};

fn main() {
    divan::main();
}

fn office() -> ilmr_sim::World {
    match ilmr_sim::world::shipped("office") {
        Some(Ok(w)) => w,
        _ => panic!("the office world ships with the crate"),
    }
}

#[divan::bench]
fn scan_361_beams_office(b: divan::Bencher) {
    let world = office();
    let scene = world.scene();
    let cfg = RobotConfig::moro().scanner;
    // Mid-corridor, looking along it: the longest beams.
    let pose = Pose::new(6.0, 12.5, 0.0);
    b.bench(|| cast_scan(divan::black_box(&scene), &cfg, divan::black_box(pose)));
}

#[divan::bench]
fn step_10ms_with_scan_office(b: divan::Bencher) {
    let mut cfg = RobotConfig::moro();
    // A scan every step, so each measured step includes one.
    cfg.scanner.rate_hz = 100.0;
    b.with_inputs(|| {
        let mut s = match Simulator::new(cfg.clone(), office(), 1) {
            Ok(s) => s,
            Err(e) => panic!("{e}"),
        };
        let _ = s.set_setpoints(0.3, 0.2);
        s
    })
    .bench_local_refs(|s| s.step(0.01));
}

/// A 10 ms step with a scan, half a second into a 0.3 m/s turn, with `profile`'s
/// errors: `calibrated` casts the scan swept while moving (in `SKEW_PARTS` parts,
/// each through a fan of its own) and adds dropouts and mixed pixels.
fn moving_step(b: divan::Bencher, profile: ilmr_sim::SimProfile) {
    let mut cfg = profile.apply(RobotConfig::moro());
    // A scan every step; a sweep cannot outlast the 10 ms between scans.
    cfg.scanner.rate_hz = 100.0;
    cfg.scanner.sweep_time = cfg.scanner.sweep_time.min(0.01);
    b.with_inputs(|| {
        let mut s = match Simulator::new(cfg.clone(), office(), 1) {
            Ok(s) => s,
            Err(e) => panic!("{e}"),
        };
        let _ = s.set_setpoints(0.3, 0.2);
        for _ in 0..50 {
            let _ = s.step(0.01);
        }
        s
    })
    .bench_local_refs(|s| s.step(0.01));
}

#[divan::bench]
fn step_10ms_moving_with_scan_office_basic(b: divan::Bencher) {
    moving_step(b, ilmr_sim::SimProfile::Basic);
}

#[divan::bench]
fn step_10ms_moving_with_scan_office_calibrated(b: divan::Bencher) {
    moving_step(b, ilmr_sim::SimProfile::Calibrated);
}

/// The most walls a world file admits (`MAX_WALLS`), 0.8 m each, spread over
/// a 1 km site round a clear patch where the robot stands: what a tick costs
/// when the world is huge but the robot's surroundings are ordinary.
fn many_walls() -> ilmr_sim::World {
    let n = ilmr_sim::world::limits::MAX_WALLS;
    let mut text = String::from(
        "name = \"many\"\nbounds = { min = [0.0, 0.0], max = [1000.0, 1000.0] }\nstart = { x = 8.0, y = 5.0 }\n",
    );
    let mut rng = ilmr_sim::rng::Rng::new(1);
    let mut made = 0;
    while made < n {
        let (x, y) = (999.0 * rng.uniform(), 999.0 * rng.uniform());
        if x < 40.0 && y < 30.0 {
            continue;
        }
        let a = std::f64::consts::TAU * rng.uniform();
        let (x2, y2) = (
            (x + 0.8 * a.cos()).clamp(0.0, 1000.0),
            (y + 0.8 * a.sin()).clamp(0.0, 1000.0),
        );
        text.push_str(&format!("[[wall]]\nfrom = [{x}, {y}]\nto = [{x2}, {y2}]\n"));
        made += 1;
    }
    match ilmr_sim::World::from_toml(&text, "many") {
        Ok(w) => w,
        Err(e) => panic!("{e}"),
    }
}

#[divan::bench(sample_count = 20)]
fn step_10ms_with_scan_100000_walls(b: divan::Bencher) {
    let world = many_walls();
    let mut cfg = RobotConfig::moro();
    cfg.scanner.rate_hz = 100.0;
    b.with_inputs(|| {
        let mut s = match Simulator::new(cfg.clone(), world.clone(), 1) {
            Ok(s) => s,
            Err(e) => panic!("{e}"),
        };
        let _ = s.set_setpoints(0.3, 0.2);
        s
    })
    .bench_local_refs(|s| s.step(0.01));
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn load_100000_walls(b: divan::Bencher) {
    let world = many_walls();
    b.bench(|| world.scene());
}

#[divan::bench]
fn step_10ms_without_scan_office(b: divan::Bencher) {
    let mut cfg = RobotConfig::moro();
    cfg.scanner.rate_hz = 0.001;
    b.with_inputs(|| {
        let mut s = match Simulator::new(cfg.clone(), office(), 1) {
            Ok(s) => s,
            Err(e) => panic!("{e}"),
        };
        let _ = s.set_setpoints(0.3, 0.2);
        s.step(0.01).ok();
        s
    })
    .bench_local_refs(|s| s.step(0.01));
}
