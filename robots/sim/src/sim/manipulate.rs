//! `manipulate(take)` and `manipulate(leave)`: Workpartner's hands pick a box
//! off the floor in front of it and set it down again.

use super::{EventKind, SimError, Simulator};
use crate::config::RobotKind;
use crate::geometry::{PlaneVector, Point2, Shape, SolidRef, Vector2};

/// How far from the gripper point a box can be taken, m.
const REACH: f64 = 0.8;

impl Simulator {
    /// `manipulate(take)`: picks up the nearest box within reach of the front.
    pub fn take_box(&mut self) -> Result<String, SimError> {
        self.require_manipulator()?;
        if self.carrying.is_some() {
            return Err(SimError::Manipulation("already carrying a box".into()));
        }
        if self.v.abs() > 0.01 {
            return Err(SimError::Manipulation("the robot must stand still".into()));
        }
        let b = &self.cfg.body;
        let grip = self
            .pose
            .to_world(&Point2::new(b.length - b.rear_overhang + 0.3, 0.0));
        let nearest = self
            .scene
            .solids()
            .iter()
            .filter(|s| s.active)
            .filter_map(|s| match s.what {
                SolidRef::PickupBox(i) => Some((i, (s.shape.center() - grip).hypot())),
                _ => None,
            })
            .filter(|&(_, d)| d <= REACH)
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        let Some((i, _)) = nearest else {
            return Err(SimError::Manipulation(format!(
                "no box within {REACH} m of the front"
            )));
        };
        if let Some(s) = self.scene.find_mut(SolidRef::PickupBox(i)) {
            s.active = false;
        }
        self.carrying = Some(i);
        let id = self.world.pickup_boxes[i].id.clone();
        self.push(EventKind::BoxTaken(id.clone()));
        Ok(id)
    }

    /// `manipulate(leave)`: sets the carried box down in front of the robot.
    pub fn leave_box(&mut self) -> Result<String, SimError> {
        self.require_manipulator()?;
        let Some(i) = self.carrying else {
            return Err(SimError::Manipulation("not carrying a box".into()));
        };
        let b = &self.cfg.body;
        let Some(solid) = self.scene.find(SolidRef::PickupBox(i)) else {
            return Err(SimError::Manipulation(
                "the carried box is not in the scene".into(),
            ));
        };
        let Shape::Box(mut shape) = solid.shape else {
            return Err(SimError::Manipulation(
                "the carried box is not a box".into(),
            ));
        };
        shape.center = self.pose.to_world(&Point2::new(
            b.length - b.rear_overhang + 0.1 + shape.half.x,
            0.0,
        ));
        shape.axis = Vector2::from_angle(self.pose.h);
        if self
            .scene
            .solids()
            .iter()
            .any(|s| s.active && s.shape.overlaps_box(&shape))
            || !shape
                .corners()
                .iter()
                .all(|&p| self.world.bounds.contains(p))
        {
            return Err(SimError::Manipulation(
                "no free floor in front of the robot".into(),
            ));
        }
        if let Some(s) = self.scene.find_mut(SolidRef::PickupBox(i)) {
            s.shape = Shape::Box(shape);
            s.active = true;
        }
        self.carrying = None;
        let id = self.world.pickup_boxes[i].id.clone();
        self.push(EventKind::BoxLeft(id.clone()));
        Ok(id)
    }

    fn require_manipulator(&self) -> Result<(), SimError> {
        if self.cfg.kind == RobotKind::Workpartner {
            Ok(())
        } else {
            Err(SimError::Unsupported {
                robot: self.cfg.kind,
                what: "manipulator",
            })
        }
    }
}
