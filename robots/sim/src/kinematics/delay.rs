//! The actuators' dead time and the steering's play: what the drive is really
//! asked for, some time after the software asked and through a loose linkage.

use std::collections::VecDeque;

/// The setpoints of the last [`crate::config::MAX_DEAD_TIME`] seconds, so that
/// the drive can follow what was asked `dead_time` ago.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SetpointHistory {
    /// (time in microseconds, speed, curvature), oldest first.
    entries: VecDeque<(u64, f64, f64)>,
}

impl SetpointHistory {
    /// Records the setpoints in force from `now_us` on.
    pub fn push(&mut self, now_us: u64, v: f64, c: f64) {
        if self.entries.back().is_some_and(|e| (e.1, e.2) == (v, c)) {
            return;
        }
        self.entries.push_back((now_us, v, c));
    }

    /// The speed and curvature setpoints in force `speed_delay_us` and
    /// `steer_delay_us` before `now_us`; before the run began and before the
    /// first setpoint, the robot stood with both at zero. Entries older than
    /// both delays are dropped, keeping the one in force.
    pub fn delayed(&mut self, now_us: u64, speed_delay_us: u64, steer_delay_us: u64) -> (f64, f64) {
        if let Some(oldest) = now_us.checked_sub(speed_delay_us.max(steer_delay_us)) {
            while self.entries.len() > 1 && self.entries[1].0 <= oldest {
                self.entries.pop_front();
            }
        }
        let at = |delay: u64| {
            now_us
                .checked_sub(delay)
                .and_then(|t| self.entries.iter().rev().find(|e| e.0 <= t))
                .map_or((0.0, 0.0), |e| (e.1, e.2))
        };
        (at(speed_delay_us).0, at(steer_delay_us).1)
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}

/// Backlash: the output stands still until the input has moved `play` away
/// from it, then is dragged along `play / 2` behind.
pub fn backlash(output: f64, input: f64, play: f64) -> f64 {
    let half = play / 2.0;
    if input > output + half {
        input - half
    } else if input < output - half {
        input + half
    } else {
        output
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_drive_follows_what_was_asked_a_dead_time_ago() {
        let mut h = SetpointHistory::default();
        h.push(0, 0.0, 0.0);
        h.push(100_000, 0.5, 0.2);
        // 50 ms later with a 100 ms dead time: still the first setpoint.
        assert_eq!(h.delayed(150_000, 100_000, 100_000), (0.0, 0.0));
        // Before the run began, nothing was asked.
        assert_eq!(h.delayed(50_000, 100_000, 0), (0.0, 0.0));
        // Speed with no delay, steering 100 ms behind.
        assert_eq!(h.delayed(150_000, 0, 100_000), (0.5, 0.0));
        assert_eq!(h.delayed(200_000, 100_000, 100_000), (0.5, 0.2));
        // What is older than the dead time is dropped, keeping the one in force.
        h.push(300_000, 0.6, 0.2);
        h.push(400_000, 0.7, 0.2);
        assert_eq!(h.delayed(450_000, 100_000, 100_000), (0.6, 0.2));
        assert_eq!(h.len(), 2);
        // Repeating a setpoint records nothing.
        h.push(410_000, 0.7, 0.2);
        assert_eq!(h.len(), 2);
    }

    #[test]
    fn backlash_holds_within_the_play_and_drags_beyond_it() {
        assert_eq!(backlash(0.0, 0.01, 0.04), 0.0);
        assert!((backlash(0.0, 0.05, 0.04) - 0.03).abs() < 1e-12);
        assert!((backlash(0.03, 0.0, 0.04) - 0.02).abs() < 1e-12);
        assert_eq!(backlash(0.3, 0.3, 0.0), 0.3);
    }
}
