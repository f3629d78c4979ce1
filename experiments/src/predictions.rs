//! Tables 11 and 12 and Test 5 (Figure 53's 0.07 m) as predictions of the calibrated
//! error model (issue 15 item 2): tests 2, 3 and 5 run over [`SEEDS`] seeds on robots
//! with the `calibrated` profile, which was fitted to Table 10 alone, and reported
//! beside the dissertation's figures without retuning.

use ilmr_sim::SimProfile;

use crate::stats::Spread;
use crate::{test2_turn_left as t2, test3_followwall as t3, test5_short_task as t5};

/// How many seeds each prediction runs over.
pub const SEEDS: usize = 20;

/// The first seed; run `i` uses `FIRST_SEED + i` (apart from Test 1's seeds).
pub const FIRST_SEED: u64 = 1001;

pub const PROFILE: SimProfile = SimProfile::Calibrated;

/// Test 2 (Table 11): `turn(left)` in the corridor.
#[derive(Debug, Clone)]
pub struct Turns {
    pub x: Spread,
    pub y: Spread,
    /// Runs whose `turn(left)` completed without touching anything.
    pub clean: usize,
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

/// Test 5 (Figure 53): the short task of Figure 52.
#[derive(Debug, Clone)]
pub struct Short {
    pub max_error: Spread,
    pub home: Spread,
    pub finished: usize,
}

#[derive(Debug, Clone)]
pub struct Predictions {
    pub test2: Turns,
    pub test3: Vec<Follows>,
    pub test5: Short,
}

fn seeds() -> impl Iterator<Item = u64> {
    (0..SEEDS as u64).map(|i| FIRST_SEED + i)
}

pub fn test2() -> Result<Turns, String> {
    let runs = seeds()
        .map(|s| t2::run_with(PROFILE, s))
        .collect::<Result<Vec<_>, _>>()?;
    let clean = runs
        .iter()
        .filter(|r| r.turn_how.as_deref() == Some("completed") && r.contacts == 0)
        .count();
    Ok(Turns {
        x: Spread::of(&runs.iter().map(|r| r.x_deviation).collect::<Vec<_>>()),
        y: Spread::of(&runs.iter().map(|r| r.y_deviation).collect::<Vec<_>>()),
        clean,
        runs: runs.len(),
    })
}

pub fn test3() -> Result<Vec<Follows>, String> {
    let runs = seeds()
        .map(|s| t3::run_with(PROFILE, s))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(t3::OFFSETS
        .iter()
        .enumerate()
        .map(|(i, &(off, table))| {
            let of = |f: fn(&t3::Follow) -> f64| {
                Spread::of(&runs.iter().map(|r| f(&r.follows[i])).collect::<Vec<_>>())
            };
            Follows {
                off,
                table,
                overshoot: of(|f| f.overshoot),
                at_end: of(|f| f.at_end),
                contacts: runs.iter().map(|r| r.follows[i].contacts).sum(),
            }
        })
        .collect())
}

pub fn test5() -> Result<Short, String> {
    let runs = seeds()
        .map(|s| t5::run_with(PROFILE, s))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Short {
        max_error: Spread::of(&runs.iter().map(|r| r.max_error).collect::<Vec<_>>()),
        home: Spread::of(&runs.iter().map(|r| r.home).collect::<Vec<_>>()),
        finished: runs.iter().filter(|r| r.finished).count(),
    })
}

pub fn run() -> Result<Predictions, String> {
    Ok(Predictions {
        test2: test2()?,
        test3: test3()?,
        test5: test5()?,
    })
}
