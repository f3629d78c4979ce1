//! The pieces a picture is drawn from, collected beside a run without changing it: the
//! true path thinned to a pose every [`EVERY`] ticks, where movement commands started
//! and ended, and the scanner's hits on a 10 cm grid.

use std::collections::BTreeSet;

use ilmr_plot::{At, Mark, Sample};

use crate::harness::{Run, SimVm};

/// Ticks between the poses drawn: 0.1 s, a few millimetres of travel, which keeps a
/// 600 s run's picture under 100 KB.
pub const EVERY: usize = 10;

/// Every `EVERY`th pose of a trace recorded after each tick of `period` seconds, and
/// the last one.
pub fn thin(
    trace: &[ilmr_hal::Pose],
    speeds: &[f64],
    curvatures: &[f64],
    period: f64,
) -> Vec<Sample> {
    let sample = |i: usize| Sample {
        t: (i + 1) as f64 * period,
        x: trace[i].x,
        y: trace[i].y,
        h: trace[i].h,
        v: speeds.get(i).copied().unwrap_or(0.0),
        c: curvatures.get(i).copied().unwrap_or(0.0),
    };
    let mut out: Vec<Sample> = (0..trace.len()).step_by(EVERY).map(sample).collect();
    if !trace.is_empty() && !(trace.len() - 1).is_multiple_of(EVERY) {
        out.push(sample(trace.len() - 1));
    }
    out
}

/// A run's path as [`thin`] samples it.
pub fn track(run: &Run, period: f64) -> Vec<Sample> {
    thin(&run.trace, &run.speeds, &run.curvatures, period)
}

/// How many points a mean path has.
pub const MEAN_POINTS: usize = 200;

/// The mean of several runs of one route: each run resampled at `n` equal shares of
/// its own length, and the runs' points at each share averaged. Runs of one route
/// that stop short or overrun stay comparable, which averaging by time would not
/// give (a late start would pull the mean back along the route).
pub fn mean_path(runs: &[Vec<(f64, f64)>], n: usize) -> Vec<(f64, f64)> {
    let resampled: Vec<Vec<(f64, f64)>> = runs
        .iter()
        .filter(|r| !r.is_empty())
        .map(|r| resample(r, n))
        .collect();
    if resampled.is_empty() {
        return Vec::new();
    }
    let k = resampled.len() as f64;
    (0..n)
        .map(|i| {
            let (x, y) = resampled
                .iter()
                .fold((0.0, 0.0), |(x, y), r| (x + r[i].0, y + r[i].1));
            (x / k, y / k)
        })
        .collect()
}

/// `n` points (n >= 2) at equal shares of `run`'s length, its ends included.
fn resample(run: &[(f64, f64)], n: usize) -> Vec<(f64, f64)> {
    let mut along = vec![0.0];
    for w in run.windows(2) {
        let last = along[along.len() - 1];
        along.push(last + (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1));
    }
    let total = along[along.len() - 1];
    let mut j = 0;
    (0..n)
        .map(|i| {
            let s = total * i as f64 / (n - 1).max(1) as f64;
            while j + 1 < run.len() - 1 && along[j + 1] < s {
                j += 1;
            }
            if j + 1 >= run.len() {
                return run[j];
            }
            let leg = along[j + 1] - along[j];
            let t = if leg > 0.0 { (s - along[j]) / leg } else { 0.0 };
            let (a, b) = (run[j], run[j + 1]);
            (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
        })
        .collect()
}

/// Marks where movement commands started and ended, at the true pose of the tick
/// (as `ilmrc run` writes them to its trace).
pub struct Marks {
    /// Per statement: whether it issues a movement command.
    movement: Vec<bool>,
    seen: usize,
    pub marks: Vec<Mark>,
}

impl Marks {
    pub fn new(vm: &SimVm) -> Marks {
        Marks {
            movement: vm.module().movement_statements(),
            seen: 0,
            marks: Vec::new(),
        }
    }

    /// Takes the events of the tick just run.
    pub fn watch(&mut self, vm: &SimVm) {
        let events = vm.events();
        let p = vm.hal().true_pose();
        for e in &events[self.seen.min(events.len())..] {
            let Some(stmt) = e.stmt else { continue };
            if !self.movement.get(stmt.index()).copied().unwrap_or(false) {
                continue;
            }
            let (at, how) = match &e.kind {
                ilmr_vm::EventKind::Start { .. } => (At::Start, None),
                ilmr_vm::EventKind::End { how, .. } => (At::End, Some(*how)),
                _ => continue,
            };
            let Some(s) = vm.module().stmt(stmt) else {
                continue;
            };
            self.marks.push(Mark {
                t: e.t,
                line: s.line,
                text: s.text.clone(),
                at,
                x: p.x,
                y: p.y,
                h: p.h,
                how,
            });
        }
        self.seen = events.len();
    }
}

/// Scanner hits in the world frame, one per 10 cm cell: a wall seen in a hundred scans
/// is drawn once, and the lab's picture stays near 150 KB.
pub struct Hits {
    /// Seconds between the scans taken.
    every: f64,
    next: f64,
    last_seq: Option<u64>,
    cells: BTreeSet<(i64, i64)>,
}

const CELL: f64 = 0.1;

impl Hits {
    pub fn new(every: f64) -> Hits {
        Hits {
            every,
            next: 0.0,
            last_seq: None,
            cells: BTreeSet::new(),
        }
    }

    /// Takes the scan of the tick just run, if it is new and due.
    pub fn watch(&mut self, vm: &SimVm) {
        let sim = vm.hal().sim();
        let Some(scan) = sim.snapshot().scan else {
            return;
        };
        if self.last_seq == Some(scan.seq) || scan.time < self.next - 1e-9 {
            return;
        }
        self.last_seq = Some(scan.seq);
        self.next = scan.time + self.every;
        // The beams were cast from this tick's true pose: the robot steps in lockstep
        // with the VM.
        for hit in scan.world_hits(sim.true_pose()) {
            self.cells
                .insert(((hit.x / CELL).round() as i64, (hit.y / CELL).round() as i64));
        }
    }

    pub fn points(&self) -> Vec<(f64, f64)> {
        self.cells
            .iter()
            .map(|&(i, j)| (i as f64 * CELL, j as f64 * CELL))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mean_path_averages_runs_at_equal_shares_of_their_length() {
        // Two straight runs a metre apart, one of them sampled unevenly and longer:
        // the mean lies between them, from their starts' middle to their ends'.
        let a = vec![(0.0, 0.0), (2.0, 0.0)];
        let b = vec![(0.0, 1.0), (0.5, 1.0), (4.0, 1.0)];
        let m = mean_path(&[a, b], 5);
        assert_eq!(m.len(), 5);
        let want = [(0.0, 0.5), (0.75, 0.5), (1.5, 0.5), (2.25, 0.5), (3.0, 0.5)];
        for (got, want) in m.iter().zip(want) {
            assert!(
                (got.0 - want.0).abs() < 1e-12 && (got.1 - want.1).abs() < 1e-12,
                "{m:?}"
            );
        }
        assert!(mean_path(&[], 5).is_empty());
        // A run standing still is its one point throughout.
        assert_eq!(mean_path(&[vec![(1.0, 2.0)]], 3), vec![(1.0, 2.0); 3]);
    }
}
