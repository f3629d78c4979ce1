//! The faults in force now, as the simulator's hooks read them. A test may set
//! them directly between steps; a [`super::FaultPlan`] sets them from its
//! schedule, changing only what its own schedule changed, so a fault set by
//! hand stays set until the plan itself turns that fault on and off.

/// Faults in force; all off by default.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Faults {
    /// No new scans arrive; the last one stays in the snapshot.
    pub scanner_dropout: bool,
    /// Relative scale error added to every wheel's pulse count.
    pub odometry_scale_error: f64,
    /// Mean extra slip: the ground moves `1 - slip` of the wheels' travel.
    pub odometry_slip: f64,
    /// The pulse counters stop reporting; the estimate stops integrating.
    pub odometry_dropout: bool,
    /// Fixes keep arriving but repeat the last good pose, so the pilot keeps
    /// snapping back to it.
    pub nav_fix_frozen: bool,
    /// No new fix arrives (the last keeps its stamp); the pilot dead-reckons.
    pub nav_fix_stale: bool,
    /// The battery reads empty and the drive has no power.
    pub dead_battery: bool,
    /// The drive takes no setpoints; its watchdog brings it to rest.
    pub drive_unresponsive: bool,
    /// Model actuators (lower case) whose commands are not answered.
    pub dead_actuators: Vec<String>,
    /// Manipulator operations do not complete.
    pub manipulator_silent: bool,
}

impl Faults {
    /// Whether `name` (any case) is a silenced model actuator.
    pub fn actuator_dead(&self, name: &str) -> bool {
        self.dead_actuators
            .iter()
            .any(|a| a.eq_ignore_ascii_case(name))
    }

    /// Applies what changed from `was` to `now` (two schedules' outputs) to
    /// `self`, leaving every field the schedule did not change as it is.
    pub(crate) fn apply_change(&mut self, was: &Faults, now: &Faults) {
        fn take<T: PartialEq + Clone>(field: &mut T, was: &T, now: &T) {
            if was != now {
                *field = now.clone();
            }
        }
        take(
            &mut self.scanner_dropout,
            &was.scanner_dropout,
            &now.scanner_dropout,
        );
        take(
            &mut self.odometry_scale_error,
            &was.odometry_scale_error,
            &now.odometry_scale_error,
        );
        take(
            &mut self.odometry_slip,
            &was.odometry_slip,
            &now.odometry_slip,
        );
        take(
            &mut self.odometry_dropout,
            &was.odometry_dropout,
            &now.odometry_dropout,
        );
        take(
            &mut self.nav_fix_frozen,
            &was.nav_fix_frozen,
            &now.nav_fix_frozen,
        );
        take(
            &mut self.nav_fix_stale,
            &was.nav_fix_stale,
            &now.nav_fix_stale,
        );
        take(&mut self.dead_battery, &was.dead_battery, &now.dead_battery);
        take(
            &mut self.drive_unresponsive,
            &was.drive_unresponsive,
            &now.drive_unresponsive,
        );
        take(
            &mut self.dead_actuators,
            &was.dead_actuators,
            &now.dead_actuators,
        );
        take(
            &mut self.manipulator_silent,
            &was.manipulator_silent,
            &now.manipulator_silent,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_schedule_changes_only_its_own_fields() {
        let mut active = Faults {
            dead_battery: true,
            ..Faults::default()
        };
        let was = Faults::default();
        let now = Faults {
            scanner_dropout: true,
            ..Faults::default()
        };
        active.apply_change(&was, &now);
        assert!(active.scanner_dropout && active.dead_battery, "{active:?}");
        active.apply_change(&now, &was);
        assert!(!active.scanner_dropout && active.dead_battery, "{active:?}");
    }
}
