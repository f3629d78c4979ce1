//! Axis-aligned boxes that hold what a check can accept: what to ask a
//! [`PointGrid`](super::PointGrid) for. Every constructor widens its box by
//! `SLACK` (plus a part in 10^12 of the coordinates), so that a point an
//! exact test computed in floating point accepts is never just outside it.

/// Rounding allowance, m.
const SLACK: f64 = 1e-6;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub lo: (f64, f64),
    pub hi: (f64, f64),
}

fn pad(scale: f64) -> f64 {
    SLACK + 1e-12 * scale
}

impl Bounds {
    /// Everything: a box of NaN, which a grid answers with every point.
    pub const ALL: Bounds = Bounds {
        lo: (f64::NAN, f64::NAN),
        hi: (f64::NAN, f64::NAN),
    };

    /// The square of half side `half` round `centre` (a negative half side
    /// counts by its size).
    pub fn square(centre: (f64, f64), half: f64) -> Bounds {
        Bounds::rect(centre, (half.abs(), half.abs()))
    }

    /// The box of half sides `half` round `centre`.
    pub fn rect(centre: (f64, f64), half: (f64, f64)) -> Bounds {
        let p = pad(centre.0.abs() + centre.1.abs() + half.0.abs() + half.1.abs());
        let (hx, hy) = (half.0.abs() + p, half.1.abs() + p);
        Bounds {
            lo: (centre.0 - hx, centre.1 - hy),
            hi: (centre.0 + hx, centre.1 + hy),
        }
    }

    /// The box round the rectangle `[lo.0, hi.0] x [lo.1, hi.1]` of a frame
    /// at `origin` turned by the angle whose sine and cosine are `sin_cos`.
    pub fn turned(
        origin: (f64, f64),
        sin_cos: (f64, f64),
        lo: (f64, f64),
        hi: (f64, f64),
    ) -> Bounds {
        let (s, c) = sin_cos;
        let (mx, my) = (0.5 * (lo.0 + hi.0), 0.5 * (lo.1 + hi.1));
        let (hx, hy) = (0.5 * (hi.0 - lo.0), 0.5 * (hi.1 - lo.1));
        let centre = (origin.0 + c * mx - s * my, origin.1 + s * mx + c * my);
        let half = (c.abs() * hx + s.abs() * hy, s.abs() * hx + c.abs() * hy);
        Bounds::rect(centre, half)
    }

    pub fn has_nan(&self) -> bool {
        [self.lo.0, self.lo.1, self.hi.0, self.hi.1]
            .iter()
            .any(|v| v.is_nan())
    }

    /// What lies in both; NaN in either asks for everything.
    pub fn and(&self, other: &Bounds) -> Bounds {
        if self.has_nan() || other.has_nan() {
            return Bounds::ALL;
        }
        Bounds {
            lo: (self.lo.0.max(other.lo.0), self.lo.1.max(other.lo.1)),
            hi: (self.hi.0.min(other.hi.0), self.hi.1.min(other.hi.1)),
        }
    }

    /// What lies in either; NaN in either asks for everything.
    pub fn or(&self, other: &Bounds) -> Bounds {
        if self.has_nan() || other.has_nan() {
            return Bounds::ALL;
        }
        Bounds {
            lo: (self.lo.0.min(other.lo.0), self.lo.1.min(other.lo.1)),
            hi: (self.hi.0.max(other.hi.0), self.hi.1.max(other.hi.1)),
        }
    }

    pub fn contains(&self, p: (f64, f64)) -> bool {
        p.0 >= self.lo.0 && p.0 <= self.hi.0 && p.1 >= self.lo.1 && p.1 <= self.hi.1
    }

    /// Whether `p` is certainly not inside: a finite point outside a box
    /// without NaN (a box of NaN, or a point of NaN, excludes nothing).
    pub fn excludes(&self, p: (f64, f64)) -> bool {
        !self.has_nan() && p.0.is_finite() && p.1.is_finite() && !self.contains(p)
    }

    /// The box round the points `ps`, widened by `margin` (NaN anywhere
    /// asks for everything).
    pub fn around(ps: &[(f64, f64)], margin: f64) -> Bounds {
        let lo = ps.iter().fold((f64::INFINITY, f64::INFINITY), |a, p| {
            (a.0.min(p.0), a.1.min(p.1))
        });
        let hi = ps
            .iter()
            .fold((f64::NEG_INFINITY, f64::NEG_INFINITY), |a, p| {
                (a.0.max(p.0), a.1.max(p.1))
            });
        if ps.is_empty() || ps.iter().any(|p| p.0.is_nan() || p.1.is_nan()) || margin.is_nan() {
            return Bounds::ALL;
        }
        Bounds::rect(
            (0.5 * (lo.0 + hi.0), 0.5 * (lo.1 + hi.1)),
            (
                0.5 * (hi.0 - lo.0) + margin.abs(),
                0.5 * (hi.1 - lo.1) + margin.abs(),
            ),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turned_rectangle_lies_inside_its_box() {
        for i in 0..64 {
            let h = f64::from(i) * 0.1 - 3.2;
            let (s, c) = h.sin_cos();
            let b = Bounds::turned((2.0, -1.0), (s, c), (-0.3, -0.5), (1.6, 0.4));
            for (x, y) in [
                (-0.3, -0.5),
                (1.6, -0.5),
                (-0.3, 0.4),
                (1.6, 0.4),
                (0.5, 0.0),
            ] {
                let w = (2.0 + c * x - s * y, -1.0 + s * x + c * y);
                assert!(b.contains(w), "{h}: {w:?} outside {b:?}");
            }
            // Tight: no more than the slack beyond the corners.
            let corners = [(-0.3, -0.5), (1.6, -0.5), (-0.3, 0.4), (1.6, 0.4)]
                .map(|(x, y)| (2.0 + c * x - s * y, -1.0 + s * x + c * y));
            let max_x = corners
                .iter()
                .map(|p| p.0)
                .fold(f64::NEG_INFINITY, f64::max);
            assert!((b.hi.0 - max_x).abs() < 1e-5);
        }
    }

    #[test]
    fn nan_asks_for_everything_and_boxes_combine() {
        let a = Bounds::square((0.0, 0.0), 1.0);
        let b = Bounds::square((1.5, 0.0), 1.0);
        let both = a.and(&b);
        assert!(both.contains((0.75, 0.5)) && !both.contains((-0.75, 0.0)));
        let either = a.or(&b);
        assert!(either.contains((-0.75, 0.0)) && either.contains((2.4, 0.0)));
        let nan = Bounds::square((f64::NAN, 0.0), 1.0);
        assert!(a.and(&nan).has_nan() && nan.or(&a).has_nan());
        assert!(!nan.excludes((5.0, 5.0)) && !a.excludes((f64::NAN, 5.0)));
        assert!(a.excludes((5.0, 5.0)) && !a.excludes((0.5, 0.5)));
        let round = Bounds::around(&[(0.0, 1.0), (2.0, -1.0)], 0.5);
        assert!(round.contains((-0.5, 1.5)) && round.excludes((-0.6, 0.0)));
        assert!(Bounds::around(&[], 1.0).has_nan());
        assert!(Bounds::square((0.0, 0.0), -1.0).contains((0.9, -0.9)));
    }
}
