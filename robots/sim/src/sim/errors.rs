//! The errors a real robot carries through a run: the ones fixed when it is
//! switched on (drawn once from the seed's own stream), the slip that wanders
//! with the ground, and what the actuators make of a setpoint (dead time and
//! play). Each is a parameter of [`RobotConfig`]; every one at zero leaves a run
//! exactly as it was without them.

use crate::config::{RobotConfig, SlipConfig, Steering};
use crate::kinematics::{SetpointHistory, backlash, curvature_for_angle, steering_angle};
use crate::rng::Rng;

/// The stream the per-run errors are drawn from: its own, so that adding one
/// never shifts a sensor's noise.
pub(super) const SYSTEMATIC_STREAM: u64 = 9;

/// Errors fixed for the whole run.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Systematic {
    /// Every wheel counts `1 + odometry_scale` of what it rolls.
    pub odometry_scale: f64,
    /// The geometry the wheels really roll on: the track is `1 / (1 + e)` of the
    /// one the odometry assumes.
    pub wheels: Steering,
    /// The curvature achieved is `curvature_gain` times the one the steering set.
    pub curvature_gain: f64,
    /// Added to the gyro's configured bias, rad/s.
    pub gyro_bias: f64,
}

impl Systematic {
    pub fn draw(cfg: &RobotConfig, seed: u64) -> Systematic {
        let mut rng = Rng::fork(seed, SYSTEMATIC_STREAM);
        let odometry_scale = rng.gauss(cfg.odometry.scale_sigma);
        let track = 1.0 / (1.0 + rng.gauss(cfg.odometry.track_sigma));
        let curvature_gain = 1.0 / (1.0 + rng.gauss(cfg.actuator.wheelbase_sigma));
        let gyro_bias = cfg.gyro.as_ref().map_or(0.0, |g| rng.gauss(g.bias_sigma));
        let wheels = match cfg.steering {
            Steering::FrontWheel {
                wheelbase,
                rear_track,
            } => Steering::FrontWheel {
                wheelbase,
                rear_track: rear_track * track,
            },
            Steering::Articulated {
                half_length,
                track: t,
            } => Steering::Articulated {
                half_length,
                track: t * track,
            },
        };
        Systematic {
            odometry_scale,
            wheels,
            curvature_gain,
            gyro_bias,
        }
    }
}

/// Slip as first-order Gauss-Markov processes (longitudinal, yaw), their state
/// kept between steps.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct SlipProcess {
    long: f64,
    yaw: f64,
}

impl SlipProcess {
    /// (longitudinal slip in [0, 0.9], yaw factor) for a step of `dt`. With no
    /// correlation time each step draws afresh, as white noise.
    pub fn step(&mut self, s: &SlipConfig, dt: f64, rng: &mut Rng) -> (f64, f64) {
        let m = Markov::new(dt, s.correlation_time);
        self.long = m.next(self.long, s.sigma, rng);
        self.yaw = m.next(self.yaw, s.yaw_sigma, rng);
        ((s.mean + self.long).clamp(0.0, 0.9), 1.0 + self.yaw)
    }
}

/// One step of a first-order Gauss-Markov process of correlation time `tau`:
/// `x' = a x + sqrt(1 - a^2) N(0, sigma)`, `a = exp(-dt / tau)`, whose spread
/// stays `sigma`. With `tau = 0` it is white noise, bit for bit `N(0, sigma)`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Markov {
    a: f64,
    k: f64,
}

impl Markov {
    pub fn new(dt: f64, tau: f64) -> Markov {
        let a = if tau > 0.0 { (-dt / tau).exp() } else { 0.0 };
        Markov {
            a,
            k: (1.0 - a * a).sqrt(),
        }
    }

    pub fn next(self, x: f64, sigma: f64, rng: &mut Rng) -> f64 {
        self.a * x + self.k * rng.gauss(sigma)
    }
}

/// The navigation subsystem's error (x, y, heading), correlated from fix to fix.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct NavError {
    e: [f64; 3],
}

impl NavError {
    /// The error of the next fix, `1 / rate` after the last.
    pub fn next(&mut self, n: &crate::config::NavConfig, rng: &mut Rng) -> [f64; 3] {
        let m = Markov::new(1.0 / n.fix_rate_hz, n.correlation_time);
        let sigmas = [n.sigma_xy, n.sigma_xy, n.sigma_h];
        for (e, s) in self.e.iter_mut().zip(sigmas) {
            *e = m.next(*e, s, rng);
        }
        self.e
    }
}

/// What the steering and drive are asked for after dead time and play.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct ActuatorState {
    history: SetpointHistory,
    /// Where the loose steering linkage stands, as a steer (articulation) angle.
    linkage: f64,
}

impl ActuatorState {
    /// The speed and curvature setpoints the drive follows at `now_us`, given
    /// those the software set now.
    pub fn follow(&mut self, cfg: &RobotConfig, now_us: u64, v_set: f64, c_set: f64) -> (f64, f64) {
        let a = &cfg.actuator;
        let (v, c) = if a.speed_dead_time > 0.0 || a.steering_dead_time > 0.0 {
            self.history.push(now_us, v_set, c_set);
            self.history.delayed(
                now_us,
                (a.speed_dead_time * 1e6).round() as u64,
                (a.steering_dead_time * 1e6).round() as u64,
            )
        } else {
            (v_set, c_set)
        };
        if a.steering_play_deg == 0.0 {
            return (v, c);
        }
        let limit = cfg.limits.max_curvature;
        let wanted = steering_angle(&cfg.steering, c.clamp(-limit, limit));
        self.linkage = backlash(self.linkage, wanted, a.steering_play_deg.to_radians());
        (v, curvature_for_angle(&cfg.steering, self.linkage))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn correlated_slip_wanders_slowly_and_white_slip_does_not() {
        let mut s = RobotConfig::moro().slip;
        s.sigma = 0.01;
        let lag_one = |s: &SlipConfig| {
            let mut p = SlipProcess::default();
            let mut rng = Rng::new(3);
            let xs: Vec<f64> = (0..20_000)
                .map(|_| p.step(s, 0.01, &mut rng).0 - s.mean)
                .collect();
            let var = xs.iter().map(|x| x * x).sum::<f64>() / xs.len() as f64;
            let cov = xs.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / xs.len() as f64;
            (var.sqrt(), cov / var)
        };
        s.mean = 0.5;
        let (white_sigma, white_r) = lag_one(&s);
        s.correlation_time = 2.0;
        let (red_sigma, red_r) = lag_one(&s);
        assert!(white_r.abs() < 0.05, "white lag-one correlation {white_r}");
        // exp(-0.01 / 2) = 0.995.
        assert!((red_r - 0.995).abs() < 0.005, "correlated {red_r}");
        assert!((white_sigma - 0.01).abs() < 0.001, "{white_sigma}");
        // 20 000 steps are 100 correlation times: the spread is near sigma.
        assert!((red_sigma - 0.01).abs() < 0.003, "{red_sigma}");
    }

    #[test]
    fn per_run_errors_are_fixed_by_the_seed_and_zero_without_sigmas() {
        let mut cfg = RobotConfig::moro();
        let none = Systematic::draw(&cfg, 5);
        assert_eq!(none.odometry_scale, 0.0);
        assert_eq!(none.curvature_gain, 1.0);
        assert_eq!(none.wheels, cfg.steering);
        cfg.odometry.scale_sigma = 0.01;
        cfg.actuator.wheelbase_sigma = 0.01;
        let a = Systematic::draw(&cfg, 5);
        assert_eq!(a, Systematic::draw(&cfg, 5));
        assert_ne!(a, Systematic::draw(&cfg, 6));
        assert!(a.odometry_scale != 0.0 && a.curvature_gain != 1.0);
    }

    #[test]
    fn play_and_dead_time_shape_what_the_steering_follows() {
        let mut cfg = RobotConfig::moro();
        cfg.actuator.steering_dead_time = 0.1;
        cfg.actuator.steering_play_deg = 2.0;
        let mut a = ActuatorState::default();
        assert_eq!(a.follow(&cfg, 0, 0.3, 0.0), (0.3, 0.0));
        // Asked for 0.5 1/m at 10 ms: the steering still follows 0.
        assert_eq!(a.follow(&cfg, 10_000, 0.3, 0.5).1, 0.0);
        // 100 ms on, it follows 0.5 less the play's half (1 degree of steer).
        let c = a.follow(&cfg, 110_000, 0.3, 0.5).1;
        let want = curvature_for_angle(
            &cfg.steering,
            steering_angle(&cfg.steering, 0.5) - 1f64.to_radians(),
        );
        assert!((c - want).abs() < 1e-12, "{c} vs {want}");
    }
}
