//! The halt ramp: every way the robot is brought to rest without a movement to
//! drive (`break`, a broken or refused movement, a priority block, the end of the
//! last movement, a supervisor fault that ends it) lowers the speed setpoint by at
//! most the model's deceleration per tick, holding the curvature, until it is 0.
//! `stop` and the supervisor's holds brake the running movement the same way in
//! `drive.rs`. Nothing sets the speed setpoint to 0 in one step.

use ilmr_hal::{Hal, HalError};
use ilmr_motion::controller::next_speed;

use crate::runtime::Vm;
use crate::runtime::clock::Clock;

impl<H: Hal, C: Clock> Vm<H, C> {
    /// One tick of the halt ramp, when no movement holds the reservation.
    pub(super) fn ramp_down(&mut self) {
        if self.motion.idle {
            if self.motion.unsent {
                let sent = self.hal.set_motion(0.0, 0.0);
                self.motion.unsent = sent.is_err();
            }
            return;
        }
        let limits = self.speed_limits();
        let v = next_speed(self.motion.v, 0.0, None, &limits, self.cfg.period);
        self.motion.v = v;
        // At rest the steering is straightened too, as a stop always did.
        let (speed, curvature) = if v > 0.0 {
            (self.motion.sign * v, self.motion.c)
        } else {
            self.motion.idle = true;
            self.motion.c = 0.0;
            (0.0, 0.0)
        };
        let sent = self.hal.set_motion(speed, curvature);
        self.motion.unsent = sent.is_err();
        match sent {
            // As in `step_motion`: the supervisor's hold already says why.
            Err(HalError::Refused(_)) if self.supervisor.holding() => {}
            Err(e) => self.error(None, format!("braking the robot failed: {e}")),
            Ok(()) => {}
        }
    }
}
