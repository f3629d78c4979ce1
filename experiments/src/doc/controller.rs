//! What this project's changes to the position controller add, over the same seeds.

use super::fmt::n;
use super::test1::{spread, verdict};
use crate::controller::{Comparison, VARIANTS};

pub fn section(c: &Comparison) -> String {
    let mut s = format!(
        "## What the controller adds (the dissertation's controller beside this project's)

The position controller of section 4.5.2.2 (eqs. 4-8) as the dissertation describes
it, and as this project runs it, on the calibrated robots over the same seeds (Test 1:
{} replicas of each row as in its section; Test 5: {} seeds as in the predictions), so
that each difference is the controller's alone. `ilmr_vm::Config::controller` switches
the two changes this project made:

- the look-ahead floor: the look-ahead is never shorter than half a turning radius
  (`ControllerParams::min_lookahead_radii`, 2 m on Workpartner); the dissertation sets
  it by the speed, Δc and the curvature gap alone;
- c_now of eq. (4) is the curvature the controller commanded last cycle; the
  dissertation's is \"the current curvature of the robot\", which lags the command by
  the steering's dead time.

Both variants read eq. (6b) with err_right (the dissertation prints err_left: taken as
a typo, `robots/motion/src/controller/mod.rs` says why). Cells: mean [95 % confidence
interval]; range, m; the verdict against the dissertation's figure as in the
predictions.

| figure | dissertation's robot (m) |{}
| --- | --- |{}
",
        c.replicas,
        c.seeds,
        VARIANTS
            .iter()
            .map(|(name, _)| format!(" {name} | |"))
            .collect::<String>(),
        " --- | --- |".repeat(VARIANTS.len()),
    );
    for r in &c.rows {
        let cells: String =
            r.by.iter()
                .map(|b| format!(" {} | {} |", spread(b), verdict(b, r.table)))
                .collect();
        s.push_str(&format!("| {} | {} |{cells}\n", r.what, n(r.table)));
    }
    let better = c
        .rows
        .iter()
        .filter(|r| r.project().hi < r.dissertation().lo)
        .count();
    let worse = c
        .rows
        .iter()
        .filter(|r| r.project().lo > r.dissertation().hi)
        .count();
    s.push_str(&format!(
        "\nThis project's controller is better than the dissertation's, with the 95 % intervals \
         apart, on {better} of {} figures, and worse on {worse}; on the others the intervals \
         overlap.

Most of the difference is c_now. Fed back as measured, the curvature lags the command
by the steering's dead time (`actuator.steering_dead_time` of the calibrated profile),
so each cycle's eq. (4) starts from a curvature already left behind: the steering
swings round the reference and the robot leaves the arc by decimetres on MoRo and by
metres on Workpartner, whose steering is slow. Commanded, the controller alone
brings MoRo within Table 10. The look-ahead floor (half a turning radius) then matters on
Workpartner alone: MoRo's 0.375 m is below the VM's shortest look-ahead, 0.6 m, so its
rows do not change, while Workpartner's look-ahead at 0.2-0.4 m/s would otherwise fall
towards those 0.6 m against its 2 m floor, and the robot would answer each 2 Hz
navigation fix with a swing of the steering it cannot make up at full lock. The dissertation's robots ran at least the
first change in effect, or they would not have measured Table 10: its text does not
say which curvature its controller read.
",
        c.rows.len()
    ));
    s
}
