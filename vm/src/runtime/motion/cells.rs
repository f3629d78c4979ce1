//! Which map point holds each 5 cm cell, so a new scan replaces the point of
//! a cell it falls in rather than adding one. Rebuilt whenever points are
//! dropped (a few times a second), so it is a hash map with a cheap hash: it
//! is only ever looked up, never iterated, so its order reaches no result.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use nalgebra::Point2;

/// Side of a cell, m.
pub(crate) const CELL: f64 = 0.05;

/// A multiply-rotate hash of the cell's two coordinates (FxHash's step).
#[derive(Default)]
struct CellHash(u64);

const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl Hasher for CellHash {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(SEED);
    }

    fn write_i64(&mut self, v: i64) {
        self.write_u64(v as u64);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// `v.floor() as i64` without the library call that `floor` is on the
/// baseline x86-64 target: truncation, one down for negative fractions.
fn floor_i64(v: f64) -> i64 {
    let t = v as i64;
    if (t as f64) > v {
        t.saturating_sub(1)
    } else {
        t
    }
}

pub(crate) fn cell(p: &Point2<f64>) -> (i64, i64) {
    (floor_i64(p.x / CELL), floor_i64(p.y / CELL))
}

#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Cells {
    of: HashMap<(i64, i64), usize, BuildHasherDefault<CellHash>>,
}

impl Cells {
    pub fn get(&self, p: &Point2<f64>) -> Option<usize> {
        self.of.get(&cell(p)).copied()
    }

    pub fn insert(&mut self, p: &Point2<f64>, index: usize) {
        self.of.insert(cell(p), index);
    }

    pub fn clear(&mut self) {
        self.of.clear();
    }

    /// Every point's cell afresh; a later point of a cell wins, as inserting
    /// them in order would.
    pub fn rebuild(&mut self, points: &[Point2<f64>]) {
        self.of.clear();
        for (i, p) in points.iter().enumerate() {
            self.of.insert(cell(p), i);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_without_the_library_call_is_floor() {
        let values = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            -1.0,
            -1.000_000_1,
            3.999_999_9,
            -3.0,
            1e10 + 0.5,
            -1e10 - 0.5,
            1e30,
            -1e30,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
        ];
        for v in values {
            assert_eq!(floor_i64(v), v.floor() as i64, "{v}");
        }
        for i in -2000..2000 {
            let v = f64::from(i) * 0.0137 - 0.05;
            assert_eq!(floor_i64(v / CELL), (v / CELL).floor() as i64, "{v}");
        }
    }

    #[test]
    fn a_rebuild_keeps_the_last_point_of_a_cell() {
        let pts = [
            Point2::new(0.01, 0.01),
            Point2::new(-0.01, 0.01),
            Point2::new(0.02, 0.04),
        ];
        let mut c = Cells::default();
        c.rebuild(&pts);
        assert_eq!(c.get(&Point2::new(0.049, 0.0)), Some(2));
        assert_eq!(c.get(&Point2::new(-0.049, 0.0)), Some(1));
        assert_eq!(c.get(&Point2::new(0.06, 0.0)), None);
    }
}
