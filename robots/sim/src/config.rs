//! Plain configuration of a simulated robot. The defaults describe the two
//! robots of the dissertation (sections 5.1-5.2); a later step builds these
//! structs from a robot model file.

use crate::geometry::{Point2, xy};
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum RobotKind {
    Moro,
    Workpartner,
}

/// The footprint rectangle, placed relative to the reference point (the point
/// whose pose and curvature the commands talk about).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BodyConfig {
    pub length: f64,
    pub width: f64,
    /// Distance from the rear edge forward to the reference point.
    pub rear_overhang: f64,
}

/// Actuator limits: the actual speed and curvature chase their setpoints
/// within these.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DriveLimits {
    /// m/s, both directions.
    pub max_speed: f64,
    /// m/s^2 while the speed's magnitude grows.
    pub max_accel: f64,
    /// m/s^2 while it shrinks.
    pub max_decel: f64,
    /// 1/m, both directions.
    pub max_curvature: f64,
    /// Curvature rate limit, 1/m per s (`curinc` in ROBO.INI).
    pub curinc: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Steering {
    /// MoRo: the front wheel steers and drives; the reference point is the
    /// middle of the rear axle.
    FrontWheel { wheelbase: f64, rear_track: f64 },
    /// Workpartner: the body bends at a joint midway between the axles; the
    /// reference point is the joint. `half_length` is joint-to-axle.
    Articulated { half_length: f64, track: f64 },
}

/// Wheel slip: the ground moves `1 - s` of what the wheels roll, with
/// `s = mean + e` kept in [0, 0.9]; the turn rate is off by a factor `1 + e_yaw`.
/// `e` and `e_yaw` are first-order Gauss-Markov processes of standard deviation
/// `sigma` and `yaw_sigma` and correlation time `correlation_time` (0: drawn
/// afresh every step, white).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SlipConfig {
    pub mean: f64,
    pub sigma: f64,
    pub yaw_sigma: f64,
    /// s; a patch of floor or grass slips alike for about this long.
    #[serde(default)]
    pub correlation_time: f64,
    /// Side-slip angle per lateral acceleration, rad per m/s^2: on a turn the
    /// robot drifts outward by `lateral * v^2 * |c|` of each metre driven,
    /// which the wheels never count.
    #[serde(default)]
    pub lateral: f64,
}

/// What the drive does between a setpoint and the wheels, beyond its rate limits.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct ActuatorConfig {
    /// s from a speed setpoint to the drive starting to follow it.
    pub speed_dead_time: f64,
    /// s from a curvature setpoint to the steering starting to follow it.
    pub steering_dead_time: f64,
    /// Backlash of the steering linkage, degrees of MoRo's front-wheel angle or
    /// Workpartner's articulation angle: the steering stands still until the
    /// command has moved this far from where it last pushed.
    pub steering_play_deg: f64,
    /// Relative error of the wheelbase (MoRo) or joint-to-axle length
    /// (Workpartner) the steering is calibrated with, drawn once per run from
    /// N(0, sigma): the curvature achieved is `c / (1 + e)` of the `c` the
    /// steering set and reports.
    pub wheelbase_sigma: f64,
}

/// Workpartner's rolking mode (legs sliding along the ground).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RolkingConfig {
    /// The top speed in rolking is `max_speed * speed_factor`.
    pub speed_factor: f64,
    /// Slip while rolking, in place of the normal slip.
    pub slip: SlipConfig,
    /// Rolling-resistance power is multiplied by this while rolking.
    pub power_factor: f64,
}

/// SICK LMS 291.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScannerConfig {
    pub rate_hz: f64,
    pub readings: usize,
    pub fov_deg: f64,
    /// Metres; a beam with no return reads exactly this.
    pub max_range: f64,
    pub noise_sigma: f64,
    /// Scanner origin in the robot frame (x forward, y left).
    #[serde(with = "xy")]
    pub mount: Point2<f64>,
    /// Probability that a beam which meets something returns nothing (reads
    /// `max_range`): dark, glossy or grazing surfaces.
    #[serde(default)]
    pub dropout: f64,
    /// Probability that a beam at an edge (a neighbour's range differs by more
    /// than [`MIXED_PIXEL_JUMP`]) reads a range between the near and the far
    /// surface: its spot fell on both.
    #[serde(default)]
    pub mixed_pixel: f64,
    /// s from the first reading of a scan to the last: a scan taken while
    /// moving is cast from the poses the robot passed through, and stamped with
    /// the pose at its end.
    #[serde(default)]
    pub sweep_time: f64,
}

/// The range difference between neighbouring beams that makes an edge whose
/// beams may be mixed pixels, m.
pub const MIXED_PIXEL_JUMP: f64 = 0.1;

/// The longest dead time the actuators accept, s: it bounds the setpoints kept.
pub const MAX_DEAD_TIME: f64 = 1.0;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OdometryConfig {
    /// Wheel travel per pulse (the coefficient `c` of equation (1)).
    pub metres_per_pulse: f64,
    /// Relative scale error of the left and right wheels' pulse counts.
    pub left_scale_error: f64,
    pub right_scale_error: f64,
    /// Relative error of the wheels' size, both sides alike, drawn once per
    /// run from N(0, sigma): every count is `1 + e` of the true travel.
    #[serde(default)]
    pub scale_sigma: f64,
    /// Relative error of the track (the distance between the left and right
    /// wheels) the odometry assumes, drawn once per run from N(0, sigma): the
    /// wheels' difference then gives the turn `1 + e` too large.
    #[serde(default)]
    pub track_sigma: f64,
}

/// MoRo's fibre-optic gyro.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GyroConfig {
    /// Constant rate bias, rad/s.
    pub bias: f64,
    /// Bias random walk, rad/s per sqrt(s).
    pub bias_walk: f64,
    /// Angle random walk, rad per sqrt(s).
    pub noise: f64,
    /// Turn-on to turn-on bias repeatability, rad/s: a bias drawn once per run
    /// from N(0, sigma) is added to `bias`.
    #[serde(default)]
    pub bias_sigma: f64,
}

/// MoRo's inductive floor-plate sensor array: a line across the body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlateSensorConfig {
    /// Distance of the array ahead of the reference point.
    pub offset: f64,
    /// The array spans `-half_width..half_width` across the body.
    pub half_width: f64,
    pub noise_sigma: f64,
    /// Reported lateral offsets are rounded to this (1 cm).
    pub resolution: f64,
}

/// Workpartner's navigation subsystem and the pilot's dead reckoning.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NavConfig {
    pub fix_rate_hz: f64,
    pub dead_reckoning_hz: f64,
    /// Standard deviation of a fix's position error, m, each axis.
    pub sigma_xy: f64,
    /// Standard deviation of a fix's heading error, rad.
    pub sigma_h: f64,
    /// s; successive fixes matched against the same landmarks err alike: the
    /// error is a first-order Gauss-Markov process (0: independent fixes).
    #[serde(default)]
    pub correlation_time: f64,
}

/// Workpartner's four rear ultrasonic sensors, facing backwards from the rear edge.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UltrasonicConfig {
    pub rate_hz: f64,
    pub min_range: f64,
    pub max_range: f64,
    pub cone_deg: f64,
    pub noise_sigma: f64,
    /// Lateral position of each sensor (left positive), leftmost first.
    pub lateral: [f64; 4],
}

/// Workpartner's pan-tilt head: colour camera and laser pointer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CameraConfig {
    pub rate_hz: f64,
    pub fov_deg: f64,
    pub max_range: f64,
    pub image_width_px: f64,
    /// Head position in the robot frame.
    #[serde(with = "xy")]
    pub head: Point2<f64>,
    pub head_height: f64,
    pub max_pan_deg: f64,
    pub max_tilt_deg: f64,
    pub laser_max_range: f64,
    pub laser_sigma: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BatteryConfig {
    pub capacity_wh: f64,
    pub v_full: f64,
    pub v_empty: f64,
    /// Electronics and sensors, always drawn.
    pub idle_w: f64,
    pub rolling_resistance: f64,
    /// Charging power at the charger.
    pub charge_w: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BodyPoseConfig {
    pub angle_rate_deg_s: f64,
    pub clearance_rate: f64,
    pub initial_clearance: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotConfig {
    pub kind: RobotKind,
    pub mass_kg: f64,
    pub body: BodyConfig,
    pub steering: Steering,
    pub limits: DriveLimits,
    #[serde(default)]
    pub actuator: ActuatorConfig,
    pub slip: SlipConfig,
    pub scanner: ScannerConfig,
    pub odometry: OdometryConfig,
    pub battery: BatteryConfig,
    pub gyro: Option<GyroConfig>,
    pub plates: Option<PlateSensorConfig>,
    pub nav: Option<NavConfig>,
    pub ultrasonic: Option<UltrasonicConfig>,
    pub camera: Option<CameraConfig>,
    pub body_pose: Option<BodyPoseConfig>,
    pub rolking: Option<RolkingConfig>,
}

impl RobotConfig {
    /// The body's front and its scanner ahead of the reference point, for the VM.
    pub fn offsets(&self) -> ilmr_hal::BodyOffsets {
        ilmr_hal::BodyOffsets {
            front: self.body.length - self.body.rear_overhang,
            scanner: self.scanner.mount.x,
        }
    }

    pub fn for_kind(kind: RobotKind) -> Self {
        match kind {
            RobotKind::Moro => Self::moro(),
            RobotKind::Workpartner => Self::workpartner(),
        }
    }

    /// MoRo: 1.2 m x 0.6 m AGV turning within a 1.5 m diameter.
    pub fn moro() -> Self {
        RobotConfig {
            kind: RobotKind::Moro,
            mass_kg: 150.0,
            body: BodyConfig {
                length: 1.2,
                width: 0.6,
                rear_overhang: 0.25,
            },
            steering: Steering::FrontWheel {
                wheelbase: 0.8,
                rear_track: 0.5,
            },
            limits: DriveLimits {
                max_speed: 1.0,
                max_accel: 0.5,
                max_decel: 0.8,
                max_curvature: 1.0 / 0.75,
                curinc: 1.0,
            },
            actuator: ActuatorConfig::default(),
            slip: SlipConfig {
                mean: 0.0,
                sigma: 0.002,
                yaw_sigma: 0.002,
                correlation_time: 0.0,
                lateral: 0.0,
            },
            scanner: ScannerConfig {
                rate_hz: 4.0,
                readings: 361,
                fov_deg: 180.0,
                max_range: 30.0,
                noise_sigma: 0.01,
                mount: Point2::new(0.85, 0.0),
                dropout: 0.0,
                mixed_pixel: 0.0,
                sweep_time: 0.0,
            },
            odometry: OdometryConfig {
                metres_per_pulse: 0.0005,
                left_scale_error: 0.0,
                right_scale_error: 0.0,
                scale_sigma: 0.0,
                track_sigma: 0.0,
            },
            battery: BatteryConfig {
                capacity_wh: 960.0,
                v_full: 25.6,
                v_empty: 21.0,
                idle_w: 40.0,
                rolling_resistance: 0.02,
                charge_w: 200.0,
            },
            gyro: Some(GyroConfig {
                bias: 2.0e-5,
                bias_walk: 1.0e-6,
                noise: 1.0e-4,
                bias_sigma: 0.0,
            }),
            plates: Some(PlateSensorConfig {
                offset: 0.45,
                half_width: 0.3,
                noise_sigma: 0.003,
                resolution: 0.01,
            }),
            nav: None,
            ultrasonic: None,
            camera: None,
            body_pose: None,
            rolking: None,
        }
    }

    /// Workpartner: articulated, about 230 kg, max curvature 0.25 1/m.
    pub fn workpartner() -> Self {
        RobotConfig {
            kind: RobotKind::Workpartner,
            mass_kg: 230.0,
            body: BodyConfig {
                length: 2.2,
                width: 1.0,
                rear_overhang: 1.1,
            },
            steering: Steering::Articulated {
                half_length: 0.6,
                track: 1.0,
            },
            limits: DriveLimits {
                max_speed: 0.6,
                max_accel: 0.3,
                max_decel: 0.5,
                max_curvature: 0.25,
                curinc: 0.8,
            },
            actuator: ActuatorConfig::default(),
            slip: SlipConfig {
                mean: 0.01,
                sigma: 0.005,
                yaw_sigma: 0.01,
                correlation_time: 0.0,
                lateral: 0.0,
            },
            scanner: ScannerConfig {
                rate_hz: 2.0,
                readings: 361,
                fov_deg: 180.0,
                max_range: 30.0,
                noise_sigma: 0.01,
                mount: Point2::new(1.0, 0.0),
                dropout: 0.0,
                mixed_pixel: 0.0,
                sweep_time: 0.0,
            },
            odometry: OdometryConfig {
                metres_per_pulse: 0.002,
                left_scale_error: 0.0,
                right_scale_error: 0.0,
                scale_sigma: 0.0,
                track_sigma: 0.0,
            },
            battery: BatteryConfig {
                capacity_wh: 2000.0,
                v_full: 51.0,
                v_empty: 42.0,
                idle_w: 150.0,
                rolling_resistance: 0.05,
                charge_w: 500.0,
            },
            gyro: None,
            plates: None,
            nav: Some(NavConfig {
                fix_rate_hz: 2.0,
                dead_reckoning_hz: 10.0,
                sigma_xy: 0.02,
                sigma_h: 0.3_f64.to_radians(),
                correlation_time: 0.0,
            }),
            ultrasonic: Some(UltrasonicConfig {
                rate_hz: 10.0,
                min_range: 0.2,
                max_range: 3.0,
                cone_deg: 25.0,
                noise_sigma: 0.01,
                lateral: [0.375, 0.125, -0.125, -0.375],
            }),
            camera: Some(CameraConfig {
                rate_hz: 10.0,
                fov_deg: 50.0,
                max_range: 20.0,
                image_width_px: 640.0,
                head: Point2::new(0.3, 0.0),
                head_height: 1.6,
                max_pan_deg: 170.0,
                max_tilt_deg: 60.0,
                laser_max_range: 30.0,
                laser_sigma: 0.01,
            }),
            body_pose: Some(BodyPoseConfig {
                angle_rate_deg_s: 10.0,
                clearance_rate: 0.1,
                initial_clearance: 0.5,
            }),
            rolking: Some(RolkingConfig {
                speed_factor: 0.5,
                slip: SlipConfig {
                    mean: 0.08,
                    sigma: 0.03,
                    yaw_sigma: 0.05,
                    correlation_time: 0.0,
                    lateral: 0.0,
                },
                power_factor: 2.5,
            }),
        }
    }

    /// Every number finite and every size, rate and limit positive; names the
    /// first field that is not.
    pub fn validate(&self) -> Result<(), String> {
        let mut checks: Vec<(&str, f64)> = vec![
            ("mass_kg", self.mass_kg),
            ("body.length", self.body.length),
            ("body.width", self.body.width),
            ("limits.max_speed", self.limits.max_speed),
            ("limits.max_accel", self.limits.max_accel),
            ("limits.max_decel", self.limits.max_decel),
            ("limits.max_curvature", self.limits.max_curvature),
            ("limits.curinc", self.limits.curinc),
            ("scanner.rate_hz", self.scanner.rate_hz),
            ("scanner.fov_deg", self.scanner.fov_deg),
            ("scanner.max_range", self.scanner.max_range),
            ("odometry.metres_per_pulse", self.odometry.metres_per_pulse),
            ("battery.capacity_wh", self.battery.capacity_wh),
            ("battery.v_full", self.battery.v_full),
        ];
        match self.steering {
            Steering::FrontWheel {
                wheelbase,
                rear_track,
            } => {
                checks.push(("steering.wheelbase", wheelbase));
                checks.push(("steering.rear_track", rear_track));
            }
            Steering::Articulated { half_length, track } => {
                checks.push(("steering.half_length", half_length));
                checks.push(("steering.track", track));
            }
        }
        if let Some(n) = &self.nav {
            checks.push(("nav.fix_rate_hz", n.fix_rate_hz));
            checks.push(("nav.dead_reckoning_hz", n.dead_reckoning_hz));
        }
        if let Some(u) = &self.ultrasonic {
            checks.push(("ultrasonic.rate_hz", u.rate_hz));
            checks.push(("ultrasonic.max_range", u.max_range));
        }
        if let Some(c) = &self.camera {
            checks.push(("camera.rate_hz", c.rate_hz));
            checks.push(("camera.fov_deg", c.fov_deg));
            checks.push(("camera.max_range", c.max_range));
            checks.push(("camera.laser_max_range", c.laser_max_range));
        }
        if let Some(p) = &self.plates {
            checks.push(("plates.half_width", p.half_width));
            checks.push(("plates.resolution", p.resolution));
        }
        if let Some((name, v)) = checks.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Err(format!("{name} must be a positive number, got {v}"));
        }
        let mut non_negative = vec![
            ("body.rear_overhang", self.body.rear_overhang),
            ("slip.mean", self.slip.mean),
            ("slip.sigma", self.slip.sigma),
            ("slip.yaw_sigma", self.slip.yaw_sigma),
            ("slip.correlation_time", self.slip.correlation_time),
            ("slip.lateral", self.slip.lateral),
            (
                "actuator.steering_play_deg",
                self.actuator.steering_play_deg,
            ),
            ("actuator.wheelbase_sigma", self.actuator.wheelbase_sigma),
            ("odometry.scale_sigma", self.odometry.scale_sigma),
            ("odometry.track_sigma", self.odometry.track_sigma),
            ("scanner.noise_sigma", self.scanner.noise_sigma),
            ("battery.idle_w", self.battery.idle_w),
            (
                "battery.rolling_resistance",
                self.battery.rolling_resistance,
            ),
            ("battery.charge_w", self.battery.charge_w),
        ];
        if let Some(g) = &self.gyro {
            non_negative.push(("gyro.bias_sigma", g.bias_sigma));
        }
        if let Some(n) = &self.nav {
            non_negative.push(("nav.correlation_time", n.correlation_time));
        }
        if let Some((name, v)) = non_negative
            .iter()
            .find(|(_, v)| !(v.is_finite() && *v >= 0.0))
        {
            return Err(format!("{name} must be zero or positive, got {v}"));
        }
        let bounded = [
            (
                "actuator.speed_dead_time",
                self.actuator.speed_dead_time,
                MAX_DEAD_TIME,
            ),
            (
                "actuator.steering_dead_time",
                self.actuator.steering_dead_time,
                MAX_DEAD_TIME,
            ),
            ("scanner.dropout", self.scanner.dropout, 1.0),
            ("scanner.mixed_pixel", self.scanner.mixed_pixel, 1.0),
            (
                "scanner.sweep_time",
                self.scanner.sweep_time,
                1.0 / self.scanner.rate_hz,
            ),
        ];
        if let Some((name, v, most)) = bounded
            .iter()
            .find(|(_, v, most)| !(v.is_finite() && (0.0..=*most).contains(v)))
        {
            return Err(format!("{name} must be 0 to {most}, got {v}"));
        }
        let most = ilmr_model::MAX_READINGS as usize;
        if !(2..=most).contains(&self.scanner.readings) {
            return Err(format!(
                "scanner.readings must be 2 to {most}, got {}",
                self.scanner.readings
            ));
        }
        if self.battery.v_empty >= self.battery.v_full || !self.battery.v_empty.is_finite() {
            return Err("battery.v_empty must be below battery.v_full".to_string());
        }
        Ok(())
    }
}
