//! The simulator's side of fault injection (`crate::faults`): installing the
//! world's plan, bringing the active faults to each step's time, placing and
//! removing appearing obstacles, and holding the odometry during a dropout.

use super::{EventKind, SimError, Simulator};
use crate::faults::{FaultKind, FaultPlan, ObstacleChange};
use crate::geometry::{Circle, Point2, Shape, Solid, SolidRef};

impl Simulator {
    /// Checks the world's faults against this robot, adds a hidden solid for
    /// each appearing obstacle and applies what is in force at t = 0.
    pub(super) fn install_fault_plan(&mut self, seed: u64) -> Result<(), SimError> {
        let specs = self.world.faults.clone();
        for s in &specs {
            s.check().map_err(SimError::OutOfRange)?;
            if let Some(what) = crate::faults::fit::missing_part(&s.kind, &self.cfg) {
                return Err(SimError::Unsupported {
                    robot: self.cfg.kind,
                    what,
                });
            }
        }
        let mut solids = self.scene.solids().to_vec();
        for (i, s) in specs.iter().enumerate() {
            if let FaultKind::ObstacleAppears { radius, .. } = s.kind {
                let mut solid = Solid::new(
                    Shape::Circle(Circle::new(Point2::new(0.0, 0.0), radius)),
                    SolidRef::Fault(i),
                );
                solid.active = false;
                solids.push(solid);
            }
        }
        self.scene = crate::geometry::Scene::new(solids);
        self.plan = FaultPlan::new(specs, seed);
        self.apply_fault_plan(0);
        Ok(())
    }

    /// Brings the faults to what is in force at `t_us`, logging the edges.
    pub(super) fn apply_fault_plan(&mut self, t_us: u64) {
        let changes = self.plan.advance(t_us, &mut self.faults);
        for (name, began) in self.plan.edges(t_us) {
            let kind = if began {
                EventKind::FaultBegan(name.to_string())
            } else {
                EventKind::FaultEnded(name.to_string())
            };
            self.events.push(super::SimEvent {
                time: t_us as f64 * 1e-6,
                kind,
            });
        }
        for c in changes {
            self.show_obstacle(c);
        }
        match (self.faults.odometry_dropout, self.odometry_held.is_some()) {
            (true, false) => {
                let reading = self.odometry.reading(&self.cfg.odometry);
                self.odometry_held = Some((reading, self.time_us));
            }
            (false, true) => self.odometry_held = None,
            _ => {}
        }
    }

    /// An appearing obstacle stands `distance` ahead of the footprint's front
    /// on the robot's heading, so it never appears on top of the robot.
    fn show_obstacle(&mut self, c: ObstacleChange) {
        let b = &self.cfg.body;
        let ahead = b.length - b.rear_overhang + c.distance + c.radius;
        let center = self.pose.to_world(&Point2::new(ahead, 0.0));
        if let Some(s) = self.scene.find_mut(SolidRef::Fault(c.index)) {
            s.shape.translate_to(center);
            s.active = c.appear;
        }
    }

    /// The counters are not reporting: the estimate must not integrate.
    pub(super) fn hold_odometry(&self) -> bool {
        self.odometry_held.is_some()
    }

    /// Time of the odometry reading the robot holds, s.
    pub(super) fn odometry_time(&self) -> f64 {
        self.odometry_held
            .as_ref()
            .map_or(self.time_us, |(_, t)| *t) as f64
            * 1e-6
    }

    /// Without power or with its controller silent the steering holds still.
    pub(super) fn curvature_target(&self) -> f64 {
        if self.faults.dead_battery || self.faults.drive_unresponsive {
            self.c
        } else {
            self.c_set
        }
    }

    pub fn fault_plan(&self) -> &FaultPlan {
        &self.plan
    }
}
