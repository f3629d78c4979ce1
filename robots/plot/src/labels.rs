//! Where text goes on the map so that no label covers another or a marker: each label
//! tries places round its point, nearest first, and takes the first free one. Points
//! in pixels, y down, as the drawing backend has them.

use std::collections::{HashMap, HashSet};

/// The font size of map labels, pixels.
pub const FONT: u32 = 13;

/// A rough width of `text` at [`FONT`]: SVG text is measured by the viewer, so this
/// errs wide (digits and lower case at 0.6 em, plus a pixel each side).
pub fn width(text: &str) -> i32 {
    (text.chars().count() as f64 * 0.6 * f64::from(FONT)).ceil() as i32 + 2
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Rect {
    x0: i32,
    y0: i32,
    x1: i32,
    y1: i32,
}

impl Rect {
    fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }
}

/// Room kept between a point and its label, pixels.
const GAP: i32 = 6;
/// Rings of places tried round a point, each further out.
const RINGS: i32 = 3;

/// Side of the grid cells taken places are filed under, pixels: a place is looked up
/// among its cells' places only, so a run with thousands of marks stays linear.
const CELL: i32 = 64;

/// The grid cells a rectangle touches.
fn cells(r: &Rect) -> impl Iterator<Item = (i32, i32)> {
    let (cx0, cx1) = (r.x0.div_euclid(CELL), (r.x1 - 1).div_euclid(CELL));
    let (cy0, cy1) = (r.y0.div_euclid(CELL), (r.y1 - 1).div_euclid(CELL));
    (cx0..=cx1).flat_map(move |x| (cy0..=cy1).map(move |y| (x, y)))
}

#[derive(Debug, Default)]
pub struct Placer {
    taken: HashMap<(i32, i32), Vec<Rect>>,
    /// Every place taken once: marks that fall on one pixel (a robot standing
    /// through many commands) block it once.
    seen: HashSet<Rect>,
}

impl Placer {
    /// Keeps a square of `half` pixels round `at` clear (a marker).
    pub fn block(&mut self, at: (i32, i32), half: i32) {
        self.take(Rect {
            x0: at.0 - half,
            y0: at.1 - half,
            x1: at.0 + half,
            y1: at.1 + half,
        });
    }

    fn take(&mut self, r: Rect) {
        if !self.seen.insert(r) {
            return;
        }
        for cell in cells(&r) {
            self.taken.entry(cell).or_default().push(r);
        }
    }

    fn free(&self, r: &Rect) -> bool {
        cells(r).all(|cell| {
            self.taken
                .get(&cell)
                .is_none_or(|rs| !rs.iter().any(|t| t.overlaps(r)))
        })
    }

    /// The offset from `at` of the top-left corner of a free place for a label of
    /// `size`, which is then taken; `None` when every place tried is covered.
    pub fn place(&mut self, at: (i32, i32), size: (i32, i32)) -> Option<(i32, i32)> {
        let (w, h) = size;
        for ring in 0..RINGS {
            let g = GAP + ring * h;
            let offsets = [
                (-w / 2, -g - h),
                (-w / 2, g),
                (g, -h / 2),
                (-g - w, -h / 2),
                (g, -g - h),
                (g, g),
                (-g - w, -g - h),
                (-g - w, g),
            ];
            for (dx, dy) in offsets {
                let r = Rect {
                    x0: at.0 + dx,
                    y0: at.1 + dy,
                    x1: at.0 + dx + w,
                    y1: at.1 + dy + h,
                };
                if self.free(&r) {
                    self.take(r);
                    return Some((dx, dy));
                }
            }
        }
        None
    }
}

/// Points within `near` pixels of each other, grouped in first-seen order: marks at
/// one place get one label listing them all, rather than labels printed over each
/// other ("6" and "11" reading as "61").
pub fn group(points: &[(i32, i32)], near: i32) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    // Points filed by cells of `near` pixels: a close point is in this cell or one
    // beside it.
    let side = near.max(1);
    let mut filed: HashMap<(i32, i32), Vec<usize>> = HashMap::new();
    let mut group_of = vec![0; points.len()];
    for (i, p) in points.iter().enumerate() {
        let cell = (p.0.div_euclid(side), p.1.div_euclid(side));
        let close = (-1..=1)
            .flat_map(|dx| (-1..=1).map(move |dy| (cell.0 + dx, cell.1 + dy)))
            .filter_map(|c| filed.get(&c))
            .flatten()
            .filter(|&&j| {
                let q = points[j];
                (p.0 - q.0).abs() <= near && (p.1 - q.1).abs() <= near
            })
            .map(|&j| group_of[j])
            .min();
        let g = close.unwrap_or_else(|| {
            groups.push(Vec::new());
            groups.len() - 1
        });
        groups[g].push(i);
        group_of[i] = g;
        filed.entry(cell).or_default().push(i);
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_at_one_point_go_to_different_sides_and_never_overlap() {
        let mut p = Placer::default();
        p.block((100, 100), 5);
        let size = (width("11"), FONT as i32);
        let placed: Vec<(i32, i32)> = (0..8)
            .map(|_| p.place((100, 100), size).expect("room round the point"))
            .collect();
        let rects: Vec<Rect> = placed
            .iter()
            .map(|&(dx, dy)| Rect {
                x0: 100 + dx,
                y0: 100 + dy,
                x1: 100 + dx + size.0,
                y1: 100 + dy + size.1,
            })
            .collect();
        for (i, a) in rects.iter().enumerate() {
            let marker = Rect {
                x0: 95,
                y0: 95,
                x1: 105,
                y1: 105,
            };
            assert!(!a.overlaps(&marker), "label {i} covers the marker");
            for b in &rects[i + 1..] {
                assert!(!a.overlaps(b), "{a:?} and {b:?}");
            }
        }
        assert_eq!(placed[0], (-size.0 / 2, -GAP - size.1), "above first");
        assert_eq!(placed[1], (-size.0 / 2, GAP), "then below");
    }

    #[test]
    fn a_crowded_point_gives_up_rather_than_cover_a_label() {
        let mut p = Placer::default();
        let size = (width("10 s"), FONT as i32);
        let free = (0..100).map_while(|_| p.place((50, 50), size)).count();
        assert!((8..=8 * RINGS as usize).contains(&free), "{free} places");
        assert_eq!(p.place((50, 50), size), None, "and then none");
        assert!(
            p.place((500, 50), size).is_some(),
            "elsewhere there is room"
        );
    }

    #[test]
    fn points_a_few_pixels_apart_share_a_label() {
        let groups = group(&[(10, 10), (200, 10), (12, 11), (10, 40)], 4);
        assert_eq!(groups, vec![vec![0, 2], vec![1], vec![3]]);
    }
}
