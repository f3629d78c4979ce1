//! One 10 ms step (with a scan due) and one full 361-beam scan, in the office.

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
