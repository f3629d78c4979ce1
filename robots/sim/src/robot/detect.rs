//! What the robot recognises, as the HAL reports it: coloured objects found
//! by the camera and ranged by the scanner (Figure 33), and door openings
//! found in the scan.

use crate::geometry::{Pose, Vec2};
use crate::sensors::{CameraFrame, Scan};
use ilmr_hal::{Detection, Side};
use ilmr_model::RobotModel;

/// A range step at least this large starts or ends an opening, m.
const EDGE_JUMP: f64 = 0.5;

/// World points of the scan's beams that returned, with their bearing from
/// the robot's heading.
pub fn scan_points(scan: &Scan, pose: Pose) -> Vec<(usize, Vec2)> {
    scan.ranges
        .iter()
        .enumerate()
        .filter(|(_, r)| **r < scan.max_range)
        .map(|(i, r)| {
            let local = scan.mount + Vec2::from_angle(scan.bearing(i)).scale(*r);
            (i, pose.transform(local))
        })
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
pub fn camera_objects(
    model: &RobotModel,
    frame: &CameraFrame,
    eye: Vec2,
    pose: Pose,
    points: &[(usize, Vec2)],
    out: &mut Vec<Detection>,
) {
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
            .iter()
            .filter(|(_, p)| {
                let to = *p - eye;
                crate::geometry::wrap_angle(to.angle() - bearing).abs() <= half
            })
            .map(|(_, p)| p.distance(eye))
            .fold(f64::INFINITY, f64::min);
        if !nearest.is_finite() {
            continue;
        }
        let radius = nearest * (d.angular_size / 2.0).tan();
        let centre = eye + Vec2::from_angle(bearing).scale(nearest + radius);
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

/// Openings in the scan as wide as the model's `door` (its two parameters
/// are the smallest and largest width): a run of beams that reach at least
/// `EDGE_JUMP` further than the returns on both sides of it. The door's
/// pose is the middle of the gap, heading through it away from the robot.
pub fn doors(model: &RobotModel, scan: &Scan, pose: Pose, out: &mut Vec<Detection>) {
    let Some(door) = model.object("door") else {
        return;
    };
    let widths: Vec<f64> = door
        .params
        .iter()
        .filter_map(|p| p.parse::<f64>().ok())
        .collect();
    let (min_w, max_w) = match widths.as_slice() {
        [a, b, ..] => (a.min(*b), a.max(*b)),
        _ => return,
    };
    let r = &scan.ranges;
    let point =
        |i: usize| pose.transform(scan.mount + Vec2::from_angle(scan.bearing(i)).scale(r[i]));
    let mut i = 0;
    while i + 1 < r.len() {
        if r[i + 1] - r[i] < EDGE_JUMP || r[i] >= scan.max_range {
            i += 1;
            continue;
        }
        // Beams i+1.. go through the opening until one comes back near.
        let start = i;
        let mut j = i + 1;
        while j < r.len() && r[j] - r[start] >= EDGE_JUMP && r[j] - EDGE_JUMP > 0.0 {
            j += 1;
        }
        if j >= r.len() || r[j] >= scan.max_range {
            i = j;
            continue;
        }
        let (a, b) = (point(start), point(j));
        let width = a.distance(b);
        if (min_w..=max_w).contains(&width) {
            let mid = (a + b).scale(0.5);
            let along = b - a;
            // The normal to the gap that points away from the robot.
            let mut normal = along.perp();
            if normal.dot(mid - pose.position()) < 0.0 {
                normal = normal.scale(-1.0);
            }
            let rel = crate::geometry::wrap_angle((mid - pose.position()).angle() - pose.h);
            out.push(Detection {
                sensor: "scanner".into(),
                object: door.name.clone(),
                x: mid.x,
                y: mid.y,
                h: normal.angle(),
                side: side_of(rel),
            });
        }
        i = j;
    }
}
