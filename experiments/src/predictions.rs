//! Tests 2-7 and Figure 20 as statistics of the calibrated error model (issue 15
//! items 2 and 3): each runs over [`seeds`](crate::seeds) seeds on robots with the
//! `calibrated` profile, which was fitted to Table 10 alone, and is reported beside
//! the dissertation's figures without retuning. The sections of tests 2-7 further
//! down show one run each on the `basic` profile, with its picture.

use ilmr_plot::{Colour, Corner, Figure, Reference, RunSpread};
use ilmr_sim::SimProfile;

use crate::stats::Spread;
use crate::{
    fig20_fetch_boxes as f20, seeds, test2_turn_left as t2, test3_followwall as t3,
    test4_obstacle as t4, test5_short_task as t5, test6_loop as t6, test7_way_out as t7,
};

pub const PROFILE: SimProfile = SimProfile::Calibrated;

/// Test 2 (Table 11): `turn(left)` in the corridor.
#[derive(Debug, Clone)]
pub struct Turns {
    pub x: Spread,
    pub y: Spread,
    /// Runs whose `turn(left)` completed without touching anything.
    pub clean: usize,
    pub contacts: u64,
    pub runs: usize,
}

/// Test 3 (Table 12): `followwall(left,1.0)` from one offset.
#[derive(Debug, Clone)]
pub struct Follows {
    pub off: f64,
    pub table: f64,
    pub overshoot: Spread,
    pub at_end: Spread,
    pub contacts: u64,
}

/// Test 4 (Figure 50): `obsavoid(on)`, `goahead(5)` past the box.
#[derive(Debug, Clone)]
pub struct Avoids {
    /// Runs that went round the box (wider than `t4::ASIDE`), ended within
    /// `t4::END_WITHIN` of x = 5 and `t4::BACK_WITHIN` of the line, and touched nothing.
    pub round: usize,
    pub clearance: Spread,
    pub aside: Spread,
    pub contacts: u64,
    pub runs: usize,
}

/// Test 5 (Figure 53): the short task of Figure 52.
#[derive(Debug, Clone)]
pub struct Short {
    pub max_error: Spread,
    pub home: Spread,
    pub link_gap: Spread,
    pub finished: usize,
    /// Each seed's true path, for the spread picture.
    pub tracks: Vec<Vec<(f64, f64)>>,
    pub route: Vec<(f64, f64)>,
}

/// Test 6 (Figure 57): the loop on Workpartner.
#[derive(Debug, Clone)]
pub struct Loops {
    /// Runs that drove the loop out: four followpaths completed, `cnt` 2, finished.
    pub done: usize,
    pub driven: Spread,
    pub off: Spread,
    pub contacts: u64,
    pub runs: usize,
}

/// Test 7 (Figure 59): the way out, and path_1 driven again.
#[derive(Debug, Clone)]
pub struct WayOuts {
    /// Runs that found the door within `t7::DOOR_WITHIN` and ended in the lobby.
    pub out: usize,
    /// Replays of path_1 that completed.
    pub replayed: usize,
    pub replay_off: Spread,
    pub replay_miss: Spread,
    pub contacts: u64,
    pub runs: usize,
}

/// Figure 20, corrected, on MoRo.
#[derive(Debug, Clone)]
pub struct Fetches {
    /// Runs that fetched both loads and came home into room H.
    pub home: usize,
    /// Each seed's `box_at` furthest from the box (`f20::BOX`), over the
    /// searches that completed, m.
    pub box_off: Spread,
    /// Searches for the box that completed, over all seeds.
    pub found: usize,
    pub time: Spread,
    pub driven: Spread,
    pub contacts: u64,
    pub runs: usize,
}

#[derive(Debug, Clone)]
pub struct Predictions {
    pub seeds: usize,
    pub test2: Turns,
    pub test3: Vec<Follows>,
    pub test4: Avoids,
    pub test5: Short,
    pub test6: Loops,
    pub test7: WayOuts,
    pub fig20: Fetches,
}

fn runs<T>(n: usize, run: impl Fn(u64) -> Result<T, String>) -> Result<Vec<T>, String> {
    seeds::first(n)
        .map(|s| run(s).map_err(|e| format!("seed {s}: {e}")))
        .collect()
}

fn spread<T>(runs: &[T], f: impl Fn(&T) -> f64) -> Spread {
    Spread::of(&runs.iter().map(f).collect::<Vec<_>>())
}

pub fn test2(n: usize) -> Result<Turns, String> {
    let runs = runs(n, |s| t2::run_with(PROFILE, s))?;
    let clean = runs
        .iter()
        .filter(|r| r.turn_how.as_deref() == Some("completed") && r.contacts == 0)
        .count();
    Ok(Turns {
        x: spread(&runs, |r| r.x_deviation),
        y: spread(&runs, |r| r.y_deviation),
        clean,
        contacts: runs.iter().map(|r| r.contacts).sum(),
        runs: runs.len(),
    })
}

pub fn test3(n: usize) -> Result<Vec<Follows>, String> {
    let runs = runs(n, |s| t3::run_with(PROFILE, s))?;
    Ok(t3::OFFSETS
        .iter()
        .enumerate()
        .map(|(i, &(off, table))| Follows {
            off,
            table,
            overshoot: spread(&runs, |r| r.follows[i].overshoot),
            at_end: spread(&runs, |r| r.follows[i].at_end),
            contacts: runs.iter().map(|r| r.follows[i].contacts).sum(),
        })
        .collect())
}

pub fn test4(n: usize) -> Result<Avoids, String> {
    let runs = runs(n, |s| t4::run_with(PROFILE, s))?;
    let round = runs
        .iter()
        .filter(|a| {
            a.finished
                && a.contacts == 0
                && a.aside > t4::ASIDE
                && (a.end.x - 5.0).abs() < t4::END_WITHIN
                && a.end.y.abs() < t4::BACK_WITHIN
        })
        .count();
    Ok(Avoids {
        round,
        clearance: spread(&runs, |a| a.clearance),
        aside: spread(&runs, |a| a.aside),
        contacts: runs.iter().map(|a| a.contacts).sum(),
        runs: runs.len(),
    })
}

pub fn test5(n: usize) -> Result<Short, String> {
    let runs = runs(n, |s| t5::run_with(PROFILE, s))?;
    Ok(Short {
        max_error: spread(&runs, |r| r.max_error),
        home: spread(&runs, |r| r.home),
        link_gap: spread(&runs, |r| r.link_gap),
        finished: runs.iter().filter(|r| r.finished).count(),
        tracks: runs
            .iter()
            .map(|r| r.track.iter().map(|p| (p.x, p.y)).collect())
            .collect(),
        route: runs.first().map(|r| r.route.clone()).unwrap_or_default(),
    })
}

pub fn test6(n: usize) -> Result<Loops, String> {
    let runs = runs(n, |s| t6::run_with(PROFILE, s))?;
    let done = runs
        .iter()
        .filter(|r| r.finished && r.cnt == t6::LOOPS && r.followpaths == t6::FOLLOWPATHS)
        .count();
    Ok(Loops {
        done,
        driven: spread(&runs, |r| r.driven),
        off: spread(&runs, |r| r.off),
        contacts: runs.iter().map(|r| r.contacts).sum(),
        runs: runs.len(),
    })
}

pub fn test7(n: usize) -> Result<WayOuts, String> {
    let runs = runs(n, |s| t7::run_with(PROFILE, s))?;
    let out = runs
        .iter()
        .filter(|r| {
            let w = &r.way_out;
            let (dx, dy) = (w.door.0 - t7::DOOR.0, w.door.1 - t7::DOOR.1);
            // As tests/test7_way_out.rs reads `LOBBY`.
            w.finished
                && dx.hypot(dy) < t7::DOOR_WITHIN
                && w.end.y < t7::LOBBY.1
                && w.end.x > t7::LOBBY.0
        })
        .count();
    let replayed = runs
        .iter()
        .filter(|r| r.replay.how.as_deref() == Some("completed"))
        .count();
    Ok(WayOuts {
        out,
        replayed,
        replay_off: spread(&runs, |r| r.replay.off),
        replay_miss: spread(&runs, |r| r.replay.miss),
        contacts: runs
            .iter()
            .map(|r| r.way_out.contacts + r.replay.contacts)
            .sum(),
        runs: runs.len(),
    })
}

pub fn fig20(n: usize) -> Result<Fetches, String> {
    let runs = runs(n, |s| f20::corrected_with(PROFILE, s))?;
    let home = runs
        .iter()
        .filter(|o| o.ended && o.turns == Some(2.0) && o.in_room_h())
        .count();
    let off = |&(x, y): &(f64, f64)| (x - f20::BOX.0).hypot(y - f20::BOX.1);
    Ok(Fetches {
        home,
        box_off: spread(&runs, |o| o.boxes_at.iter().map(off).fold(0.0, f64::max)),
        found: runs.iter().map(|o| o.boxes_at.len()).sum(),
        time: spread(&runs, |o| o.time),
        driven: spread(&runs, |o| o.driven),
        contacts: runs.iter().map(|o| o.contacts).sum(),
        runs: runs.len(),
    })
}

/// Every experiment over the first `n` seeds.
pub fn run(n: usize) -> Result<Predictions, String> {
    Ok(Predictions {
        seeds: n,
        test2: test2(n)?,
        test3: test3(n)?,
        test4: test4(n)?,
        test5: test5(n)?,
        test6: test6(n)?,
        test7: test7(n)?,
        fig20: fig20(n)?,
    })
}

impl Short {
    /// The spread: each seed's true path of Figure 52's task drawn thin over their
    /// mean and the ideal route.
    pub fn spread_figure(&self) -> Figure {
        let mut f = Figure::new(format!(
            "Test 5 over {} seeds: the short task of Figure 52 in empty, {PROFILE} MoRo",
            self.tracks.len()
        ));
        f.legend = Corner::UpperLeft;
        f.references.push(Reference {
            label: Some("ideal route".into()),
            colour: Colour::REFERENCE,
            points: self.route.clone(),
        });
        f.spreads.push(RunSpread {
            label: "true paths, one per seed".into(),
            colour: Colour::TRUE_PATH,
            mean: crate::picture::mean_path(&self.tracks, crate::picture::MEAN_POINTS),
            runs: self.tracks.clone(),
        });
        f
    }
}
