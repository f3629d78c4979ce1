//! Random fault plans for soak tests: a seed gives the same plan every time.

use super::{FaultKind, FaultSpec, MAX_BIAS};
use crate::config::RobotKind;
use crate::rng::Rng;

/// The stream label of plan drawing, apart from the sensors' and the plan's own.
const PLAN_STREAM: u64 = 9;

/// `count` faults, each starting within `0..horizon` s and lasting 0.5 to 10 s,
/// of the kinds `robot` can suffer (MoRo has no navigation fix and no
/// manipulator), with parameters drawn within their ranges. Obstacles appear
/// 1 to 3 m ahead, which a robot at its top speed can stop short of.
pub fn random_plan(seed: u64, horizon: f64, count: usize, robot: RobotKind) -> Vec<FaultSpec> {
    let mut rng = Rng::fork(seed, PLAN_STREAM);
    let kinds: &[&str] = match robot {
        RobotKind::Moro => &[
            "scanner_dropout",
            "odometry_slip",
            "odometry_bias",
            "odometry_dropout",
            "dead_battery",
            "actuator_dead",
            "obstacle_appears",
        ],
        RobotKind::Workpartner => &super::KIND_NAMES,
    };
    let horizon = if horizon.is_finite() {
        horizon.max(0.0)
    } else {
        0.0
    };
    (0..count)
        .filter_map(|_| {
            let pick = (rng.uniform() * kinds.len() as f64) as usize;
            let mut kind = FaultKind::named(kinds[pick.min(kinds.len() - 1)])?;
            match &mut kind {
                FaultKind::OdometrySlip { slip } => *slip = 0.05 + 0.45 * rng.uniform(),
                FaultKind::OdometryBias { bias } => {
                    *bias = MAX_BIAS * 0.4 * (2.0 * rng.uniform() - 1.0)
                }
                FaultKind::ObstacleAppears { distance, .. } => {
                    *distance = 1.0 + 2.0 * rng.uniform()
                }
                _ => {}
            }
            // Whole milliseconds keep plans readable when printed.
            let ms = |s: f64| (s * 1000.0).round() / 1000.0;
            let start = ms(horizon * rng.uniform());
            let duration = ms(0.5 + 9.5 * rng.uniform());
            Some(FaultSpec::new(kind, start, Some(duration)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_seed_gives_one_valid_plan() {
        let a = random_plan(11, 60.0, 50, RobotKind::Moro);
        assert_eq!(a, random_plan(11, 60.0, 50, RobotKind::Moro));
        assert_ne!(a, random_plan(12, 60.0, 50, RobotKind::Moro));
        assert_eq!(a.len(), 50);
        assert!(a.iter().all(|s| s.check().is_ok() && s.start < 60.0));
        assert!(
            a.iter()
                .all(|s| !matches!(s.kind, FaultKind::NavFrozen | FaultKind::ManipulatorSilent)),
            "MoRo has neither"
        );
        let w = random_plan(3, 30.0, 200, RobotKind::Workpartner);
        let mut names: Vec<&str> = w.iter().map(|s| s.kind.name()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), super::super::KIND_NAMES.len());
    }
}
