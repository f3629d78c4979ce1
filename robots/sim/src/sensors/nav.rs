//! Workpartner's position: the navigation subsystem's fix at 2 Hz, and the
//! pilot's dead reckoning at 10 Hz by equation (1) in between (section 4.2.1).

use crate::geometry::Pose;
use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NavFix {
    /// Counts fixes from 0.
    pub seq: u64,
    pub time: f64,
    pub pose: Pose,
}

/// Equation (1) over the pulse counts of the four leg wheels.
#[derive(Debug, Clone, PartialEq)]
pub struct DeadReckoning {
    pub pose: Pose,
    leg_old: [i64; 4],
    /// Metres per pulse: the coefficient `c` of equation (1).
    c: f64,
}

impl DeadReckoning {
    pub fn new(pose: Pose, legs: [i64; 4], c: f64) -> Self {
        DeadReckoning {
            pose,
            leg_old: legs,
            c,
        }
    }

    /// One update, written as equation (1) is:
    ///
    /// ```text
    /// ds = 1/4 sum_{i=0..3} [leg_new(i) - leg_old(i)] c
    /// dh = tanh([leg_new(1) - leg_old(1)] c - [leg_new(0) - leg_old(0)] c)
    /// h  = h + dh
    /// x  = x + cos(h) ds
    /// y  = y + sin(h) ds
    /// ```
    ///
    /// The heading uses the new `h`, and the wheel-difference is not divided
    /// by a track width: the equation holds for Workpartner's 1 m track.
    pub fn update(&mut self, leg_new: [i64; 4]) {
        let c = self.c;
        let d = |i: usize| (leg_new[i] - self.leg_old[i]) as f64;
        let ds = 0.25 * (0..4).map(|i| d(i) * c).sum::<f64>();
        let dh = (d(1) * c - d(0) * c).tanh();
        let h = self.pose.h + dh;
        let x = self.pose.x + h.cos() * ds;
        let y = self.pose.y + h.sin() * ds;
        self.pose = Pose::new(x, y, h);
        self.leg_old = leg_new;
    }

    /// A new fix replaces the dead-reckoned pose; counting goes on from here.
    pub fn reset(&mut self, pose: Pose) {
        self.pose = pose;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equation_one_by_hand() {
        let mut dr = DeadReckoning::new(Pose::new(0.0, 0.0, 0.0), [0; 4], 0.01);
        // Straight: 100 pulses on every leg is 1 m ahead.
        dr.update([100, 100, 100, 100]);
        assert!((dr.pose.x - 1.0).abs() < 1e-12 && dr.pose.y.abs() < 1e-12);
        // Leg 1 (front right) 10 pulses ahead of leg 0: turn left by tanh(0.1).
        dr.update([195, 205, 195, 205]);
        let h = 0.1_f64.tanh();
        assert!((dr.pose.h - h).abs() < 1e-12);
        assert!((dr.pose.x - (1.0 + h.cos())).abs() < 1e-12);
        assert!((dr.pose.y - h.sin()).abs() < 1e-12);
    }
}
