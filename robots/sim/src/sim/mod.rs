//! The simulator: one robot in one world, stepped by the caller with a fixed
//! dt. Time is kept in whole microseconds so that periodic sensors fire on
//! exact ticks, and every random draw comes from a per-sensor seeded stream,
//! so equal inputs give bit-identical runs.

mod error;
mod errors;
mod estimate;
mod faulting;
mod manipulate;
mod sensing;
mod snapshot;
mod targets;

pub use crate::faults::Faults;
pub use error::{Contact, SimError};
pub use snapshot::{EventKind, SensorSnapshot, SimEvent};

use crate::config::{RobotConfig, SlipConfig};
use crate::faults::FaultPlan;
use crate::geometry::{Obb, Point2, Pose, Scene, SolidRef};
use crate::kinematics::{
    BodyPose, MovementMode, advance, next_curvature, next_speed, slide, steering_angle,
    wheel_travel,
};
use crate::rng::Rng;
use crate::sensors::{
    Battery, BatteryReading, CameraFrame, Gyro, NavFix, Odometry, Periodic, PlateEvent, Scan,
    UltrasonicReading,
};
use crate::world::World;
use errors::{ActuatorState, NavError, SlipProcess, Systematic};
use estimate::Estimator;
use std::sync::Arc;
use targets::Walker;

/// Independent noise streams, one per source, so that one sensor's draws never
/// shift another's.
#[derive(Debug, Clone)]
struct Streams {
    slip: Rng,
    scanner: Rng,
    gyro: Rng,
    plates: Rng,
    nav: Rng,
    ultrasonic: Rng,
    camera: Rng,
    /// The scanner's dropouts and mixed pixels, apart from its range noise.
    scanner_faults: Rng,
}

impl Streams {
    fn new(seed: u64) -> Self {
        Streams {
            slip: Rng::fork(seed, 1),
            scanner: Rng::fork(seed, 2),
            gyro: Rng::fork(seed, 3),
            plates: Rng::fork(seed, 4),
            nav: Rng::fork(seed, 5),
            ultrasonic: Rng::fork(seed, 6),
            camera: Rng::fork(seed, 7),
            // 8 is the fault plan's slip, 9 the per-run errors.
            scanner_faults: Rng::fork(seed, 10),
        }
    }
}

#[derive(Debug, Clone)]
struct Timers {
    scanner: Periodic,
    ultrasonic: Option<Periodic>,
    camera: Option<Periodic>,
}

#[derive(Debug, Clone)]
pub struct Simulator {
    cfg: RobotConfig,
    world: World,
    scene: Scene,
    walkers: Vec<Walker>,
    rng: Streams,
    timers: Timers,
    pub faults: Faults,
    /// The world's scheduled faults; they set `faults` as they start and end.
    plan: FaultPlan,
    /// The odometry reading the robot last received and when (a dropout
    /// holds it; `None` while the counters report).
    odometry_held: Option<(crate::sensors::OdometryReading, u64)>,
    /// Errors fixed for this run, drawn from the seed.
    systematic: Systematic,
    slip: SlipProcess,
    actuator: ActuatorState,
    nav_error: NavError,

    time_us: u64,
    pose: Pose,
    v: f64,
    c: f64,
    v_set: f64,
    c_set: f64,
    mode: MovementMode,
    body: BodyPose,
    body_set: BodyPose,
    pan: f64,
    tilt: f64,
    carrying: Option<usize>,
    in_contact: bool,
    contacts: u64,

    odometry: Odometry,
    gyro: Option<Gyro>,
    estimator: Estimator,
    /// User frame set by `locate`: reported pose = frame ∘ world estimate.
    frame: Pose,
    battery: Battery,
    charging: bool,

    scan: Option<Arc<Scan>>,
    scan_seq: u64,
    nav_fix: Option<NavFix>,
    fix_seq: u64,
    plate: Option<PlateEvent>,
    plate_seq: u64,
    ultrasonic: Option<UltrasonicReading>,
    camera: Option<CameraFrame>,
    camera_seq: u64,
    events: Vec<SimEvent>,
}

impl Simulator {
    /// A robot standing still at the world's start pose. The estimate starts
    /// equal to the true pose; the first scan, fix and frames are taken at t = 0.
    pub fn new(cfg: RobotConfig, world: World, seed: u64) -> Result<Simulator, SimError> {
        cfg.validate().map_err(SimError::Config)?;
        let scene = world.scene();
        let start = world.start;
        let walkers = world.targets.iter().map(Walker::new).collect();
        let timers = Timers {
            scanner: Periodic::from_hz(cfg.scanner.rate_hz),
            ultrasonic: cfg
                .ultrasonic
                .as_ref()
                .map(|u| Periodic::from_hz(u.rate_hz)),
            camera: cfg.camera.as_ref().map(|c| Periodic::from_hz(c.rate_hz)),
        };
        let clearance = cfg.body_pose.as_ref().map_or(0.0, |b| b.initial_clearance);
        let body = BodyPose {
            roll: 0.0,
            pitch: 0.0,
            clearance,
        };
        let systematic = Systematic::draw(&cfg, seed);
        let mut sim = Simulator {
            gyro: cfg
                .gyro
                .as_ref()
                .map(|g| Gyro::new(g, systematic.gyro_bias)),
            systematic,
            slip: SlipProcess::default(),
            actuator: ActuatorState::default(),
            nav_error: NavError::default(),
            estimator: Estimator::new(&cfg, start),
            cfg,
            world,
            scene,
            walkers,
            rng: Streams::new(seed),
            timers,
            faults: Faults::default(),
            plan: FaultPlan::new(Vec::new(), seed),
            odometry_held: None,
            time_us: 0,
            pose: start,
            v: 0.0,
            c: 0.0,
            v_set: 0.0,
            c_set: 0.0,
            mode: MovementMode::Wheels,
            body,
            body_set: body,
            pan: 0.0,
            tilt: 0.0,
            carrying: None,
            in_contact: false,
            contacts: 0,
            odometry: Odometry::default(),
            frame: Pose::default(),
            battery: Battery::full(),
            charging: false,
            scan: None,
            scan_seq: 0,
            nav_fix: None,
            fix_seq: 0,
            plate: None,
            plate_seq: 0,
            ultrasonic: None,
            camera: None,
            camera_seq: 0,
            events: Vec::new(),
        };
        if let Some(c) = sim.contact_at(start) {
            return Err(SimError::StartInCollision(c));
        }
        sim.install_fault_plan(seed)?;
        // Pulse counters start at zero with the wheel count set.
        sim.odometry.update(
            &wheel_travel(&sim.systematic.wheels, 0.0, 0.0),
            &sim.cfg.odometry,
            0.0,
        );
        sim.sense_periodic();
        Ok(sim)
    }

    pub fn config(&self) -> &RobotConfig {
        &self.cfg
    }

    pub fn world(&self) -> &World {
        &self.world
    }

    /// The solids as they stand now (targets where they have walked to).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.time_us as f64 * 1e-6
    }

    /// Ground truth, world frame: what a trace records.
    pub fn true_pose(&self) -> Pose {
        self.pose
    }

    /// Actual (lagging) speed and curvature of the drive.
    pub fn true_speed(&self) -> f64 {
        self.v
    }

    pub fn true_curvature(&self) -> f64 {
        self.c
    }

    /// Whether the footprint is against something now.
    pub fn in_contact(&self) -> bool {
        self.in_contact
    }

    /// How many contacts have begun since the start.
    pub fn contact_count(&self) -> u64 {
        self.contacts
    }

    /// Where each target stands now, in world order.
    pub fn target_positions(&self) -> Vec<(String, Point2<f64>)> {
        self.world
            .targets
            .iter()
            .zip(&self.walkers)
            .map(|(t, w)| (t.name.clone(), w.position))
            .collect()
    }

    /// Events since the last call, oldest first.
    pub fn drain_events(&mut self) -> Vec<SimEvent> {
        std::mem::take(&mut self.events)
    }

    /// Speed setpoint, m/s, signed; the drive saturates at the top speed.
    pub fn set_speed(&mut self, v: f64) -> Result<(), SimError> {
        if !v.is_finite() {
            return Err(SimError::NotFinite("speed setpoint"));
        }
        self.v_set = v;
        Ok(())
    }

    /// Curvature setpoint, 1/m, left positive; saturates at the max curvature.
    pub fn set_curvature(&mut self, c: f64) -> Result<(), SimError> {
        if !c.is_finite() {
            return Err(SimError::NotFinite("curvature setpoint"));
        }
        self.c_set = c;
        Ok(())
    }

    pub fn set_setpoints(&mut self, v: f64, c: f64) -> Result<(), SimError> {
        self.set_speed(v)?;
        self.set_curvature(c)
    }

    pub fn setpoints(&self) -> (f64, f64) {
        (self.v_set, self.c_set)
    }

    /// `movemode(...)`. Rolking and parking need legs (a `rolking` config).
    pub fn set_movement_mode(&mut self, mode: MovementMode) -> Result<(), SimError> {
        if mode != MovementMode::Wheels && self.cfg.rolking.is_none() {
            return Err(SimError::Unsupported {
                robot: self.cfg.kind,
                what: "rolking or parking mode",
            });
        }
        self.mode = mode;
        Ok(())
    }

    /// `bodypose(r=..,p=..,rc=..)`: the body moves toward it at limited rates.
    pub fn set_body_pose(&mut self, target: BodyPose) -> Result<(), SimError> {
        if self.cfg.body_pose.is_none() {
            return Err(SimError::Unsupported {
                robot: self.cfg.kind,
                what: "body pose control",
            });
        }
        target.check().map_err(SimError::OutOfRange)?;
        self.body_set = target;
        Ok(())
    }

    /// Points the pan-tilt head (radians, relative to the robot).
    pub fn set_pan_tilt(&mut self, pan: f64, tilt: f64) -> Result<(), SimError> {
        let Some(cam) = &self.cfg.camera else {
            return Err(SimError::Unsupported {
                robot: self.cfg.kind,
                what: "pan-tilt head",
            });
        };
        if !(pan.is_finite() && tilt.is_finite()) {
            return Err(SimError::NotFinite("pan-tilt angle"));
        }
        if pan.abs() > cam.max_pan_deg.to_radians() || tilt.abs() > cam.max_tilt_deg.to_radians() {
            return Err(SimError::OutOfRange(format!(
                "pan {:.1} / tilt {:.1} deg is outside +/-{} / +/-{} deg",
                pan.to_degrees(),
                tilt.to_degrees(),
                cam.max_pan_deg,
                cam.max_tilt_deg
            )));
        }
        self.pan = pan;
        self.tilt = tilt;
        Ok(())
    }

    /// `locate(x,y,h)`: from now on the robot reports poses in a frame where
    /// its current estimate is `pose`.
    pub fn locate(&mut self, pose: Pose) -> Result<(), SimError> {
        if !pose.is_finite() {
            return Err(SimError::NotFinite("locate pose"));
        }
        self.frame = pose.compose(self.estimator.pose().inverse());
        Ok(())
    }

    /// The footprint rectangle at a reference pose.
    pub fn footprint(&self, at: Pose) -> Obb {
        let b = &self.cfg.body;
        let center = at.to_world(&Point2::new(b.length / 2.0 - b.rear_overhang, 0.0));
        Obb::new(center, at.h, b.length, b.width)
    }

    /// What the footprint would touch at `at`.
    pub fn contact_at(&self, at: Pose) -> Option<Contact> {
        let fp = self.footprint(at);
        if !fp.corners().iter().all(|&p| self.world.bounds.contains(p)) {
            return Some(Contact::OutOfBounds);
        }
        self.scene.overlapping(&fp).map(Contact::Solid)
    }

    /// Advances the simulation by `dt` seconds (rounded to whole microseconds).
    pub fn step(&mut self, dt: f64) -> Result<(), SimError> {
        if !(dt.is_finite() && (1e-6..=1.0).contains(&dt)) {
            return Err(SimError::BadTimeStep(dt));
        }
        let dt_us = (dt * 1e6).round() as u64;
        let dt = dt_us as f64 * 1e-6;
        // A step ending at t is governed by the faults in force at t.
        self.apply_fault_plan(self.time_us + dt_us);

        for (i, w) in self.walkers.iter_mut().enumerate() {
            w.step(dt);
            if let Some(s) = self.scene.find_mut(SolidRef::Target(i)) {
                s.shape.translate_to(w.position);
            }
        }

        let v0 = self.v;
        let (v1, c1) = self.drive(dt);
        let slip = self.draw_slip(dt);
        let ds_wheels = (v0 + v1) / 2.0 * dt;
        let fault_slip = self.plan.draw_slip(self.faults.odometry_slip);
        let ds = ds_wheels * (1.0 - slip.0) * (1.0 - fault_slip);
        let turn = c1 * self.systematic.curvature_gain;
        let dh = ds * turn * slip.1;
        // Side slip outward of the turn, from the lateral acceleration v^2 c.
        let lateral = -self.cfg.slip.lateral * v1 * v1 * turn * ds.abs();
        let before = self.pose;
        let moved = |f: f64| slide(advance(before, ds * f, dh * f), lateral * f, dh * f);
        let candidate = moved(1.0);

        let (rolled, turned) = match self.contact_at(candidate) {
            Some(contact) => {
                if !self.in_contact {
                    self.contacts += 1;
                    self.push(EventKind::ContactBegan(contact));
                }
                self.in_contact = true;
                self.v = 0.0;
                // Move up to the obstacle, so that the next push meets it at
                // once instead of creeping through a gap and re-touching.
                let f = self.free_fraction(&moved);
                self.pose = moved(f);
                (ds_wheels * f, dh * f)
            }
            None => {
                if self.in_contact {
                    self.push(EventKind::ContactEnded);
                }
                self.in_contact = false;
                self.pose = candidate;
                self.v = v1;
                (ds_wheels, dh)
            }
        };
        self.c = c1;
        self.time_us += dt_us;

        self.odometry.update(
            &wheel_travel(&self.systematic.wheels, rolled, turn),
            &self.cfg.odometry,
            self.faults.odometry_scale_error + self.systematic.odometry_scale,
        );
        let gyro_dh = match (&mut self.gyro, &self.cfg.gyro) {
            (Some(g), Some(gc)) => Some(g.update(gc, turned, dt, &mut self.rng.gyro)),
            _ => None,
        };
        if !self.hold_odometry() {
            self.estimator.integrate(&self.cfg, &self.odometry, gyro_dh);
        }
        self.detect_plates(before);
        self.update_battery(v0, dt);
        if let Some(bp) = &self.cfg.body_pose {
            self.body = self.body.toward(
                self.body_set,
                bp.angle_rate_deg_s.to_radians(),
                bp.clearance_rate,
                dt,
            );
        }
        self.sense_periodic();
        Ok(())
    }

    /// The largest fraction of a step's motion (to 2^-20 of it) that stays free.
    fn free_fraction(&self, moved: &impl Fn(f64) -> Pose) -> f64 {
        let (mut free, mut hit) = (0.0, 1.0);
        for _ in 0..20 {
            let mid = (free + hit) / 2.0;
            if self.contact_at(moved(mid)).is_some() {
                hit = mid;
            } else {
                free = mid;
            }
        }
        free
    }

    /// The actuators' response to the setpoints over one step: they follow what
    /// was set a dead time ago, the steering through its play.
    fn drive(&mut self, dt: f64) -> (f64, f64) {
        let (v_set, c_set) =
            self.actuator
                .follow(&self.cfg, self.time_us, self.v_set, self.curvature_target());
        let powered = !self.faults.dead_battery
            && !self.faults.drive_unresponsive
            && self.battery.charge > 0.0;
        let top = match (self.mode, &self.cfg.rolking) {
            (MovementMode::Rolking, Some(r)) => self.cfg.limits.max_speed * r.speed_factor,
            _ => self.cfg.limits.max_speed,
        };
        let v_target = if self.mode == MovementMode::Parking || !powered {
            0.0
        } else {
            v_set.clamp(-top, top)
        };
        (
            next_speed(self.v, v_target, &self.cfg.limits, dt),
            next_curvature(self.c, c_set, &self.cfg.limits, dt),
        )
    }

    /// (longitudinal slip, yaw factor) for this step.
    fn draw_slip(&mut self, dt: f64) -> (f64, f64) {
        let s: &SlipConfig = match (self.mode, &self.cfg.rolking) {
            (MovementMode::Rolking, Some(r)) => &r.slip,
            _ => &self.cfg.slip,
        };
        self.slip.step(s, dt, &mut self.rng.slip)
    }

    fn push(&mut self, kind: EventKind) {
        self.events.push(SimEvent {
            time: self.time(),
            kind,
        });
    }

    fn estimated_pose(&self) -> Pose {
        self.frame.compose(self.estimator.pose())
    }

    /// Replaces the robot's own estimate (world frame), as an external
    /// localisation would. Tests use it to start from a known error.
    pub fn reset_estimate(&mut self, world_pose: Pose) {
        self.estimator.reset(world_pose);
    }

    /// Sets the battery's state of charge (0..1), for low-battery tasks.
    pub fn set_battery_charge(&mut self, charge: f64) -> Result<(), SimError> {
        if !(charge.is_finite() && (0.0..=1.0).contains(&charge)) {
            return Err(SimError::OutOfRange(format!(
                "battery charge {charge} is outside 0..1"
            )));
        }
        self.battery.charge = charge;
        Ok(())
    }

    /// Everything the robot's software can see now.
    pub fn snapshot(&self) -> SensorSnapshot {
        let dead = self.faults.dead_battery;
        let bc = &self.cfg.battery;
        SensorSnapshot {
            time: self.time(),
            pose: self.estimated_pose(),
            speed: self.v,
            curvature: self.c,
            steering_angle: steering_angle(&self.cfg.steering, self.c),
            scan: self.scan.clone(),
            odometry: match &self.odometry_held {
                Some((held, _)) => held.clone(),
                None => self.odometry.reading(&self.cfg.odometry),
            },
            odometry_time: self.odometry_time(),
            gyro: self.gyro.as_ref().map(Gyro::reading),
            plate: self.plate,
            nav_fix: self.nav_fix.map(|f| NavFix {
                pose: self.frame.compose(f.pose),
                ..f
            }),
            ultrasonic: self.ultrasonic,
            camera: self.camera.clone(),
            battery: BatteryReading {
                voltage: if dead {
                    bc.v_empty
                } else {
                    self.battery.voltage(bc)
                },
                charge: if dead { 0.0 } else { self.battery.charge },
                charging: self.charging,
            },
            movement_mode: self.mode,
            body_pose: self.cfg.body_pose.as_ref().map(|_| self.body),
            carrying: self.carrying.map(|i| self.world.pickup_boxes[i].id.clone()),
            blocked: self.in_contact,
        }
    }
}
