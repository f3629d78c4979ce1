//! The simulator's sensing pass: plate crossings, the battery, and the
//! readings that come at their own rates (navigation fix, scan, ultrasonic,
//! camera).

use super::estimate::Estimator;
use super::{EventKind, Simulator};
use crate::geometry::{PlaneVector, Pose, Shape, SolidRef};
use crate::kinematics::MovementMode;
use crate::sensors::{
    CameraFrame, Head, Load, NavFix, PlateEvent, Scan, ScanNoise, ScanPose, UltrasonicReading,
    Visible, crossings, measure_ultrasonic, observe, quantise,
};
use std::sync::Arc;

impl Simulator {
    pub(super) fn detect_plates(&mut self, before: Pose) {
        let Some(pc) = self.cfg.plates.clone() else {
            return;
        };
        let hits = crossings(&pc, &self.world.plates, before, self.pose);
        for (plate, lateral) in hits {
            let measured = quantise(
                lateral + self.rng.plates.gauss(pc.noise_sigma),
                pc.resolution,
            );
            let ev = PlateEvent {
                seq: self.plate_seq,
                time: self.time(),
                plate,
                lateral: measured,
            };
            self.plate_seq += 1;
            self.plate = Some(ev);
            self.push(EventKind::Plate(ev));
        }
    }

    pub(super) fn update_battery(&mut self, v0: f64, dt: f64) {
        let at_charger = self
            .world
            .charger
            .as_ref()
            .is_some_and(|c| (c.position - self.pose.position()).hypot() <= c.radius);
        self.charging = at_charger && self.v.abs() < 1e-3 && !self.faults.dead_battery;
        let rolling_factor = match (self.mode, &self.cfg.rolking) {
            (MovementMode::Rolking, Some(r)) => r.power_factor,
            _ => 1.0,
        };
        let load = Load {
            speed: self.v,
            accel: (self.v - v0) / dt,
            mass: self.cfg.mass_kg,
            rolling_factor,
            charging: self.charging,
        };
        let had_charge = self.battery.charge > 0.0;
        self.battery.update(&self.cfg.battery, &load, dt);
        if had_charge && self.battery.charge <= 0.0 {
            self.push(EventKind::BatteryEmpty);
        }
    }

    /// Readings that come at their own rates: navigation fix, scan,
    /// ultrasonic, camera.
    pub(super) fn sense_periodic(&mut self) {
        let now = self.time_us;
        let time = self.time();
        let counts = self.odometry.pulses();
        let odometry_held = self.odometry_held.is_some();
        let fix_stale = self.faults.nav_fix_stale;
        if let (
            Estimator::Pilot {
                dr,
                dr_timer,
                fix_timer,
            },
            Some(nc),
        ) = (&mut self.estimator, &self.cfg.nav)
        {
            if dr_timer.due(now) && !odometry_held {
                dr.update(counts);
            }
            if fix_timer.due(now) && !fix_stale {
                let pose = match (&self.nav_fix, self.faults.nav_fix_frozen) {
                    (Some(old), true) => old.pose,
                    _ => {
                        let [ex, ey, eh] = self.nav_error.next(nc, &mut self.rng.nav);
                        Pose::new(self.pose.x + ex, self.pose.y + ey, self.pose.h + eh)
                    }
                };
                dr.reset(pose);
                self.nav_fix = Some(NavFix {
                    seq: self.fix_seq,
                    time,
                    pose,
                });
                self.fix_seq += 1;
            }
        }
        if self.timers.scanner.due(now) && !self.faults.scanner_dropout {
            let at = ScanPose {
                truth: self.pose,
                estimate: self.estimated_pose(),
                speed: self.v,
                turn_rate: self.v * self.c * self.systematic.curvature_gain,
            };
            let noise = ScanNoise {
                range: &mut self.rng.scanner,
                artefacts: &mut self.rng.scanner_faults,
            };
            let scan = Scan::take(
                &self.scene,
                &self.cfg.scanner,
                at,
                time,
                self.scan_seq,
                noise,
            );
            self.scan_seq += 1;
            self.scan = Some(Arc::new(scan));
        }
        if let (Some(t), Some(uc)) = (&mut self.timers.ultrasonic, &self.cfg.ultrasonic)
            && t.due(now)
        {
            let ranges = measure_ultrasonic(
                uc,
                &self.scene,
                self.pose,
                self.cfg.body.rear_overhang,
                &mut self.rng.ultrasonic,
            );
            self.ultrasonic = Some(UltrasonicReading { time, ranges });
        }
        if let (Some(t), Some(cc)) = (&mut self.timers.camera, &self.cfg.camera)
            && t.due(now)
        {
            let things = self.visible_things();
            let head = Head {
                pan: self.pan,
                tilt: self.tilt,
            };
            let (detections, laser) = observe(
                cc,
                &self.scene,
                &things,
                self.pose,
                &head,
                &mut self.rng.camera,
            );
            self.camera = Some(CameraFrame {
                seq: self.camera_seq,
                time,
                pan: self.pan,
                tilt: self.tilt,
                detections,
                laser,
            });
            self.camera_seq += 1;
        }
    }

    /// Coloured things the camera may see: targets, boxes on the ground, the charger.
    pub(super) fn visible_things(&self) -> Vec<Visible> {
        let mut out: Vec<Visible> = self
            .world
            .targets
            .iter()
            .zip(&self.walkers)
            .enumerate()
            .map(|(i, (t, w))| Visible {
                name: t.name.clone(),
                colour: t.colour,
                position: w.position,
                radius: t.radius,
                solid: Some(SolidRef::Target(i)),
            })
            .collect();
        for (i, b) in self.world.pickup_boxes.iter().enumerate() {
            let Some(colour) = b.colour else { continue };
            if self.carrying == Some(i) {
                continue;
            }
            let Some(solid) = self.scene.find(SolidRef::PickupBox(i)) else {
                continue;
            };
            if let Shape::Box(shape) = solid.shape {
                out.push(Visible {
                    name: b.id.clone(),
                    colour,
                    position: shape.center,
                    radius: shape.half.x.max(shape.half.y),
                    solid: Some(SolidRef::PickupBox(i)),
                });
            }
        }
        if let Some(ch) = &self.world.charger
            && let Some(colour) = ch.colour
        {
            out.push(Visible {
                name: "charger".to_string(),
                colour,
                position: ch.position,
                radius: 0.3,
                solid: None,
            });
        }
        out
    }
}
