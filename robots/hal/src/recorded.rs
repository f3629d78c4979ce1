//! A HAL wrapper that remembers every speed setpoint the VM asked for, refused
//! calls included, so that a test can prove the VM never jumps the setpoint
//! (issue 7: every halt within the model's deceleration).

use crate::hal::Hal;
use crate::types::{AsyncOp, BodyPose, HalError, KnownMap, OpId, OpStatus, Pose, Snapshot};

/// `inner` with a log of `(tick time, speed)` for each `set_motion` call.
#[derive(Debug)]
pub struct Recorded<H> {
    pub inner: H,
    t: f64,
    setpoints: Vec<(f64, f64)>,
}

impl<H> Recorded<H> {
    pub fn new(inner: H) -> Recorded<H> {
        Recorded {
            inner,
            t: 0.0,
            setpoints: Vec::new(),
        }
    }

    /// Every speed setpoint with the time of the tick that sent it, in order.
    pub fn setpoints(&self) -> &[(f64, f64)] {
        &self.setpoints
    }

    /// The first change of the speed setpoint faster than the limits allow:
    /// between ticks it may rise (in magnitude) by `acceleration * dt` and fall
    /// by `deceleration * dt` per tick of `period` seconds; through zero the fall
    /// and the rise count separately. The last setpoint of a tick counts.
    pub fn first_jump(&self, period: f64, acceleration: f64, deceleration: f64) -> Option<String> {
        let mut prev = (0.0, 0.0);
        let mut i = 0;
        while i < self.setpoints.len() {
            let t = self.setpoints[i].0;
            while i + 1 < self.setpoints.len() && (self.setpoints[i + 1].0 - t).abs() < 1e-9 {
                i += 1;
            }
            let v = self.setpoints[i].1;
            let ticks = ((t - prev.0) / period).round().max(1.0);
            let (a, b) = (prev.1, v);
            let through_zero = a * b < 0.0;
            let fall = if through_zero {
                a.abs()
            } else {
                (a.abs() - b.abs()).max(0.0)
            };
            let rise = if through_zero {
                b.abs()
            } else {
                (b.abs() - a.abs()).max(0.0)
            };
            if !(fall <= deceleration * period * ticks + 1e-9
                && rise <= acceleration * period * ticks + 1e-9)
            {
                return Some(format!(
                    "the speed setpoint went {a} -> {b} m/s at t = {t:.2} s \
                     (acceleration {acceleration}, deceleration {deceleration} m/s2)"
                ));
            }
            prev = (t, v);
            i += 1;
        }
        None
    }
}

impl<H: Hal> Hal for Recorded<H> {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        self.t = t;
        self.inner.update(t)
    }
    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        self.inner.snapshot(out)
    }
    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
        self.setpoints.push((self.t, speed));
        self.inner.set_motion(speed, curvature)
    }
    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
        self.inner.actuator(id, value)
    }
    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        self.inner.locmode(mode)
    }
    fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError> {
        self.inner.bodypose(pose)
    }
    fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
        self.inner.locate(pose)
    }
    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
        self.inner.start(op)
    }
    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        self.inner.poll(op)
    }
    fn cancel(&mut self, op: OpId) -> Result<(), HalError> {
        self.inner.cancel(op)
    }
    fn known_map(&mut self) -> Option<KnownMap> {
        self.inner.known_map()
    }
    fn actuator_range(&mut self, id: &str) -> Option<(f64, f64)> {
        self.inner.actuator_range(id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scripted::{Limits, ScriptedRobot};

    fn drive(speeds: &[f64]) -> Recorded<ScriptedRobot> {
        let mut r = Recorded::new(ScriptedRobot::new(Limits::default()));
        for (i, &v) in speeds.iter().enumerate() {
            r.update(i as f64 * 0.01).ok();
            r.set_motion(v, 0.0).ok();
        }
        r
    }

    #[test]
    fn a_ramp_passes_and_a_jump_is_named() {
        let ramp = drive(&[0.005, 0.01, 0.015, 0.01, 0.005, 0.0]);
        assert_eq!(ramp.first_jump(0.01, 0.5, 0.5), None);
        let jump = drive(&[0.005, 0.01, 0.0]);
        let why = jump.first_jump(0.01, 0.5, 0.5).unwrap_or_default();
        assert!(why.contains("0.01 -> 0 m/s at t = 0.02"), "{why}");
    }

    #[test]
    fn through_zero_fall_and_rise_count_apart() {
        assert_eq!(drive(&[0.004, -0.004]).first_jump(0.01, 0.5, 0.5), None);
        assert!(drive(&[0.004, -0.006]).first_jump(0.01, 0.5, 0.5).is_some());
    }

    #[test]
    fn the_last_setpoint_of_a_tick_counts() {
        let mut r = Recorded::new(ScriptedRobot::new(Limits::default()));
        r.update(0.0).ok();
        r.set_motion(0.3, 0.0).ok();
        r.set_motion(0.0, 0.0).ok();
        assert_eq!(r.first_jump(0.01, 0.5, 0.5), None);
    }
}
