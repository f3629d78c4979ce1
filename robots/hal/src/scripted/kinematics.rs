//! A bicycle-free kinematic model: speed and curvature follow their setpoints within
//! rate limits, and the pose integrates exactly along the resulting arc.

use crate::types::Pose;

/// Rate limits of the integrator. Defaults are MoRo-like.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// m/s^2 when the speed magnitude grows.
    pub acceleration: f64,
    /// m/s^2 when the speed magnitude shrinks.
    pub deceleration: f64,
    /// Largest change of curvature, 1/m per second.
    pub curvature_rate: f64,
    /// Largest curvature magnitude, 1/m.
    pub max_curvature: f64,
    /// Largest speed magnitude, m/s.
    pub max_speed: f64,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            acceleration: 0.5,
            deceleration: 0.8,
            curvature_rate: 2.0,
            max_curvature: 1.4,
            max_speed: 1.0,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Kinematics {
    pub pose: Pose,
    pub speed: f64,
    pub curvature: f64,
    pub speed_set: f64,
    pub curvature_set: f64,
}

impl Kinematics {
    pub fn step(&mut self, limits: &Limits, dt: f64) {
        let target_v = self.speed_set.clamp(-limits.max_speed, limits.max_speed);
        let growing = target_v.abs() > self.speed.abs() && target_v * self.speed >= 0.0;
        let rate = if growing {
            limits.acceleration
        } else {
            limits.deceleration
        };
        self.speed = approach(self.speed, target_v, rate * dt);
        let target_c = self
            .curvature_set
            .clamp(-limits.max_curvature, limits.max_curvature);
        self.curvature = approach(self.curvature, target_c, limits.curvature_rate * dt);

        let ds = self.speed * dt;
        let dh = ds * self.curvature;
        let Pose { x, y, h } = self.pose;
        // Exact arc integration; the chord formula degenerates to a straight step.
        let (nx, ny) = if dh.abs() < 1e-9 {
            (x + ds * h.cos(), y + ds * h.sin())
        } else {
            let r = 1.0 / self.curvature;
            (
                x + r * ((h + dh).sin() - h.sin()),
                y - r * ((h + dh).cos() - h.cos()),
            )
        };
        self.pose = Pose::new(nx, ny, h + dh);
    }
}

fn approach(from: f64, to: f64, max_step: f64) -> f64 {
    if (to - from).abs() <= max_step {
        to
    } else {
        from + max_step.copysign(to - from)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_run_reaches_speed_within_the_acceleration_limit() {
        let limits = Limits::default();
        let mut k = Kinematics {
            speed_set: 0.5,
            ..Kinematics::default()
        };
        for _ in 0..50 {
            k.step(&limits, 0.01);
        }
        assert!((k.speed - 0.25).abs() < 1e-9, "0.5 s at 0.5 m/s^2");
        for _ in 0..100 {
            k.step(&limits, 0.01);
        }
        assert!((k.speed - 0.5).abs() < 1e-12);
        assert!(k.pose.y.abs() < 1e-12);
    }

    #[test]
    fn constant_curvature_drives_a_circle() {
        let limits = Limits::default();
        let mut k = Kinematics {
            speed: 1.0,
            speed_set: 1.0,
            curvature: 1.0,
            curvature_set: 1.0,
            ..Kinematics::default()
        };
        let quarter = std::f64::consts::FRAC_PI_2;
        let steps = (quarter / 0.01).round() as usize;
        for _ in 0..steps {
            k.step(&limits, 0.01);
        }
        // Quarter circle of radius 1 to the left ends near (1, 1) facing +y.
        assert!((k.pose.x - 1.0).abs() < 0.01, "{:?}", k.pose);
        assert!((k.pose.y - 1.0).abs() < 0.01, "{:?}", k.pose);
    }
}
