//! Coloured objects found by the camera and ranged by the scanner
//! (Figure 33), and where the laser pointer on the same head points
//! (`savepos(name,laser)`), as the HAL reports them.

use crate::geometry::{PlaneVector, Point2, Pose, Vector2};
use crate::sensors::{CameraFrame, Scan};
use ilmr_hal::{Detection, Side};
use ilmr_model::RobotModel;

/// World points of the scan's beams that returned, with their bearing from
/// the robot's heading.
pub fn scan_points(scan: &Scan, pose: Pose) -> Vec<(usize, Point2<f64>)> {
    scan.ranges
        .iter()
        .enumerate()
        .filter(|(_, r)| **r < scan.max_range)
        .map(|(i, _)| (i, pose.to_world(&scan.local_point(i))))
        .collect()
}

fn side_of(bearing: f64) -> Side {
    if bearing >= 0.0 {
        Side::Left
    } else {
        Side::Right
    }
}

/// Camera detections whose colour names a model object (`user yellow 30`),
/// placed where the scanner measures something on the camera's bearing.
/// A detection the scanner does not confirm is left out, as Figure 33 does.
/// The scan's points are worked out only for a frame that has such a
/// detection: most frames have none, and this runs every tick.
pub fn camera_objects(
    model: &RobotModel,
    frame: &CameraFrame,
    eye: Point2<f64>,
    pose: Pose,
    scan: &Scan,
    out: &mut Vec<Detection>,
) {
    let mut points: Option<Vec<(usize, Point2<f64>)>> = None;
    for d in &frame.detections {
        let colour = format!("{:?}", d.colour);
        let Some(object) = model.objects.iter().find(|o| {
            o.params
                .first()
                .is_some_and(|c| c.eq_ignore_ascii_case(&colour))
        }) else {
            continue;
        };
        let bearing = pose.h + d.bearing;
        let half = (d.angular_size / 2.0).max(1f64.to_radians());
        let nearest = points
            .get_or_insert_with(|| scan_points(scan, pose))
            .iter()
            .filter(|(_, p)| {
                let to = *p - eye;
                crate::geometry::wrap_angle(to.polar_angle() - bearing).abs() <= half
            })
            .map(|(_, p)| (p - eye).hypot())
            .fold(f64::INFINITY, f64::min);
        if !nearest.is_finite() {
            continue;
        }
        let radius = nearest * (d.angular_size / 2.0).tan();
        let centre = eye + Vector2::from_angle(bearing) * (nearest + radius);
        out.push(Detection {
            sensor: "camera".into(),
            object: object.name.clone(),
            x: centre.x,
            y: centre.y,
            h: bearing,
            side: side_of(d.bearing),
        });
    }
}

/// Where the laser pointer's beam meets something, on the floor plan: the
/// slant distance `frame.laser` taken along the head's pan, shortened by its
/// tilt. Reported as a detection by the `laser` device (object `spot`),
/// heading along the beam, so that `savepos(name,laser)` stores the point.
pub fn laser_spot(
    model: &RobotModel,
    frame: &CameraFrame,
    eye: Point2<f64>,
    pose: Pose,
    out: &mut Vec<Detection>,
) {
    let (Some(device), Some(slant)) = (model.device("laser"), frame.laser) else {
        return;
    };
    let along = slant * frame.tilt.cos();
    let bearing = pose.h + frame.pan;
    let spot = eye + Vector2::from_angle(bearing) * along;
    if !spot.coords.is_finite() {
        return;
    }
    out.push(Detection {
        sensor: device.name.clone(),
        object: "spot".into(),
        x: spot.x,
        y: spot.y,
        h: bearing,
        side: side_of(frame.pan),
    });
}
