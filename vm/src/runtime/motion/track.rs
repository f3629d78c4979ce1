//! The path tracker: pure pursuit in the travel frame with a braking speed profile.
//! It stands in for ilmr-motion's predictive curvature controller behind the same
//! inputs (pose, path, progress) and outputs (speed and curvature setpoints).

use ilmr_hal::Pose;

use super::path::Path;
use crate::runtime::config::Config;

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Control {
    pub speed: f64,
    pub curvature: f64,
    pub remaining: f64,
}

/// One control step. `brake`: plan to stop at the path's end (no linked successor).
pub(crate) fn control(
    path: &Path,
    seg: &mut usize,
    s: &mut f64,
    body: Pose,
    speed: f64,
    cfg: &Config,
    brake: bool,
) -> Control {
    let th = if path.dir < 0.0 {
        body.h + std::f64::consts::PI
    } else {
        body.h
    };
    path.advance(seg, s, body.x, body.y);
    let remaining = path.total() - *s;
    let (tx, ty, _) = path.pose_at(*s + cfg.lookahead, *seg);
    let (dx, dy) = (tx - body.x, ty - body.y);
    let lx = dx * th.cos() + dy * th.sin();
    let ly = -dx * th.sin() + dy * th.cos();
    let d2 = lx * lx + ly * ly;
    let k = if d2 > 1e-12 { 2.0 * ly / d2 } else { 0.0 };
    let k = k.clamp(-cfg.max_curvature, cfg.max_curvature);
    let mut v = speed.abs();
    if brake && remaining.is_finite() {
        v = v.min((2.0 * cfg.deceleration * (remaining - cfg.goal_tolerance).max(0.0)).sqrt());
        if remaining > cfg.goal_tolerance {
            // Creep rather than stall just short of the goal.
            v = v.max(0.03_f64.min(speed.abs()));
        }
    }
    Control {
        speed: path.dir * v,
        curvature: path.dir * k,
        remaining,
    }
}
