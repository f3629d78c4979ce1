//! Reference paths as straight and circular segments in the travel frame (the heading
//! of motion, which is the body heading plus pi when reversing). Closed forms make the
//! projection and the split used by linking exact and allocation-free.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

pub(crate) fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI { w - TAU } else { w }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Seg {
    pub x: f64,
    pub y: f64,
    /// Travel heading at the start.
    pub h: f64,
    /// Geometric curvature (dh/ds) in the travel frame; 0 for a line.
    pub k: f64,
    pub len: f64,
    /// Arc length of the path at this segment's start.
    pub s0: f64,
}

impl Seg {
    pub fn at(&self, t: f64) -> (f64, f64, f64) {
        if self.k.abs() < 1e-12 {
            (self.x + t * self.h.cos(), self.y + t * self.h.sin(), self.h)
        } else {
            let h1 = self.h + self.k * t;
            (
                self.x + (h1.sin() - self.h.sin()) / self.k,
                self.y - (h1.cos() - self.h.cos()) / self.k,
                h1,
            )
        }
    }

    /// Arc length along this segment of the point nearest to (px, py), unclamped.
    pub fn project(&self, px: f64, py: f64) -> f64 {
        if self.k.abs() < 1e-12 {
            (px - self.x) * self.h.cos() + (py - self.y) * self.h.sin()
        } else {
            let r = 1.0 / self.k;
            let (cx, cy) = (self.x - r * self.h.sin(), self.y + r * self.h.cos());
            let a0 = (self.y - cy).atan2(self.x - cx);
            let a = (py - cy).atan2(px - cx);
            wrap(a - a0) / self.k
        }
    }
}

/// A path: segments joined end to end, followed in one direction of travel.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Path {
    pub segs: Vec<Seg>,
    /// +1 forwards, -1 reversing.
    pub dir: f64,
    start: (f64, f64, f64),
}

impl Path {
    /// Empties the path (keeping its buffer) and starts it at a travel pose.
    pub fn reset(&mut self, x: f64, y: f64, h: f64, dir: f64) {
        self.segs.clear();
        self.dir = dir;
        self.start = (x, y, h);
    }

    pub fn total(&self) -> f64 {
        self.segs.last().map_or(0.0, |s| s.s0 + s.len)
    }

    pub fn end(&self) -> (f64, f64, f64) {
        self.segs.last().map_or(self.start, |s| s.at(s.len))
    }

    pub fn line(&mut self, len: f64) {
        let (x, y, h) = self.end();
        if len > 0.0 {
            let s0 = self.total();
            self.segs.push(Seg {
                x,
                y,
                h,
                k: 0.0,
                len,
                s0,
            });
        }
    }

    /// An arc of curvature `k` turning the travel heading by `k * len`; split into
    /// quarter turns so that projection never wraps.
    pub fn arc(&mut self, k: f64, len: f64) {
        if k.abs() < 1e-12 {
            return self.line(len);
        }
        let piece = FRAC_PI_2 / k.abs();
        let mut left = len;
        while left > 1e-12 {
            let l = left.min(piece);
            let (x, y, h) = self.end();
            let s0 = self.total();
            self.segs.push(Seg {
                x,
                y,
                h,
                k,
                len: l,
                s0,
            });
            left -= l;
        }
    }

    /// A straight segment from the end to (x, y).
    pub fn line_to(&mut self, x: f64, y: f64) {
        let (x0, y0, _) = self.end();
        let len = (x - x0).hypot(y - y0);
        if len > 1e-9 {
            let s0 = self.total();
            self.segs.push(Seg {
                x: x0,
                y: y0,
                h: (y - y0).atan2(x - x0),
                k: 0.0,
                len,
                s0,
            });
        }
    }

    /// The cubic Bezier of equations (2)-(3) from the end to (x, y, h), as lines.
    pub fn bezier_to(&mut self, x: f64, y: f64, h: f64) {
        let (x0, y0, h0) = self.end();
        let d = (x - x0).hypot(y - y0);
        let (x1, y1) = (x0 + 0.4 * d * h0.cos(), y0 + 0.4 * d * h0.sin());
        let (x2, y2) = (x - 0.4 * d * h.cos(), y - 0.4 * d * h.sin());
        let n = ((d / 0.05).ceil() as usize).clamp(8, 400);
        for i in 1..=n {
            let t = i as f64 / n as f64;
            let u = 1.0 - t;
            let (a, b, c, e) = (u * u * u, 3.0 * t * u * u, 3.0 * t * t * u, t * t * t);
            self.line_to(
                a * x0 + b * x1 + c * x2 + e * x,
                a * y0 + b * y1 + c * y2 + e * y,
            );
        }
    }

    /// Shortens the path by `by` metres from its end.
    pub fn trim_end(&mut self, by: f64) {
        let keep = (self.total() - by).max(0.0);
        while let Some(last) = self.segs.last_mut() {
            if last.s0 >= keep {
                self.segs.pop();
            } else {
                last.len = last.len.min(keep - last.s0);
                break;
            }
        }
    }

    /// Travel pose at arc length `s`; beyond the end the path goes on straight.
    pub fn pose_at(&self, s: f64, hint: usize) -> (f64, f64, f64) {
        let Some(last) = self.segs.last() else {
            let (x, y, h) = self.start;
            return (x + s * h.cos(), y + s * h.sin(), h);
        };
        let mut i = hint.min(self.segs.len() - 1);
        while i + 1 < self.segs.len() && self.segs[i].s0 + self.segs[i].len < s {
            i += 1;
        }
        let seg = &self.segs[i];
        if s > last.s0 + last.len {
            let (x, y, h) = last.at(last.len);
            let extra = s - (last.s0 + last.len);
            return (x + extra * h.cos(), y + extra * h.sin(), h);
        }
        seg.at((s - seg.s0).max(0.0))
    }

    /// Moves the progress (`seg`, `s`) forward to the point nearest (px, py); never
    /// backwards, and at most a few segments per call.
    pub fn advance(&self, seg: &mut usize, s: &mut f64, px: f64, py: f64) {
        let mut guard = 0;
        while let Some(cur) = self.segs.get(*seg) {
            let t = cur.project(px, py);
            if t > cur.len && *seg + 1 < self.segs.len() && guard < 64 {
                *seg += 1;
                guard += 1;
                continue;
            }
            let along = cur.s0 + t.clamp(0.0, cur.len.max(t));
            if along > *s {
                *s = along;
            }
            break;
        }
    }

    /// Appends the part of `other` after arc length `s` to `out` (which starts empty).
    pub fn remainder_into(&self, s: f64, out: &mut Path) {
        let (x, y, h) = self.pose_at(s, 0);
        out.reset(x, y, h, self.dir);
        for seg in &self.segs {
            let end = seg.s0 + seg.len;
            if end <= s {
                continue;
            }
            let from = (s - seg.s0).max(0.0);
            let (sx, sy, sh) = seg.at(from);
            let s0 = out.total();
            out.segs.push(Seg {
                x: sx,
                y: sy,
                h: sh,
                k: seg.k,
                len: seg.len - from,
                s0,
            });
        }
    }

    /// Appends `tail` (which must start where this path ends) to this path.
    pub fn extend(&mut self, tail: &Path) {
        for seg in &tail.segs {
            let s0 = self.total();
            self.segs.push(Seg { s0, ..*seg });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_of_a_quarter_circle_ends_where_geometry_says() {
        let mut p = Path::default();
        p.reset(0.0, 0.0, 0.0, 1.0);
        p.arc(1.0, FRAC_PI_2);
        let (x, y, h) = p.end();
        assert!((x - 1.0).abs() < 1e-9 && (y - 1.0).abs() < 1e-9 && (h - FRAC_PI_2).abs() < 1e-9);
        let mut s = 0.0;
        let mut seg = 0;
        let mid = FRAC_PI_2 / 2.0;
        let (mx, my, _) = p.pose_at(mid, 0);
        // Radially outward from the centre (0, 1).
        p.advance(&mut seg, &mut s, mx * 1.1, 1.0 + (my - 1.0) * 1.1);
        assert!((s - mid).abs() < 0.01, "{s}");
    }

    #[test]
    fn remainder_and_extend_keep_the_geometry() {
        let mut p = Path::default();
        p.reset(0.0, 0.0, 0.0, 1.0);
        p.line(2.0);
        p.arc(0.5, 1.0);
        let mut r = Path::default();
        p.remainder_into(1.5, &mut r);
        assert!((r.total() - 1.5).abs() < 1e-9);
        assert_eq!(r.end(), p.end());
        r.line(1.0);
        assert!((r.total() - 2.5).abs() < 1e-9);
    }

    #[test]
    fn bezier_reaches_its_goal() {
        let mut p = Path::default();
        p.reset(0.0, 0.0, 0.0, 1.0);
        p.bezier_to(3.0, 2.0, FRAC_PI_2);
        let (x, y, _) = p.end();
        assert!((x - 3.0).abs() < 1e-9 && (y - 2.0).abs() < 1e-9);
        p.trim_end(1.0);
        assert!(p.total() > 2.0);
    }
}
