//! A kinematic robot for closed-loop tests: a unicycle whose curvature is
//! steered at a limited rate through a short dead time, driven by the
//! controller and speed profile of this crate. Deliberately small: the real
//! simulator lives in another crate.

#![allow(dead_code)]

use ilmr_motion::controller::{self, ControlInput, ControllerParams, SpeedLimits};
use ilmr_motion::{Path, Pose};
use std::collections::VecDeque;

#[derive(Clone, Copy, Debug)]
pub struct Robot {
    pub max_curvature: f64,
    /// Δc, 1/m/s.
    pub curinc: f64,
    pub limits: SpeedLimits,
    /// Control cycles between a steering command and its effect.
    pub dead_ticks: usize,
}

/// MoRo: turns within a 1.5 m diameter (section 5.2), so 1/0.75 1/m.
/// Its `curinc` and acceleration are not given; these are plausible for a
/// small AGV with a steered front wheel.
pub const MORO: Robot = Robot {
    max_curvature: 1.0 / 0.75,
    curinc: 1.0,
    limits: SpeedLimits {
        max_accel: 0.5,
        max_decel: 0.5,
    },
    dead_ticks: 5,
};

/// Workpartner: maximum curvature 0.25 1/m (the guide), `curinc 0.8`
/// (ROBO.INI, Figure 39); a 230 kg machine accelerates gently.
pub const WORKPARTNER: Robot = Robot {
    max_curvature: 0.25,
    curinc: 0.8,
    limits: SpeedLimits {
        max_accel: 0.3,
        max_decel: 0.3,
    },
    dead_ticks: 10,
};

pub const DT: f64 = 0.01;

#[derive(Clone, Debug)]
pub struct Run {
    pub trace: Vec<Pose>,
    pub speeds: Vec<f64>,
    pub curvatures: Vec<f64>,
    pub max_deviation: f64,
    pub clipped_ticks: usize,
    pub arrived: bool,
}

pub struct Sim {
    pub robot: Robot,
    pub params: ControllerParams,
    pub pose: Pose,
    /// Curvature the wheels have now.
    pub curvature: f64,
    /// Curvature commanded last cycle: the controller's c_now. The wheels
    /// reach it a dead time later, so feeding back the measured curvature
    /// would slow the controller's ramp by the dead time.
    pub commanded: f64,
    pub speed: f64,
    pending: VecDeque<f64>,
}

impl Sim {
    pub fn new(robot: Robot, pose: Pose) -> Self {
        Sim {
            robot,
            params: ControllerParams::new(robot.max_curvature, robot.curinc, DT),
            pose,
            curvature: 0.0,
            commanded: 0.0,
            speed: 0.0,
            pending: VecDeque::from(vec![0.0; robot.dead_ticks]),
        }
    }

    /// One control cycle on `path` from index `k`; returns the new k.
    pub fn tick(&mut self, path: &Path, k: usize, target: f64, stop: Option<f64>) -> (usize, bool) {
        let out = controller::step(
            &self.params,
            &ControlInput {
                path,
                k,
                pose: self.pose,
                curvature: self.commanded,
                speed: self.speed,
            },
        )
        .expect("valid controller input");
        self.commanded = out.curvature;
        self.pending.push_back(out.curvature);
        let wanted = self.pending.pop_front().unwrap_or(out.curvature);
        let step = self.robot.curinc * DT;
        self.curvature += (wanted - self.curvature).clamp(-step, step);
        let dir = path.points()[out.k].direction.sign();
        self.speed = dir * controller::next_speed(self.speed, target, stop, &self.robot.limits, DT);
        self.pose = self.pose.advance(self.speed * DT, self.curvature);
        (out.k, out.clipped)
    }

    /// Drives `path` to its end at `target` speed, stopping there.
    pub fn drive(&mut self, path: &Path, target: f64) -> Run {
        let mut run = Run {
            trace: vec![],
            speeds: vec![],
            curvatures: vec![],
            max_deviation: 0.0,
            clipped_ticks: 0,
            arrived: false,
        };
        let mut k = 0;
        let limit = (60.0 * path.length() / target.max(0.05) / DT) as usize + 2000;
        for _ in 0..limit {
            if controller::has_arrived(path, k, &self.pose, 0.0, 0.005) {
                run.arrived = true;
                break;
            }
            let stop = controller::stop_in(path, k, &self.pose, 0.0, false);
            let (nk, clipped) = self.tick(path, k, target, stop);
            k = nk;
            run.clipped_ticks += usize::from(clipped);
            run.trace.push(self.pose);
            run.speeds.push(self.speed);
            run.curvatures.push(self.curvature);
            run.max_deviation = run
                .max_deviation
                .max(path.distance_to(&self.pose.position()));
        }
        run
    }
}
