//! Tests 2-7 and Figure 20 over many seeds on the calibrated model, each row beside
//! the dissertation's figure with its verdict and why.

use super::fmt::{f, n};
use super::test1::{spread, verdict};
use crate::predictions::{PROFILE, Predictions};
use crate::seeds::FIRST;
use crate::stats::Spread;
use crate::{test2_turn_left as t2, test5_short_task as t5, test6_loop as t6};

/// A table row: the figure, the dissertation's, the model's, the verdict, why.
fn row(what: &str, dissertation: &str, model: &str, verdict: &str, why: &str) -> String {
    format!("| {what} | {dissertation} | {model} | {verdict} | {why} |\n")
}

fn measured(what: &str, s: &Spread, table: f64, why: &str) -> String {
    row(what, &n(table), &spread(s), &verdict(s, table), why)
}

/// A count of runs that did what the dissertation's run did: it reproduces the
/// dissertation only when every seed does.
fn count(what: &str, dissertation: &str, k: usize, runs: usize, why: &str) -> String {
    let verdict = if k == runs {
        "reproduces".to_string()
    } else {
        format!("misses ({} of {runs} fail)", runs - k)
    };
    row(what, dissertation, &format!("{k} of {runs}"), &verdict, why)
}

/// A figure of the project's own, with nothing of the dissertation's beside it.
fn own(what: &str, model: &str, why: &str) -> String {
    row(what, "-", model, "the project's own", why)
}

pub fn section(p: &Predictions) -> String {
    let mut s = format!(
        "## Predictions of the calibrated model: tests 2-7 and Figure 20 over {} seeds

Each experiment as its section below runs it, on robots with the `{PROFILE}` error model
fitted to Table 10 alone, over {} seeds ({FIRST}, {}, ...; tests 6 and 7 drive their
second run with the next seed), and not retuned for these figures. Cells: mean [95 %
confidence interval of the mean]; the range over the seeds, whose top is the worst run.
A measured figure reproduces the dissertation's when the mean is within 30 % of it,
beats it below, misses it above; a run the dissertation reports as a success
reproduces it when every seed succeeds. `tests/predictions.rs` asserts each row against
the dissertation's figure with the tolerance it states (`cargo test` runs the first
seeds; `ILMR_EXPERIMENTS=full` all of them).

| figure | dissertation | calibrated model | verdict | why |
| --- | --- | --- | --- | --- |
",
        p.seeds,
        p.seeds,
        FIRST + 1
    );
    s.push_str(&measured(
        "Test 2 (Table 11), x deviation heading north, m",
        &p.test2.x,
        t2::TABLE_11_X,
        "the model lacks whatever made the real corridor runs wander (see below)",
    ));
    s.push_str(&measured(
        "Test 2 (Table 11), y deviation before the corner, m",
        &p.test2.y,
        t2::TABLE_11_Y,
        "followwall holds the distance the gyro-corrected heading gives it",
    ));
    s.push_str(&count(
        "Test 2 (Table 11), turns without a deviant trial",
        "4 of 5",
        p.test2.clean,
        p.test2.runs,
        "the deviant trial was blamed on scanner data the model does not produce",
    ));
    for f in &p.test3 {
        s.push_str(&measured(
            &format!(
                "Test 3 (Table 12), excess of the goal distance from {} m off, m",
                n(f.off)
            ),
            &f.overshoot,
            f.table,
            "Table 12 is the qnx-simulator's; here the calibrated MoRo's dead time",
        ));
    }
    let t4 = &p.test4;
    s.push_str(&count(
        "Test 4 (Figure 50), `obsavoid(on)` round the box and back, no contact",
        "passes it (\"tested successfully\")",
        t4.round,
        t4.runs,
        "the avoider plans round what the scanner sees; its noise is centimetres",
    ));
    s.push_str(&own(
        "Test 4, footprint's clearance of the box, m",
        &spread(&t4.clearance),
        "Figure 50 gives no distance",
    ));
    let t5 = &p.test5;
    s.push_str(&measured(
        "Test 5 (Figure 53), largest distance from the route, m",
        &t5.max_error,
        t5::FIGURE_53,
        "the dead time's overrun at each stop, corrected by `use(goalpos)` on the way back",
    ));
    s.push_str(&measured(
        "Test 5 (Figure 53), distance from the start at the end, m",
        &t5.home,
        t5::FIGURE_53,
        "the way back is driven on odometry whose scale errors are a per cent",
    ));
    s.push_str(&measured(
        "Test 5 (Figure 55), time to link two commands, s",
        &t5.link_gap,
        t5::LINK_BAR,
        "the next movement starts in the tick the linked one ends; MoRo's took about 0.1 s",
    ));
    let t6 = &p.test6;
    s.push_str(&count(
        "Test 6 (Figure 57), the loop driven out (4 followpaths, `cnt` 2)",
        "done",
        t6.done,
        t6.runs,
        "followpath and the reversing skills finish on every seed",
    ));
    s.push_str(&row(
        "Test 6, metres driven",
        &format!("more than {}", n(t6::DRIVEN_BAR)),
        &spread(&t6.driven),
        &if t6.driven.min > t6::DRIVEN_BAR {
            "reproduces".to_string()
        } else {
            format!("misses (shortest {})", f(t6.driven.min, 1))
        },
        "the same task over the same taught path",
    ));
    s.push_str(&own(
        "Test 6, farthest from the taught path mid-way, m",
        &spread(&t6.off),
        "Figure 57 gives no deviation; the 0.1 m navigation fixes set it",
    ));
    let t7 = &p.test7;
    s.push_str(&count(
        "Test 7 (Figure 59), the way out: door found, ended in the lobby",
        "done",
        t7.out,
        t7.runs,
        if t7.out == t7.runs {
            "in the office's 2 m corridors, out of the lab door `turn(left)` has room while the rear axle is within about 0.1 m of the door's line: the outline keeps its margin (rounded at the corners) and the avoider's area its own (section 4.5.7)"
        } else {
            "in the office's 2 m corridors: a run that fails stops in the lab door, where `turn(left)` finds no room for the calibrated robot's outline"
        },
    ));
    s.push_str(&count(
        "Test 7, `followpath(path_1)` driven again",
        "done",
        t7.replayed,
        t7.runs,
        if t7.replayed == t7.runs {
            "path_1, recorded on the way out, is driven from the start on a fresh robot"
        } else {
            "a replay that fails stands stalled short of path_1's end; not yet analysed"
        },
    ));
    s.push_str(&own(
        "Test 7, the replay's farthest from path_1, m",
        &spread(&t7.replay_off),
        "the dissertation shows path_1 driven, not how close",
    ));
    let fig = &p.fig20;
    s.push_str(&own(
        "Figure 20, both loads fetched and home in room H",
        &format!("{} of {}", fig.home, fig.runs),
        "section 4.1 shows the task, never a run. Before the box recogniser bridged dropouts, `findtarget(scanner,box)`, issued while MoRo was still in the hall, took a stretch of the hall's walls or the cupboard between two dropouts for the box on every seed and each trip drove on to wherever that was (17 of 20 home all the same; seeds 1002, 1013 and 1014 failed). With the search going on into the store room, two seeds failed on the door detector: a mixed pixel at the store room door's far jamb, 0.19 m behind the wall's line, passed for the jamb and put the door 0.23 m east of its middle, so that backing out along `ToDoor` the supervisor held MoRo 0.08 m from the east jamb (equation (12)'s 1.2 x width, checked backwards where the scanner does not look); and room H's door, seen through three beams 9 m off while MoRo still turned out of its three-point turn, started `Turn(Door)`'s Bezier (equation (3): control points 0.4 of the distance along the headings) pointing at the hall's north wall, and it bulged to within 0.1 m of the avoider's area, which held it. A jamb off the line of the wall returns beyond it is now stepped over, and a door needs four beams through it: the Bezier into H peaks at most 28.97 m north, 0.95 m from the wall's face",
    ));
    s.push_str(&own(
        "Figure 20, `box_at` from the box's centre, the further of each seed's searches, m",
        &spread(&fig.box_off),
        &format!(
            "{} searches ended, all on `box2`; the recogniser reports the middle of the face it sees (the box's east end, 0.2 m from its centre) in the robot's dead-reckoned frame; `tests/predictions.rs` asserts every one within {} m (`BOX_CALIBRATED_WITHIN`: 0.2 m for the face, 0.3 m of dead reckoning, within which `approach(box_at,1.35)` still stops short of the box); the walls and cupboard it took for the box before lay 3-8 m off",
            fig.found,
            n(crate::fig20_fetch_boxes::BOX_CALIBRATED_WITHIN)
        ),
    ));
    s.push_str(&own(
        "Figure 20, simulated seconds",
        &spread(&fig.time),
        "two 20 s loads and the way in between",
    ));
    let contacts = p.test2.contacts
        + p.test3.iter().map(|f| f.contacts).sum::<u64>()
        + t4.contacts
        + t6.contacts
        + t7.contacts
        + fig.contacts;
    s.push_str(&format!(
        "
Contacts with walls or obstacles over all these runs: {contacts}.

Table 11 has one deviant trial of five (\"the reason could have been an erroneous data
from the scanner\"); the model's scanner errors (1 cm noise, dropouts, mixed pixels,
skew) do not fool `turn(left)`'s search for room, and what fooled MoRo's is not
modelled. The x and y deviations beat the table by far: the calibrated MoRo's largest
error is the drive's dead time, felt where it stops, while `turn(left)` drives on at
0.3 m/s, and the heading errors its gyro corrects; whatever else made the real
corridor runs wander (the real walls and what the scanner made of them) is not
modelled. Table 12 comes from the dissertation's qnx-simulator, not from MoRo (section
5.6.2), so the calibrated model is compared with another simulator there. Figure 53's
0.07 m is the real MoRo's largest error \"when going back to the starting point\".
Test 4's `stop` and `off` rows in its section below are the project's own (Table 9
runs `obsavoid(on)` only) and stay out of this table.
"
    ));
    s.push('\n');
    s.push_str(&super::picture(
        10,
        "Test 5 over the seeds: each seed's true path drawn thin over their mean, and the ideal route",
    ));
    s
}
