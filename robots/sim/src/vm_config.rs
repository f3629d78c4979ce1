//! The VM's tunables for a robot: the one place that turns a ROBO.INI model
//! (and, for a simulated robot, its body) into `ilmr_vm::Config`, used by
//! `ilmrc run` and by the experiment tests alike.

use crate::config::RobotConfig;
use ilmr_model::RobotModel;
use ilmr_vm::Config;
use ilmr_vm::runtime::safety::Safety;

/// `turn(left|right)` on a simulated body: three quarters of full lock, so
/// the controller keeps steering in reserve (the setting the dissertation's
/// tests were reproduced with, docs/experiments.md).
pub const TURN_SHARE: f64 = 0.75;

/// The physical settings from `model` (each `Config` field names the model
/// parameter it stands for), and with a simulated `body` its geometry: front
/// and scanner offsets. Without a body (a scripted robot, or none) the VM's
/// defaults stand for what the model does not say, as they did for every
/// scripted trace recorded so far.
pub fn vm_config(model: &RobotModel, body: Option<&RobotConfig>) -> Config {
    let base = Config::default();
    let mut config = Config {
        default_speed: model.default_speed(),
        max_curvature: model.max_curvature(),
        curinc: model.curinc(),
        turn_curvature: base.turn_curvature.min(model.max_curvature()),
        acceleration: model.max_acceleration(),
        deceleration: model.max_deceleration(),
        robot_width: model.robot_width(),
        robot_length: model.robot_length(),
        followwall_d: model.followwall_d(),
        obstacle_curvature: model.omax_curvature(),
        safety: Safety::from_model(model),
        ..base
    };
    if let Some(body) = body {
        config.turn_curvature = TURN_SHARE * model.max_curvature();
        config.front_offset = body.body.length - body.body.rear_overhang;
        config.scanner_offset = body.scanner.mount.x;
        config.security_wait = model.bs_security();
    }
    config
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::RobotKind;
    use crate::robot::config_from_model;

    #[test]
    fn a_simulated_body_sets_its_geometry_and_the_turn_share() {
        let model = RobotModel::builtin("workpartner").unwrap_or_else(|| unreachable!());
        let body = config_from_model(&model, RobotKind::Workpartner);
        let c = vm_config(&model, Some(&body));
        assert_eq!(c.max_curvature, 0.25);
        assert!((c.turn_curvature - 0.1875).abs() < 1e-12);
        assert_eq!(c.front_offset, body.body.length - body.body.rear_overhang);
        assert_eq!(c.scanner_offset, body.scanner.mount.x);
        assert_eq!(c.security_wait, model.bs_security());
        assert_eq!(c.safety.max_speed, model.max_speed());
        let bare = vm_config(&model, None);
        assert_eq!(bare.front_offset, Config::default().front_offset);
        assert!(bare.turn_curvature <= 0.25);
    }
}
