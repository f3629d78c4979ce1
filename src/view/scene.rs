//! The pieces Foxglove's messages are made of: times, poses, transforms, and the
//! scene entities of the world and of lines on the floor.

use foxglove::schemas::{
    Color, CubePrimitive, CylinderPrimitive, FrameTransform, FrameTransforms, KeyValuePair,
    LinePrimitive, Point3, Pose, Quaternion, SceneEntity, SceneUpdate, Timestamp, Vector3,
    line_primitive,
};
use ilmr_sim::geometry::Shape;
use ilmr_sim::{PlaneVector, World};

use super::{FRAME, ROBOT_FRAME};

const GREY: Color = Color {
    r: 0.55,
    g: 0.55,
    b: 0.55,
    a: 1.0,
};
pub(super) const PATH_COLOR: Color = Color {
    r: 0.15,
    g: 0.15,
    b: 0.15,
    a: 1.0,
};
pub(super) const TRAJECTORY_COLOR: Color = Color {
    r: 0.1,
    g: 0.45,
    b: 0.85,
    a: 1.0,
};

/// Nanoseconds of the run's logical time.
pub fn nanos(t: f64) -> u64 {
    (t.max(0.0) * 1e9).round() as u64
}

pub(super) fn stamp(t: f64) -> Timestamp {
    let ns = nanos(t);
    // A run of more than 136 years of logical time is cut to the last second that fits.
    let sec = u32::try_from(ns / 1_000_000_000).unwrap_or(u32::MAX);
    Timestamp::new(sec, (ns % 1_000_000_000) as u32)
}

pub(super) fn point(x: f64, y: f64) -> Point3 {
    Point3 { x, y, z: 0.0 }
}

pub(super) fn pose(x: f64, y: f64, z: f64, h: f64) -> Pose {
    Pose {
        position: Some(Vector3 { x, y, z }),
        orientation: Some(heading(h)),
    }
}

pub(super) fn heading(h: f64) -> Quaternion {
    Quaternion {
        x: 0.0,
        y: 0.0,
        z: (h / 2.0).sin(),
        w: (h / 2.0).cos(),
    }
}

pub(super) fn transform(t: f64, x: f64, y: f64, h: f64) -> FrameTransforms {
    FrameTransforms {
        transforms: vec![FrameTransform {
            timestamp: Some(stamp(t)),
            parent_frame_id: FRAME.into(),
            child_frame_id: ROBOT_FRAME.into(),
            translation: Some(Vector3 { x, y, z: 0.0 }),
            rotation: Some(heading(h)),
        }],
    }
}

pub(super) fn entity(t: f64, id: String) -> SceneEntity {
    SceneEntity {
        timestamp: Some(stamp(t)),
        frame_id: FRAME.into(),
        id,
        ..SceneEntity::default()
    }
}

/// A line strip on the floor, as an entity of its own that is kept (no lifetime).
pub(super) fn strip(
    t: f64,
    id: String,
    label: Option<String>,
    points: Vec<Point3>,
    color: Color,
    thickness: f64,
) -> SceneUpdate {
    let metadata = label
        .map(|value| KeyValuePair {
            key: "command".into(),
            value,
        })
        .into_iter()
        .collect();
    SceneUpdate {
        deletions: Vec::new(),
        entities: vec![SceneEntity {
            metadata,
            lines: vec![LinePrimitive {
                r#type: line_primitive::Type::LineStrip as i32,
                pose: Some(pose(0.0, 0.0, 0.0, 0.0)),
                thickness,
                scale_invariant: false,
                points,
                color: Some(color),
                colors: Vec::new(),
                indices: Vec::new(),
            }],
            ..entity(t, id)
        }],
    }
}

/// The world's solids as a scene: walls, obstacles and boxes as cubes, round things as
/// cylinders, 1 m high.
pub(super) fn scene(w: &World) -> SceneUpdate {
    let cube = |center: ilmr_sim::Point2<f64>, h: f64, length: f64, width: f64| CubePrimitive {
        pose: Some(pose(center.x, center.y, 0.5, h)),
        size: Some(Vector3 {
            x: length,
            y: width,
            z: 1.0,
        }),
        color: Some(GREY),
    };
    let mut cubes = Vec::new();
    let mut cylinders = Vec::new();
    for wall in &w.walls {
        for &(a, b) in &wall.pieces {
            let mid = ilmr_sim::Point2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
            let h = (b.y - a.y).atan2(b.x - a.x);
            cubes.push(cube(mid, h, (a - b).hypot(), wall.thickness));
        }
    }
    let mut obb = |o: &ilmr_sim::geometry::Obb| {
        let h = o.axis.y.atan2(o.axis.x);
        cubes.push(cube(o.center, h, 2.0 * o.half.x, 2.0 * o.half.y));
    };
    for o in &w.obstacles {
        match o {
            Shape::Box(b) => obb(b),
            Shape::Circle(c) => cylinders.push(CylinderPrimitive {
                pose: Some(pose(c.center.x, c.center.y, 0.5, 0.0)),
                size: Some(Vector3 {
                    x: 2.0 * c.radius,
                    y: 2.0 * c.radius,
                    z: 1.0,
                }),
                bottom_scale: 1.0,
                top_scale: 1.0,
                color: Some(GREY),
            }),
        }
    }
    for b in &w.pickup_boxes {
        obb(&b.shape);
    }
    SceneUpdate {
        deletions: Vec::new(),
        entities: vec![SceneEntity {
            cubes,
            cylinders,
            ..entity(0.0, w.name.clone())
        }],
    }
}
