//! A schedule of faults over simulated time, and the seeded stream their
//! random parts draw from.

use super::{FaultKind, FaultSpec, Faults};
use crate::rng::Rng;

/// The stream label of the faults' draws; the sensors use 1..=7, so a plan
/// never shifts a sensor's noise.
const FAULT_STREAM: u64 = 8;
/// Relative spread of an injected slip from step to step.
const SLIP_SPREAD: f64 = 0.25;

/// An appearing obstacle that must be shown or taken away now.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObstacleChange {
    /// Index of the fault in the plan (and in the world's `faults`).
    pub index: usize,
    pub distance: f64,
    pub radius: f64,
    pub appear: bool,
}

#[derive(Debug, Clone)]
pub struct FaultPlan {
    specs: Vec<FaultSpec>,
    rng: Rng,
    /// What the schedule contributed at the last step.
    last: Faults,
    /// Per spec: its obstacle stands now.
    shown: Vec<bool>,
}

impl FaultPlan {
    /// `specs` must have passed [`FaultSpec::check`].
    pub fn new(specs: Vec<FaultSpec>, seed: u64) -> FaultPlan {
        let shown = vec![false; specs.len()];
        FaultPlan {
            specs,
            rng: Rng::fork(seed, FAULT_STREAM),
            last: Faults::default(),
            shown,
        }
    }

    pub fn specs(&self) -> &[FaultSpec] {
        &self.specs
    }

    /// What the schedule puts in force at `t_us`. Overlapping faults of one
    /// kind add their slip or bias; any of them silences what it names.
    pub fn scheduled(&self, t_us: u64) -> Faults {
        let mut f = Faults::default();
        for s in self.specs.iter().filter(|s| s.active_at(t_us)) {
            match &s.kind {
                FaultKind::ScannerDropout => f.scanner_dropout = true,
                FaultKind::OdometrySlip { slip } => f.odometry_slip += slip,
                FaultKind::OdometryBias { bias } => f.odometry_scale_error += bias,
                FaultKind::OdometryDropout => f.odometry_dropout = true,
                FaultKind::NavFrozen => f.nav_fix_stale = true,
                FaultKind::DeadBattery => f.dead_battery = true,
                FaultKind::ActuatorDead { actuator }
                    if actuator.eq_ignore_ascii_case(super::DRIVE) =>
                {
                    f.drive_unresponsive = true;
                }
                FaultKind::ActuatorDead { actuator } => {
                    if !f.actuator_dead(actuator) {
                        f.dead_actuators.push(actuator.to_ascii_lowercase());
                    }
                }
                FaultKind::ManipulatorSilent => f.manipulator_silent = true,
                FaultKind::ObstacleAppears { .. } => {}
            }
        }
        f.odometry_slip = f.odometry_slip.min(super::MAX_SLIP);
        f
    }

    /// Brings `active` to the schedule at `t_us` and says which obstacles
    /// appear or go, in plan order.
    pub(crate) fn advance(&mut self, t_us: u64, active: &mut Faults) -> Vec<ObstacleChange> {
        let now = self.scheduled(t_us);
        if now != self.last {
            active.apply_change(&self.last, &now);
            self.last = now;
        }
        let mut changes = Vec::new();
        for (i, s) in self.specs.iter().enumerate() {
            let FaultKind::ObstacleAppears { distance, radius } = s.kind else {
                continue;
            };
            let on = s.active_at(t_us);
            if on != self.shown[i] {
                self.shown[i] = on;
                changes.push(ObstacleChange {
                    index: i,
                    distance,
                    radius,
                    appear: on,
                });
            }
        }
        changes
    }

    /// The kinds whose window starts or ends at `t_us`, for events.
    pub(crate) fn edges(&self, t_us: u64) -> Vec<(&'static str, bool)> {
        self.specs
            .iter()
            .filter_map(|s| {
                let (start, end) = s.window_us();
                if start == t_us {
                    Some((s.kind.name(), true))
                } else if end == Some(t_us) {
                    Some((s.kind.name(), false))
                } else {
                    None
                }
            })
            .collect()
    }

    /// This step's slip around the mean `slip`, within 0..`MAX_SLIP`. No draw
    /// is made without slip, so a plan without it leaves the stream alone.
    pub(crate) fn draw_slip(&mut self, slip: f64) -> f64 {
        if slip <= 0.0 {
            return 0.0;
        }
        (slip * (1.0 + self.rng.gauss(SLIP_SPREAD))).clamp(0.0, super::MAX_SLIP)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(kind: FaultKind, start: f64, duration: Option<f64>) -> FaultSpec {
        FaultSpec::new(kind, start, duration)
    }

    #[test]
    fn a_window_is_closed_at_the_start_and_open_at_the_end() {
        let s = spec(FaultKind::ScannerDropout, 1.0, Some(2.0));
        assert!(!s.active_at(999_999));
        assert!(s.active_at(1_000_000));
        assert!(s.active_at(2_999_999));
        assert!(!s.active_at(3_000_000));
        let forever = spec(FaultKind::DeadBattery, 0.5, None);
        assert!(forever.active_at(u64::MAX));
    }

    #[test]
    fn overlapping_faults_add_up_and_clear_together() {
        let plan = FaultPlan::new(
            vec![
                spec(FaultKind::OdometryBias { bias: 0.02 }, 0.0, Some(2.0)),
                spec(FaultKind::OdometryBias { bias: 0.03 }, 1.0, Some(2.0)),
                spec(
                    FaultKind::ActuatorDead {
                        actuator: "Brake".into(),
                    },
                    0.0,
                    None,
                ),
                spec(
                    FaultKind::ActuatorDead {
                        actuator: "drive".into(),
                    },
                    0.0,
                    None,
                ),
            ],
            1,
        );
        let f = plan.scheduled(1_500_000);
        assert!((f.odometry_scale_error - 0.05).abs() < 1e-12);
        assert_eq!(f.dead_actuators, vec!["brake".to_string()]);
        assert!(f.drive_unresponsive);
        assert!(plan.scheduled(3_000_000).odometry_scale_error == 0.0);
    }

    #[test]
    fn obstacles_appear_and_go_once() {
        let kind = FaultKind::ObstacleAppears {
            distance: 1.0,
            radius: 0.2,
        };
        let mut plan = FaultPlan::new(vec![spec(kind, 0.5, Some(0.5))], 1);
        let mut f = Faults::default();
        assert!(plan.advance(400_000, &mut f).is_empty());
        let on = plan.advance(500_000, &mut f);
        assert_eq!(on.len(), 1);
        assert!(on[0].appear && on[0].index == 0);
        assert!(plan.advance(600_000, &mut f).is_empty());
        let off = plan.advance(1_000_000, &mut f);
        assert!(off.len() == 1 && !off[0].appear);
        assert_eq!(plan.edges(500_000), vec![("obstacle_appears", true)]);
        assert_eq!(plan.edges(1_000_000), vec![("obstacle_appears", false)]);
    }
}
