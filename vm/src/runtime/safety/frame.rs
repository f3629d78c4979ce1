//! The known map stays in the frame the robot reported when the VM started; a
//! `locate` moves the robot's estimate to another frame. The VM keeps the rigid
//! transform from the estimate's frame to the map's, so that a `gotoxy` target
//! given after a `locate` is checked against the right walls.

use ilmr_hal::Pose;

/// A rigid transform with its sine and cosine worked out once, for carrying
/// many points: `apply` gives bit for bit the position `compose` gives.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rigid {
    x: f64,
    y: f64,
    s: f64,
    c: f64,
}

impl Rigid {
    pub fn new(p: Pose) -> Rigid {
        let (s, c) = p.h.sin_cos();
        Rigid {
            x: p.x,
            y: p.y,
            s,
            c,
        }
    }

    /// The sine and cosine of the turn.
    pub fn sin_cos(&self) -> (f64, f64) {
        (self.s, self.c)
    }

    /// The point `p`, given in the transform's frame, in its parent.
    pub fn apply(&self, p: (f64, f64)) -> (f64, f64) {
        (
            self.x + self.c * p.0 - self.s * p.1,
            self.y + self.s * p.0 + self.c * p.1,
        )
    }

    /// From the known map's frame to the estimate's.
    pub fn from_map(map_from_estimate: Pose) -> Rigid {
        Rigid::new(inverse(map_from_estimate))
    }

    /// From the estimate's frame to the known map's.
    pub fn to_map(map_from_estimate: Pose) -> Rigid {
        Rigid::new(map_from_estimate)
    }
}

/// `a` then `b`: the pose `b`, given in the frame `a`, expressed in `a`'s parent.
fn compose(a: Pose, b: Pose) -> Pose {
    let (x, y) = Rigid::new(a).apply((b.x, b.y));
    // Headings unfolded: only their sines and cosines are used.
    Pose { x, y, h: a.h + b.h }
}

fn inverse(p: Pose) -> Pose {
    let (s, c) = p.h.sin_cos();
    Pose {
        x: -c * p.x - s * p.y,
        y: s * p.x - c * p.y,
        h: -p.h,
    }
}

/// The transform after a `locate` that says the robot, estimated at `before` a
/// moment ago, is at `after`: the robot has not moved, so both name the same
/// place of the map.
pub(crate) fn relocated(map_from_estimate: Pose, before: Pose, after: Pose) -> Pose {
    compose(compose(map_from_estimate, before), inverse(after))
}

/// Points on the surfaces of the known map's solids, `SPACING` apart, in the
/// map's frame: what the robot would see of its site plan if it could look
/// everywhere. The supervisor checks them where the scanner cannot look
/// (behind a reversing robot).
pub(crate) fn surface_points(map: &ilmr_hal::KnownMap) -> Vec<(f64, f64)> {
    const SPACING: f64 = 0.05;
    let mut out = Vec::new();
    for s in &map.solids {
        let (dx, dy) = (s.b.0 - s.a.0, s.b.1 - s.a.1);
        let len = dx.hypot(dy);
        if !(len.is_finite() && s.radius.is_finite()) {
            continue;
        }
        if len < 1e-9 {
            // A round solid: its rim.
            let n = ((std::f64::consts::TAU * s.radius / SPACING).ceil() as usize).clamp(8, 10_000);
            for i in 0..n {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                out.push((s.a.0 + s.radius * a.cos(), s.a.1 + s.radius * a.sin()));
            }
            continue;
        }
        let (ux, uy) = (dx / len, dy / len);
        let (nx, ny) = (-uy * s.radius, ux * s.radius);
        let n = ((len / SPACING).ceil() as usize).clamp(1, 1_000_000);
        for i in 0..=n {
            let t = len * i as f64 / n as f64;
            let (cx, cy) = (s.a.0 + ux * t, s.a.1 + uy * t);
            out.push((cx + nx, cy + ny));
            out.push((cx - nx, cy - ny));
        }
        // The ends of a wall piece (a door post) face the opening.
        for end in [s.a, s.b] {
            out.push(end);
        }
    }
    out
}

pub(crate) fn to_map(map_from_estimate: Pose, p: (f64, f64)) -> (f64, f64) {
    Rigid::to_map(map_from_estimate).apply(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: (f64, f64), b: (f64, f64)) -> bool {
        (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9
    }

    #[test]
    fn without_a_locate_the_frames_agree() {
        assert!(close(to_map(Pose::default(), (3.0, -2.0)), (3.0, -2.0)));
    }

    #[test]
    fn a_locate_maps_the_new_frame_back_onto_the_old() {
        // The robot stands at (8, 5) facing +y, and is told it is at the origin
        // facing +x: one metre ahead in the new frame is (8, 6) on the map.
        let t = relocated(
            Pose::default(),
            Pose::new(8.0, 5.0, std::f64::consts::FRAC_PI_2),
            Pose::default(),
        );
        assert!(close(to_map(t, (0.0, 0.0)), (8.0, 5.0)));
        assert!(close(to_map(t, (1.0, 0.0)), (8.0, 6.0)));
        // A second locate composes with the first.
        let t2 = relocated(t, Pose::new(1.0, 0.0, 0.0), Pose::new(10.0, 10.0, 0.0));
        assert!(close(to_map(t2, (10.0, 10.0)), (8.0, 6.0)));
        assert!(close(Rigid::from_map(t2).apply((8.0, 6.0)), (10.0, 10.0)));
    }

    #[test]
    fn a_wall_is_seen_on_both_faces() {
        let map = ilmr_hal::KnownMap {
            bounds: None,
            solids: vec![ilmr_hal::Solid {
                a: (0.0, 0.0),
                b: (1.0, 0.0),
                radius: 0.1,
                name: None,
            }],
        };
        let pts = surface_points(&map);
        assert!(pts.iter().any(|p| close(*p, (0.5, 0.1))));
        assert!(pts.iter().any(|p| close(*p, (0.5, -0.1))));
        assert!(pts.iter().all(|p| p.1.abs() <= 0.1 + 1e-12));
    }
}
