//! The robot's own idea of its pose, built only from its sensors. MoRo (and
//! any robot without a navigation fix) integrates wheel distance and gyro or
//! differential heading every step; Workpartner dead-reckons by equation (1)
//! at 10 Hz and takes each 2 Hz navigation fix as its new pose.
//!
//! The estimate lives in the world frame; `locate` sets a user frame on top
//! (ILMR's `locate(x,y,h)`), and everything reported is in the user frame.

use super::super::sensors::{DeadReckoning, Odometry, Periodic};
use crate::config::{RobotConfig, Steering};
use crate::geometry::Pose;
use crate::kinematics::advance;

#[derive(Debug, Clone, PartialEq)]
pub enum Estimator {
    /// Per-step integration: distance from the side wheels, heading from the
    /// gyro when there is one, else from the side wheels' difference.
    Odometric { pose: Pose, last: [i64; 4] },
    /// Workpartner's pilot.
    Pilot {
        dr: DeadReckoning,
        dr_timer: Periodic,
        fix_timer: Periodic,
    },
}

impl Estimator {
    pub fn new(cfg: &RobotConfig, start: Pose) -> Self {
        match &cfg.nav {
            Some(n) => Estimator::Pilot {
                dr: DeadReckoning::new(start, [0; 4], cfg.odometry.metres_per_pulse),
                dr_timer: Periodic::from_hz(n.dead_reckoning_hz),
                fix_timer: Periodic::from_hz(n.fix_rate_hz),
            },
            None => Estimator::Odometric {
                pose: start,
                last: [0; 4],
            },
        }
    }

    pub fn pose(&self) -> Pose {
        match self {
            Estimator::Odometric { pose, .. } => *pose,
            Estimator::Pilot { dr, .. } => dr.pose,
        }
    }

    /// One step of odometric integration; `gyro_dh` is the gyro's measured turn.
    pub fn integrate(&mut self, cfg: &RobotConfig, odo: &Odometry, gyro_dh: Option<f64>) {
        let Estimator::Odometric { pose, last } = self else {
            return;
        };
        let now = odo.pulses();
        let side = odo.side();
        let mpp = cfg.odometry.metres_per_pulse;
        let ds = (Odometry::side_mean(&now, &side, odo.count())
            - Odometry::side_mean(last, &side, odo.count()))
            * mpp;
        let dh = gyro_dh.unwrap_or_else(|| {
            let track = match cfg.steering {
                Steering::FrontWheel { rear_track, .. } => rear_track,
                Steering::Articulated { track, .. } => track,
            };
            let delta = |want: i8| {
                let picked: Vec<f64> = (0..odo.count())
                    .filter(|&i| side[i] == want)
                    .map(|i| (now[i] - last[i]) as f64 * mpp)
                    .collect();
                picked.iter().sum::<f64>() / picked.len().max(1) as f64
            };
            (delta(1) - delta(-1)) / track
        });
        *pose = advance(*pose, ds, dh);
        *last = now;
    }

    /// Sets the world-frame estimate outright (a fix, or a test's reset).
    pub fn reset(&mut self, to: Pose) {
        match self {
            Estimator::Odometric { pose, .. } => *pose = to,
            Estimator::Pilot { dr, .. } => dr.reset(to),
        }
    }
}
