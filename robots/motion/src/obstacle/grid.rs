//! A spatial index over a point cloud, so that a check looking a few metres
//! around the robot visits the points there and not the whole map.
//!
//! A query returns a superset of the points in its box, cell by cell: a
//! caller runs its own exact test over them, and where its answer could
//! depend on the order it visits points in (a running minimum of values
//! that may tie as 0.0 and -0.0), it puts the few it keeps back in index
//! order. Sorting every candidate would cost more than the test.

use super::bounds::Bounds;
use nalgebra::Point2;

/// Most cells along either side of the table: a cloud spread wider gets
/// coarser cells rather than an unbounded table.
const MAX_SIDE: usize = 1024;

/// Points bucketed in square cells over their bounding box, each cell's
/// indices contiguous (row by row).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointGrid {
    cols: Axis,
    rows: Axis,
    /// `items[starts[c]..starts[c + 1]]` are cell `c`'s points.
    starts: Vec<usize>,
    items: Vec<usize>,
    /// Points with a coordinate that is not finite: no box can place them,
    /// so every query returns them and the caller's own test decides.
    loose: Vec<usize>,
    len: usize,
    /// Each point's cell while the index is built.
    cell_of: Vec<usize>,
}

/// One axis of the table: where it starts, how wide its cells are, how many.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Axis {
    origin: f64,
    cell: f64,
    count: usize,
    /// The last cell's number, as a float, to clamp against.
    last: f64,
}

impl Axis {
    fn new(origin: f64, cell: f64, count: usize) -> Axis {
        Axis {
            origin,
            cell,
            count,
            last: (count - 1) as f64,
        }
    }

    /// The cell of `v`, clamped to the table: monotone in `v`, so a value
    /// inside a query's range lands inside the range's cells. (No `floor`:
    /// truncating a positive value is the same, and `floor` is a library
    /// call on the baseline x86-64 target.)
    fn of(&self, v: f64) -> usize {
        let c = (v - self.origin) / self.cell;
        if c.is_nan() || c <= 0.0 {
            0
        } else if c >= self.last {
            self.count - 1
        } else {
            c as i64 as usize
        }
    }
}

impl PointGrid {
    /// An index of `points` with cells `cell` metres wide (coarser when the
    /// points spread over more than `MAX_SIDE` cells).
    pub fn new<P>(cell: f64, points: &[P], xy: impl Fn(&P) -> (f64, f64)) -> PointGrid {
        let mut g = PointGrid::default();
        g.rebuild(cell, points, xy);
        g
    }

    /// Indexes `points` afresh, reusing the buffers.
    pub fn rebuild<P>(&mut self, cell: f64, points: &[P], xy: impl Fn(&P) -> (f64, f64)) {
        self.len = points.len();
        self.items.clear();
        self.loose.clear();
        self.starts.clear();
        self.cell_of.clear();
        let finite = |(x, y): (f64, f64)| x.is_finite() && y.is_finite();
        let mut lo = (f64::INFINITY, f64::INFINITY);
        let mut hi = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for p in points.iter().map(&xy).filter(|&p| finite(p)) {
            lo = (lo.0.min(p.0), lo.1.min(p.1));
            hi = (hi.0.max(p.0), hi.1.max(p.1));
        }
        if lo.0 > hi.0 {
            // Nothing finite: one empty cell, everything loose.
            self.cols = Axis::new(0.0, 1.0, 1);
            self.rows = Axis::new(0.0, 1.0, 1);
            self.starts.extend([0, 0]);
            self.loose.extend(0..points.len());
            return;
        }
        let span = (hi.0 - lo.0).max(hi.1 - lo.1);
        let cell = if cell.is_finite() && cell > 0.0 {
            cell
        } else {
            1.0
        };
        let cell = cell.max(span / (MAX_SIDE - 1) as f64);
        let most = Axis::new(0.0, cell, MAX_SIDE);
        self.cols = Axis::new(lo.0, cell, most.of(hi.0 - lo.0) + 1);
        self.rows = Axis::new(lo.1, cell, most.of(hi.1 - lo.1) + 1);
        // A counting sort by cell: indices stay ascending within each cell.
        let cells = self.cols.count * self.rows.count;
        self.starts.resize(cells + 1, 0);
        for (i, p) in points.iter().map(&xy).enumerate() {
            if finite(p) {
                let c = self.rows.of(p.1) * self.cols.count + self.cols.of(p.0);
                self.cell_of.push(c);
                self.starts[c + 1] += 1;
            } else {
                self.cell_of.push(usize::MAX);
                self.loose.push(i);
            }
        }
        for c in 1..self.starts.len() {
            self.starts[c] += self.starts[c - 1];
        }
        self.items.resize(self.starts[cells], 0);
        // Each cell's start moves on as it fills, ending at the next cell's
        // start; moved back one place, the starts are the starts again.
        for (i, &c) in self.cell_of.iter().enumerate() {
            if c != usize::MAX {
                self.items[self.starts[c]] = i;
                self.starts[c] += 1;
            }
        }
        self.starts.copy_within(0..cells, 1);
        self.starts[0] = 0;
    }

    /// How many points were indexed: a caller checks it against the cloud
    /// it queries.
    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Into `out` (cleared first), each once: the index of every point inside
    /// `b` (edges included), and some near it; every point when `b` has a
    /// NaN.
    pub fn within(&self, b: &Bounds, out: &mut Vec<usize>) {
        out.clear();
        if b.has_nan() {
            out.extend(0..self.len);
            return;
        }
        out.extend_from_slice(&self.loose);
        let (lo, hi) = (b.lo, b.hi);
        if lo.0 > hi.0 || lo.1 > hi.1 || self.items.is_empty() {
            return;
        }
        let (c0, c1) = (self.cols.of(lo.0), self.cols.of(hi.0));
        let (r0, r1) = (self.rows.of(lo.1), self.rows.of(hi.1));
        for r in r0..=r1 {
            // A row's cells are contiguous in `items`.
            let a = self.starts[r * self.cols.count + c0];
            let b = self.starts[r * self.cols.count + c1 + 1];
            out.extend_from_slice(&self.items[a..b]);
        }
    }
}

/// `PointGrid::new` over map points.
pub fn grid_of(cell: f64, points: &[Point2<f64>]) -> PointGrid {
    PointGrid::new(cell, points, |p| (p.x, p.y))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) use ilmr_geometry::SplitMix64 as Rng;

    /// A cloud with the awkward cases: points on cell edges, repeated
    /// points, a tight cluster, and now and then a far or non-finite one.
    pub(crate) fn cloud(rng: &mut Rng, n: usize, cell: f64) -> Vec<Point2<f64>> {
        (0..n)
            .map(|i| match rng.next_u64() % 20 {
                0 => Point2::new(
                    (rng.next_u64() % 40) as f64 * cell,
                    (rng.next_u64() % 40) as f64 * cell,
                ),
                1 if i > 0 => Point2::new(0.5, 0.5),
                2 => Point2::new(rng.range(1.0, 1.1), rng.range(-1.0, -0.9)),
                3 if rng.next_u64().is_multiple_of(8) => Point2::new(f64::NAN, 1.0),
                4 if rng.next_u64().is_multiple_of(8) => Point2::new(1e7, -3.0),
                _ => Point2::new(rng.range(-6.0, 6.0), rng.range(-6.0, 6.0)),
            })
            .collect()
    }

    fn brute(points: &[Point2<f64>], lo: (f64, f64), hi: (f64, f64)) -> Vec<usize> {
        (0..points.len())
            .filter(|&i| {
                let p = points[i];
                p.x >= lo.0 && p.x <= hi.0 && p.y >= lo.1 && p.y <= hi.1
            })
            .collect()
    }

    #[test]
    fn a_query_returns_every_point_in_its_box_once() {
        let mut rng = Rng::new(7);
        for round in 0..300 {
            let cell = [0.05, 0.25, 0.5, 1.3][round % 4];
            let n = (rng.next_u64() % 400) as usize;
            let pts = cloud(&mut rng, n, cell);
            let grid = grid_of(cell, &pts);
            assert_eq!(grid.len(), pts.len());
            let mut out = vec![99];
            for _ in 0..20 {
                let (x, y) = (rng.range(-8.0, 8.0), rng.range(-8.0, 8.0));
                // Edges exactly on points and on cell boundaries too.
                let (x, y) = match rng.next_u64() % 3 {
                    0 if !pts.is_empty() => {
                        let p = pts[(rng.next_u64() as usize) % pts.len()];
                        (p.x, p.y)
                    }
                    1 => ((x / cell).round() * cell, (y / cell).round() * cell),
                    _ => (x, y),
                };
                let lo = (x, y);
                let hi = (x + rng.range(0.0, 5.0), y + rng.range(0.0, 5.0));
                grid.within(&Bounds { lo, hi }, &mut out);
                out.sort_unstable();
                assert!(out.windows(2).all(|w| w[0] < w[1]), "no repeats");
                let want = brute(&pts, lo, hi);
                let missed: Vec<usize> = want
                    .iter()
                    .copied()
                    .filter(|i| out.binary_search(i).is_err())
                    .collect();
                assert!(missed.is_empty(), "round {round}: missed {missed:?}");
            }
        }
    }

    #[test]
    fn a_query_is_a_small_part_of_a_large_cloud() {
        let mut rng = Rng::new(3);
        let pts: Vec<Point2<f64>> = (0..10_000)
            .map(|_| Point2::new(rng.range(0.0, 50.0), rng.range(0.0, 50.0)))
            .collect();
        let grid = grid_of(0.25, &pts);
        let mut out = Vec::new();
        grid.within(&Bounds::square((25.0, 25.0), 2.0), &mut out);
        let want = brute(&pts, (23.0, 23.0), (27.0, 27.0));
        assert!(out.len() >= want.len() && out.len() < 2 * want.len() + 50);
    }

    #[test]
    fn odd_queries_and_clouds_fall_back_to_everything_they_might_need() {
        let pts = vec![
            Point2::new(1.0, 1.0),
            Point2::new(f64::INFINITY, 0.0),
            Point2::new(2.0, 2.0),
        ];
        let grid = grid_of(0.5, &pts);
        let mut out = Vec::new();
        let boxed = |lo, hi| Bounds { lo, hi };
        grid.within(&boxed((f64::NAN, 0.0), (1.0, 1.0)), &mut out);
        assert_eq!(out, vec![0, 1, 2], "a NaN box: everything");
        grid.within(&boxed((0.0, 0.0), (1.5, 1.5)), &mut out);
        out.sort_unstable();
        assert_eq!(out, vec![0, 1], "the loose point always");
        grid.within(&boxed((3.0, 3.0), (2.0, 2.0)), &mut out);
        assert_eq!(out, vec![1], "an empty box: only the loose point");
        let everywhere = boxed(
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::INFINITY),
        );
        grid.within(&everywhere, &mut out);
        out.sort_unstable();
        assert_eq!(out, vec![0, 1, 2]);
        let empty = grid_of(0.5, &[]);
        empty.within(&Bounds::square((0.0, 0.0), 10.0), &mut out);
        assert!(out.is_empty() && empty.is_empty());
        let bad_cell = grid_of(f64::NAN, &pts);
        bad_cell.within(&Bounds::square((1.0, 1.0), 0.1), &mut out);
        out.sort_unstable();
        assert_eq!(out, vec![0, 1]);
    }
}
