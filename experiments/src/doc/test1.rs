//! Test 1: `turn(d=90,c=..)`, Table 10, run over many seeds with the calibrated error
//! model, and how that model was fitted.

use super::fmt::{f, list, n};
use super::picture;
use crate::stats::Spread;
use crate::test1_turn::{PROFILE, REPLICAS, SEED, Sweep, TOLERANCE, Test1};

/// "0.0231 [0.0205, 0.0257]; 0.0112-0.0403".
pub fn spread(s: &Spread) -> String {
    format!(
        "{} [{}, {}]; {}-{}",
        f(s.mean, 4),
        f(s.lo, 4),
        f(s.hi, 4),
        f(s.min, 4),
        f(s.max, 4)
    )
}

/// Whether the replicas' mean reproduces the table's figure within the tolerance.
pub fn verdict(s: &Spread, table: f64) -> String {
    let e = s.relative_error(table);
    let pct = format!("{:+.0} %", 100.0 * e);
    if e.abs() <= TOLERANCE {
        format!("reproduces ({pct})")
    } else if e < 0.0 {
        format!("beats ({pct})")
    } else {
        format!("misses ({pct})")
    }
}

fn row(s: &Sweep) -> String {
    let d = s.spec.dissertation;
    let (max, mean, std) = (s.max(), s.mean(), s.std());
    format!(
        "| {} x {}, {} | {} | {} | {} | {} | {} | {} | {} / {} |\n",
        s.replicas.len(),
        s.spec.speeds.len(),
        s.label(),
        n(d.max),
        spread(&max),
        verdict(&max, d.max),
        n(d.mean),
        spread(&mean),
        verdict(&mean, d.mean),
        n(d.std),
        f(std.mean, 4),
    )
}

fn by_speed(s: &Sweep) -> String {
    let cells: Vec<String> = s
        .by_speed()
        .iter()
        .map(|(v, sp)| format!("{} m/s: {} (worst {})", n(*v), f(sp.mean, 4), f(sp.max, 4)))
        .collect();
    format!("| {} | {} |\n", s.label(), cells.join(", "))
}

fn calibration() -> String {
    let mut s = String::from(
        "### Calibration

The robots' errors are the `calibrated` profile of `ilmr-sim`
(`robots/sim/src/profile.rs`, listed with each parameter's source in
[docs/robot-model.md](robot-model.md#the-simulated-robots-errors)). Every parameter
but the fitted ones below was fixed first, from the dissertation's text, a data sheet
or a typical value; then the fitted ones were set, once, so that the replicas' mean
maximum and mean deviation of each row of Table 10 come within 30 % of the table's.
Tables 11 and 12 and Test 5 were not looked at while fitting: they are the model's
predictions.

How it went (each point of a grid run over 10 or 20 replicas with the command below):

- MoRo's deviation is set by the drive's dead time: the robot stops late, `v x dead
  time` past the arc's end, so the deviation grows with speed as Table 10's does. The
  wheelbase error, the steering's play and its own dead time barely matter (the
  controller and the gyro correct them), and wheel-size (odometry scale) errors grow
  with the radius, so they hit c=0.4 harder than c=0.6, the opposite of Table 10;
  they stay at their typical values. The dead time was fitted on 0.04, 0.06 and
  0.08 s: 0.06 s brings three of MoRo's four figures within 30 %. None brings the
  fourth, c=0.6's maximum, without the row's mean: at 0.08 s its maximum is 22 %
  short and its mean 57 % over. Table 10's 0.08 m is one trial far from its row's
  others (the row's standard deviation, 0.0242 m, exceeds its mean, 0.0225 m); the
  model has no such outlier. Nor can another value of the errors part the two rows
  as the table does: they are driven at the same speeds and the overrun does not
  depend on the curvature (their maxima here are 0.048 and 0.045 m), while within
  30 % c=0.6's maximum must exceed 0.056 m and c=0.4's stay below 0.052 m. Only an
  error that doubled between c=0.4 and c=0.6 at the same speed would do it; the
  lateral slip, which grows with the curvature, does not (`slip.lateral` at six times
  its typical value: 0.041 and 0.038 m, the controller corrects it).
- Workpartner's deviation is set by its 2 Hz navigation fixes: read as one standard
  deviation, section 5.1.2's 0.1 m would by itself put the robot 0.21 m (mean) off
  the arc, more than Table 10's 0.183 m with every error, so it is read as a 95 %
  bound (two standard deviations), the usual sense of a navigation accuracy; that
  reading was chosen while fitting. The fitted parameter is the steering's play: at
  full lock it leaves the joint short of 0.25 1/m, the clipping section 5.6.1 and
  Figure 48 blame. On 0.5, 1.0 and 1.5 degrees the maximum and mean came +1 / -13 %,
  +17 / +4 % and +36 / +23 % off the table's; 0.75 degrees lies between the first two.

```sh
cargo run --release -p ilmr-experiments --bin calibrate -- \\
    --set moro:actuator.speed_dead_time=0.08 --set moro:actuator.steering_dead_time=0.08
```

prints each row of Table 10 beside the replicas' mean maximum and mean with their
95 % intervals, ranges and the mean at each speed (`--replicas N`, `--profile
ideal|basic|calibrated`, `--set ROBOT:PARAM=VALUE` as often as needed; 6 s of wall time
for 20 replicas in release).

The fitted values (in each row one robot's value was fitted, the other's is the
typical value its source gives):

| parameter | MoRo | Workpartner | unit |
| --- | --- | --- | --- |
",
    );
    for p in ilmr_sim::profile::CALIBRATED {
        if !p.source.contains("fitted") {
            continue;
        }
        let v = |x: Option<f64>| x.map_or("-".to_string(), n);
        s.push_str(&format!(
            "| `{}` | {} | {} | {} |\n",
            p.name,
            v(p.moro),
            v(p.workpartner),
            p.unit
        ));
    }
    s
}

pub fn section(t: &Test1) -> String {
    let speeds: Vec<String> = t
        .sweeps
        .iter()
        .map(|s| format!("- {} at {} m/s", s.label(), list(s.spec.speeds)))
        .collect();
    let mut s = format!(
        "## Test 1: `turn(d=90,c=..)` (Table 10, Figure 46)

`speed(v)` then `t=turn(d=90,c=c)` from (0, 0, 0) in `empty`, on robots with the
`{PROFILE}` error model; deviation = largest distance of the true trace from the
reference arc. A row of Table 10 is one trial per speed on the real robot:

{}

Each row is run {REPLICAS} times (replicas), every trial with a seed of its own (trial
`i` of replica `r`: seed {SEED} + r x speeds + i). A row's maximum is the largest of
its trials, so Table 10's maximum is compared with the mean over the replicas of each
replica's maximum, and its mean with the mean of each replica's mean. Cells: mean
[95 % confidence interval of the mean]; the range over the replicas. A row
reproduces the table when the mean is within {}% of it (`tests/test1_turn.rs`
asserts it).

| replicas x trials, row | Table 10 max (m) | simulated max | | Table 10 mean (m) | simulated mean | | std, Table 10 / simulated |
| --- | --- | --- | --- | --- | --- | --- | --- |
",
        speeds.join("\n"),
        n(100.0 * TOLERANCE),
    );
    for sweep in &t.sweeps {
        s.push_str(&row(sweep));
    }
    s.push_str(
        "\nThe maximum deviation at each speed, mean over the replicas (and the worst), metres:\n\n| row | speed: max deviation |\n| --- | --- |\n",
    );
    for sweep in &t.sweeps {
        s.push_str(&by_speed(sweep));
    }
    s.push('\n');
    s.push_str(&calibration());
    s.push('\n');
    s.push_str(&picture(
        1,
        "Test 1: the first replicas' true paths over the ideal arcs, MoRo c=0.6 and c=0.4, Workpartner c=0.25",
    ));
    s.push_str(&format!(
        "\nThe spread over the replicas: each row's trial at its fastest speed in every one of\nthe {REPLICAS} replicas, drawn thin, and their mean (each path resampled at equal shares\nof its length) drawn thick over the ideal arc.\n\n"
    ));
    s.push_str(&picture(
        9,
        "Test 1's spread: each row's fastest trial in every replica, thin, over their mean",
    ));
    s
}
