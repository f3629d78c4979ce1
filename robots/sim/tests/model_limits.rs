//! A robot model's numbers reach the simulator bounded (issue 12): a scanner
//! of a hundred million readings is refused on load, and a configuration
//! that asks for one anyway does not start.

mod common;

use ilmr_model::{MAX_READINGS, RobotModel};
use ilmr_sim::{RobotConfig, RobotKind, Simulator, config_from_model};

#[test]
fn a_hundred_million_beam_scanner_never_reaches_the_simulator() {
    let ini = include_str!("../../model/models/moro.ini")
        .replace("scanner 1 0 30000 361", "scanner 1 0 30000 100000000");
    let (model, warnings) = RobotModel::parse(&ini, "moro");
    assert!(
        warnings.iter().any(|w| w
            .message
            .starts_with("scanner readings: 100000000 out of range")),
        "{warnings:?}"
    );
    let cfg = config_from_model(&model, RobotKind::Moro);
    assert!(cfg.scanner.readings <= MAX_READINGS as usize);
    let mut sim = common::sim(cfg, common::open_floor(), 1);
    common::run(&mut sim, 50);
    assert!(sim.snapshot().scan.is_some());
}

#[test]
fn a_configuration_past_the_limit_does_not_start() {
    let mut cfg = RobotConfig::moro();
    cfg.scanner.readings = 100_000_000;
    let err = Simulator::new(cfg, common::open_floor(), 1)
        .err()
        .map(|e| e.to_string());
    assert!(
        err.as_deref()
            .is_some_and(|e| e.contains("scanner.readings must be 2 to 4096")),
        "{err:?}"
    );
}
