//! A uniform grid over the scene's fixed solids (walls and obstacles), so
//! that a ray, a footprint or a scan's reach looks only at the cells it
//! crosses: a world of 100,000 walls costs a tick about what the few walls
//! near the robot cost (issue 12). Each solid is listed in every cell its
//! shape comes within `MARGIN` of, so a point on a shape is always in a cell
//! that lists it, whatever rounding does at cell borders.

use super::{Obb, PlaneVector, Point2, Shape, Solid, Vector2};

/// Side of a cell, m: a few beams' worth of wall at scanner range.
const CELL: f64 = 2.0;
/// Most cells along a side; a larger world gets larger cells (a 10 km site,
/// the largest a world file admits, gets 10 m cells and 8 MB of table).
const MAX_SIDE: usize = 1024;
/// How far outside a cell a shape may be and still be listed there, m.
const MARGIN: f64 = 0.01;

#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct SolidGrid {
    origin: Point2<f64>,
    cell: f64,
    cols: usize,
    rows: usize,
    /// `items[starts[c]..starts[c + 1]]`: cell `c`'s solids, ascending.
    starts: Vec<usize>,
    items: Vec<usize>,
}

/// The axis-aligned box round a shape: (min, max).
fn extent(shape: &Shape) -> (Point2<f64>, Point2<f64>) {
    match shape {
        Shape::Circle(c) => (
            Point2::new(c.center.x - c.radius, c.center.y - c.radius),
            Point2::new(c.center.x + c.radius, c.center.y + c.radius),
        ),
        Shape::Box(b) => {
            let cs = b.corners();
            let mut lo = cs[0];
            let mut hi = cs[0];
            for p in &cs[1..] {
                lo = Point2::new(lo.x.min(p.x), lo.y.min(p.y));
                hi = Point2::new(hi.x.max(p.x), hi.y.max(p.y));
            }
            (lo, hi)
        }
    }
}

impl SolidGrid {
    /// Indexes `solids[i]` for each `i` in `members` (ascending).
    pub fn new(solids: &[Solid], members: &[usize]) -> SolidGrid {
        let mut bounds: Option<(Point2<f64>, Point2<f64>)> = None;
        for &i in members {
            let (lo, hi) = extent(&solids[i].shape);
            if !(lo.coords.is_finite() && hi.coords.is_finite()) {
                continue;
            }
            bounds = Some(match bounds {
                None => (lo, hi),
                Some((a, b)) => (
                    Point2::new(a.x.min(lo.x), a.y.min(lo.y)),
                    Point2::new(b.x.max(hi.x), b.y.max(hi.y)),
                ),
            });
        }
        let Some((lo, hi)) = bounds else {
            return SolidGrid::default();
        };
        let origin = Point2::new(lo.x - MARGIN, lo.y - MARGIN);
        let (w, h) = (hi.x - lo.x + 2.0 * MARGIN, hi.y - lo.y + 2.0 * MARGIN);
        let cell = CELL.max(w / MAX_SIDE as f64).max(h / MAX_SIDE as f64);
        let cols = ((w / cell).ceil() as usize).clamp(1, MAX_SIDE);
        let rows = ((h / cell).ceil() as usize).clamp(1, MAX_SIDE);
        let mut g = SolidGrid {
            origin,
            cell,
            cols,
            rows,
            starts: Vec::new(),
            items: Vec::new(),
        };
        let mut pairs: Vec<(usize, usize)> = Vec::new();
        for &i in members {
            let shape = &solids[i].shape;
            let (lo, hi) = extent(shape);
            if !(lo.coords.is_finite() && hi.coords.is_finite()) {
                continue;
            }
            let (c0, r0) = g.cell_of(Point2::new(lo.x - MARGIN, lo.y - MARGIN));
            let (c1, r1) = g.cell_of(Point2::new(hi.x + MARGIN, hi.y + MARGIN));
            for r in r0..=r1 {
                for c in c0..=c1 {
                    if g.touches(shape, c, r) {
                        pairs.push((r * cols + c, i));
                    }
                }
            }
        }
        let n = cols * rows;
        let mut starts = vec![0usize; n + 1];
        for &(c, _) in &pairs {
            starts[c + 1] += 1;
        }
        for c in 1..=n {
            starts[c] += starts[c - 1];
        }
        let mut next = starts.clone();
        let mut items = vec![0usize; pairs.len()];
        // `pairs` is in ascending solid order, so each cell's list is too.
        for &(c, i) in &pairs {
            items[next[c]] = i;
            next[c] += 1;
        }
        g.starts = starts;
        g.items = items;
        g
    }

    fn is_empty(&self) -> bool {
        self.starts.is_empty()
    }

    /// The cell holding `p`, clamped to the table.
    fn cell_of(&self, p: Point2<f64>) -> (usize, usize) {
        let f = |v: f64, o: f64, n: usize| {
            let k = ((v - o) / self.cell).floor();
            if k.is_nan() || k <= 0.0 {
                0
            } else {
                (k as usize).min(n - 1)
            }
        };
        (
            f(p.x, self.origin.x, self.cols),
            f(p.y, self.origin.y, self.rows),
        )
    }

    /// Whether `shape` comes within `MARGIN` of cell (c, r).
    fn touches(&self, shape: &Shape, c: usize, r: usize) -> bool {
        let lo = Point2::new(
            self.origin.x + c as f64 * self.cell - MARGIN,
            self.origin.y + r as f64 * self.cell - MARGIN,
        );
        let side = self.cell + 2.0 * MARGIN;
        let square = Obb::new(
            Point2::new(lo.x + side / 2.0, lo.y + side / 2.0),
            0.0,
            side,
            side,
        );
        shape.overlaps_box(&square)
    }

    fn cell(&self, c: usize, r: usize) -> &[usize] {
        let k = r * self.cols + c;
        &self.items[self.starts[k]..self.starts[k + 1]]
    }

    /// Appends the solids of every cell that meets the box `lo..hi` (with
    /// repeats; the caller sorts and dedups).
    pub fn within(&self, lo: Point2<f64>, hi: Point2<f64>, out: &mut Vec<usize>) {
        if self.is_empty() {
            return;
        }
        let far = Point2::new(
            self.origin.x + self.cols as f64 * self.cell,
            self.origin.y + self.rows as f64 * self.cell,
        );
        if hi.x < self.origin.x || hi.y < self.origin.y || lo.x > far.x || lo.y > far.y {
            return;
        }
        let (c0, r0) = self.cell_of(lo);
        let (c1, r1) = self.cell_of(hi);
        for r in r0..=r1 {
            for c in c0..=c1 {
                out.extend_from_slice(self.cell(c, r));
            }
        }
    }

    /// Visits the cells a ray crosses, in order, up to `t_max`: `visit`
    /// gets each cell's solids and the distance at which the ray enters it,
    /// and returns whether to go on. `origin` and `dir` must be finite.
    pub fn along(
        &self,
        origin: Point2<f64>,
        dir: Vector2<f64>,
        t_max: f64,
        mut visit: impl FnMut(&[usize], f64) -> bool,
    ) {
        if self.is_empty() {
            return;
        }
        let size = Vector2::new(self.cols as f64 * self.cell, self.rows as f64 * self.cell);
        // The part of the ray inside the table (slab test).
        let (mut t0, mut t1) = (0.0_f64, t_max);
        for (o, d, lo, len) in [
            (origin.x, dir.x, self.origin.x, size.x),
            (origin.y, dir.y, self.origin.y, size.y),
        ] {
            if d == 0.0 {
                if o < lo || o > lo + len {
                    return;
                }
            } else {
                let (a, b) = ((lo - o) / d, (lo + len - o) / d);
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
        }
        // Also false when either is NaN.
        if t0.partial_cmp(&t1).is_none_or(|o| o.is_gt()) {
            return;
        }
        let p = origin + dir * t0;
        let (mut c, mut r) = self.cell_of(p);
        let next = |d: f64, pv: f64, k: usize, o: f64| -> (i64, f64, f64) {
            if d > 0.0 {
                let edge = o + (k + 1) as f64 * self.cell;
                (1, t0 + (edge - pv) / d, self.cell / d)
            } else if d < 0.0 {
                let edge = o + k as f64 * self.cell;
                (-1, t0 + (edge - pv) / d, -self.cell / d)
            } else {
                (0, f64::INFINITY, f64::INFINITY)
            }
        };
        let (sx, mut tx, dx) = next(dir.x, p.x, c, self.origin.x);
        let (sy, mut ty, dy) = next(dir.y, p.y, r, self.origin.y);
        let mut enter = t0;
        loop {
            if !visit(self.cell(c, r), enter) {
                return;
            }
            enter = tx.min(ty);
            if enter > t1 {
                return;
            }
            if tx <= ty {
                let Some(k) = c.checked_add_signed(sx as isize).filter(|&k| k < self.cols) else {
                    return;
                };
                c = k;
                tx += dx;
            } else {
                let Some(k) = r.checked_add_signed(sy as isize).filter(|&k| k < self.rows) else {
                    return;
                };
                r = k;
                ty += dy;
            }
        }
    }
}
