//! Helpers shared by the integration tests.
#![allow(dead_code)]

use ilmr_sim::{RobotConfig, Simulator, World};

pub const DT: f64 = 0.01;

pub fn world(text: &str) -> World {
    match World::from_toml(text, "<test>") {
        Ok(w) => w,
        Err(e) => panic!("test world does not load: {e}"),
    }
}

pub fn sim(cfg: RobotConfig, w: World, seed: u64) -> Simulator {
    match Simulator::new(cfg, w, seed) {
        Ok(s) => s,
        Err(e) => panic!("simulator does not start: {e}"),
    }
}

pub fn shipped(name: &str) -> World {
    match ilmr_sim::world::shipped(name) {
        Some(Ok(w)) => w,
        Some(Err(e)) => panic!("{e}"),
        None => panic!("no shipped world {name}"),
    }
}

/// Steps `n` times at the VM's 100 Hz.
pub fn run(sim: &mut Simulator, n: usize) {
    for _ in 0..n {
        if let Err(e) = sim.step(DT) {
            panic!("step failed: {e}");
        }
    }
}

pub fn open_floor() -> World {
    world(
        r#"
name = "open"
bounds = { min = [-60.0, -60.0], max = [60.0, 60.0] }
start = { x = 0.0, y = 0.0, heading = 0.0 }
"#,
    )
}

/// Centre and mean radius of points spread evenly round a circle.
pub fn circle_fit(points: &[(f64, f64)]) -> (f64, f64, f64) {
    let n = points.len() as f64;
    let cx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let cy = points.iter().map(|p| p.1).sum::<f64>() / n;
    let r = points
        .iter()
        .map(|p| (p.0 - cx).hypot(p.1 - cy))
        .sum::<f64>()
        / n;
    (cx, cy, r)
}
