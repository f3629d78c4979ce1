//! Typed trace events and their JSON Lines rendering:
//! `{"t":0.01,"event":"start","line":3,"text":"goahead(1.2)"}` then event-specific keys.
//!
//! A tick keeps one `issue` and one `start` event per statement and one `var` event
//! per variable and statement ([`Coalesce`]): a repeat joins the first, which then
//! carries the last value (or `while` iteration) and how many there were (`count`).
//! A tight loop runs thousands of statements a tick; without this its trace grew by
//! megabytes a second. The events of a tick are then bounded by the program's size,
//! not by the tick's budget.

use std::fmt::Write;

use ilmr_hal::segment_distance;
use ilmr_motion::obstacle::AvoidState;

use crate::bytecode::{Module, StmtId, VarId};

use super::safety::{Code, Fault};
use super::vars::{FIELDS, FieldMask, How, VarRecord};

#[derive(Debug, Clone, PartialEq)]
pub enum EventKind {
    /// A statement was executed by its block.
    Issue,
    /// A command began to act later than it was issued: a queued movement got the
    /// reservation, an `if` body started, a `while` iteration started.
    Start { iteration: Option<u32> },
    End {
        how: How,
        /// A movement ended early because the next one was joined to it.
        linked: bool,
        /// The stable code of a safety refusal or of the fault that ended it.
        code: Option<Code>,
        reason: Option<String>,
    },
    Var {
        var: VarId,
        changed: FieldMask,
        record: VarRecord,
    },
    Pose {
        x: f64,
        y: f64,
        h: f64,
        speed: f64,
        curvature: f64,
        /// Ground truth (`true`) or the robot's estimate.
        truth: bool,
    },
    /// A movement got a reference path (when it started, or a behaviour re-planned
    /// it): the path's points in the robot's frame, thinned by [`outline`] to
    /// [`OUTLINE_TOLERANCE`]. Traced at [`super::config::TraceLevel::Full`] only, like
    /// pose samples: it is for drawing.
    Path { points: Vec<(f64, f64)> },
    /// Obstacle avoidance changed state while the movement ran (section 4.5.7):
    /// `avoiding` (it drives round an obstacle, the movement's output suppressed),
    /// `returning` (back to the reference after the security wait), `normal`,
    /// `blocked` (halted: `obsavoid(stop)`, or no way round).
    Avoid { state: AvoidState },
    /// The supervisor raised a fault (`docs/reliability.md`): its reaction is in
    /// force until `Recovered` (an operation that timed out is given up at once).
    Fault { fault: Fault, message: String },
    /// The fault's condition has cleared.
    Recovered { fault: Fault },
    /// A block ran out of the tick's budget and was suspended.
    Overrun { pending: u32 },
    /// A runtime error that ended no command (a division by zero, a HAL call failing).
    Error { message: String },
}

#[derive(Debug, Clone, PartialEq)]
pub struct Event {
    pub tick: u64,
    /// Seconds.
    pub t: f64,
    pub stmt: Option<StmtId>,
    pub kind: EventKind,
    /// How many events of this tick this one stands for (1 unless [`Coalesce`] joined
    /// repeats into it).
    pub count: u32,
}

impl Event {
    /// One event, standing for itself.
    pub fn new(tick: u64, t: f64, stmt: Option<StmtId>, kind: EventKind) -> Event {
        Event {
            tick,
            t,
            stmt,
            kind,
            count: 1,
        }
    }
}

/// What makes two events of one tick the same for [`Coalesce`]: the kind, the
/// statement, and for `var` the variable and the fields that changed (a status
/// change is news of its own, not one more write of the value).
type Key = (u8, u32, u32);

fn coalesce_key(e: &Event) -> Option<Key> {
    let stmt = e.stmt.map_or(u32::MAX, |s| s.0);
    match &e.kind {
        EventKind::Issue => Some((0, stmt, 0)),
        EventKind::Start { .. } => Some((1, stmt, 0)),
        EventKind::Var { var, changed, .. } => Some((2 | changed.0 << 2, stmt, var.0)),
        _ => None,
    }
}

/// Joins repeats of `issue`, `start` and `var` events within a tick into the first
/// (see the module's documentation). Other events are never joined: an `end` or an
/// `overrun` each say something of their own, and both are bounded per tick by the
/// live commands and blocks.
#[derive(Debug, Default)]
pub struct Coalesce {
    tick: u64,
    /// Where in the event buffer the first event of each key of `tick` is.
    first: rustc_hash::FxHashMap<Key, usize>,
}

impl Coalesce {
    /// Appends `e` to `events`, or joins it into the same event earlier in its tick.
    pub fn push(&mut self, events: &mut Vec<Event>, e: Event) {
        let Some(key) = coalesce_key(&e) else {
            events.push(e);
            return;
        };
        if self.tick != e.tick {
            self.first.clear();
            self.tick = e.tick;
        }
        // The buffer may have been taken since: the index must still hold this
        // tick's event of the same key.
        if let Some(first) = self
            .first
            .get(&key)
            .and_then(|&i| events.get_mut(i))
            .filter(|f| f.tick == e.tick && coalesce_key(f) == Some(key))
        {
            first.count = first.count.saturating_add(e.count);
            match (&mut first.kind, e.kind) {
                (EventKind::Start { iteration }, EventKind::Start { iteration: last }) => {
                    *iteration = last;
                }
                (EventKind::Var { record, .. }, EventKind::Var { record: last, .. }) => {
                    *record = last;
                }
                _ => {}
            }
            return;
        }
        self.first.insert(key, events.len());
        events.push(e);
    }
}

impl EventKind {
    pub fn name(&self) -> &'static str {
        match self {
            EventKind::Issue => "issue",
            EventKind::Start { .. } => "start",
            EventKind::End { .. } => "end",
            EventKind::Var { .. } => "var",
            EventKind::Pose { .. } => "pose",
            EventKind::Path { .. } => "path",
            EventKind::Avoid { .. } => "avoid",
            EventKind::Fault { .. } => "fault",
            EventKind::Recovered { .. } => "recovered",
            EventKind::Overrun { .. } => "overrun",
            EventKind::Error { .. } => "error",
        }
    }
}

/// Formats a number with at most four decimals and no trailing zeros (`-0` as `0`).
pub fn fmt_num(x: f64) -> String {
    if !x.is_finite() {
        return if x.is_nan() {
            "null".into()
        } else if x > 0.0 {
            "1e999".into()
        } else {
            "-1e999".into()
        };
    }
    let s = format!("{:.4}", x);
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" { "0".into() } else { s }
}

/// How far a traced reference path may stray from the planned one, metres: a plot
/// cannot show less, and a straight leg keeps only its two ends.
pub const OUTLINE_TOLERANCE: f64 = 0.01;

/// The points of a polyline that keep it within `tolerance` of the original
/// (Ramer-Douglas-Peucker, with an explicit stack so a long path cannot overflow
/// the call stack). The ends are always kept.
pub fn outline(points: &[(f64, f64)], tolerance: f64) -> Vec<(f64, f64)> {
    if points.len() <= 2 {
        return points.to_vec();
    }
    let mut keep = vec![false; points.len()];
    keep[0] = true;
    keep[points.len() - 1] = true;
    let mut spans = vec![(0, points.len() - 1)];
    while let Some((a, b)) = spans.pop() {
        let (far, dist) = (a + 1..b)
            .map(|i| (i, segment_distance(points[i], points[a], points[b])))
            .fold(
                (a, 0.0),
                |best, cur| if cur.1 > best.1 { cur } else { best },
            );
        if dist > tolerance {
            keep[far] = true;
            spans.push((a, far));
            spans.push((far, b));
        }
    }
    points
        .iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(*p))
        .collect()
}

fn json_str(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

/// One event as one line of JSON (no newline).
pub fn render_event(m: &Module, e: &Event) -> String {
    let mut o = String::with_capacity(96);
    let _ = write!(
        o,
        "{{\"t\":{},\"event\":\"{}\"",
        fmt_num(e.t),
        e.kind.name()
    );
    if let Some(s) = e.stmt.and_then(|s| m.stmt(s)) {
        let _ = write!(o, ",\"line\":{},\"text\":", s.line);
        json_str(&mut o, &s.text);
    }
    match &e.kind {
        EventKind::Issue => {}
        EventKind::Start { iteration } => {
            if let Some(i) = iteration {
                let _ = write!(o, ",\"iteration\":{i}");
            }
        }
        EventKind::End {
            how,
            linked,
            code,
            reason,
        } => {
            let _ = write!(o, ",\"how\":\"{}\"", how.name());
            if *linked {
                o.push_str(",\"linked\":true");
            }
            if let Some(c) = code {
                let _ = write!(o, ",\"code\":\"{}\"", c.code());
            }
            if let Some(r) = reason {
                o.push_str(",\"reason\":");
                json_str(&mut o, r);
            }
            if let Some(c) = code {
                o.push_str(",\"help\":");
                json_str(&mut o, c.help());
            }
        }
        EventKind::Var {
            var,
            changed,
            record,
        } => {
            o.push_str(",\"var\":");
            json_str(&mut o, m.global(*var).map_or("?", |g| g.name.as_str()));
            for f in FIELDS {
                if changed.has(f) {
                    let _ = write!(o, ",\"{}\":{}", f.name(), fmt_num(record.get(f)));
                }
            }
            if let Some(how) = record
                .how
                .filter(|_| changed.has(ilmr_stdlib::Field::Status))
            {
                let _ = write!(o, ",\"how\":\"{}\"", how.name());
            }
        }
        EventKind::Pose {
            x,
            y,
            h,
            speed,
            curvature,
            truth,
        } => {
            let _ = write!(
                o,
                ",\"x\":{},\"y\":{},\"h\":{},\"v\":{},\"c\":{},\"source\":\"{}\"",
                fmt_num(*x),
                fmt_num(*y),
                fmt_num(*h),
                fmt_num(*speed),
                fmt_num(*curvature),
                if *truth { "true" } else { "estimated" }
            );
        }
        EventKind::Path { points } => {
            o.push_str(",\"points\":[");
            for (i, (x, y)) in points.iter().enumerate() {
                if i > 0 {
                    o.push(',');
                }
                let _ = write!(o, "[{},{}]", fmt_num(*x), fmt_num(*y));
            }
            o.push(']');
        }
        EventKind::Avoid { state } => {
            let name = match state {
                AvoidState::Normal => "normal",
                AvoidState::Avoiding => "avoiding",
                AvoidState::Returning => "returning",
                AvoidState::Blocked => "blocked",
            };
            let _ = write!(o, ",\"state\":\"{name}\"");
        }
        EventKind::Fault { fault, message } => {
            let _ = write!(
                o,
                ",\"fault\":\"{}\",\"code\":\"{}\",\"reaction\":\"{}\",\"message\":",
                fault.name(),
                Code::Fault(*fault).code(),
                fault.reaction().name()
            );
            json_str(&mut o, message);
            o.push_str(",\"help\":");
            json_str(&mut o, Code::Fault(*fault).help());
        }
        EventKind::Recovered { fault } => {
            let _ = write!(
                o,
                ",\"fault\":\"{}\",\"code\":\"{}\"",
                fault.name(),
                Code::Fault(*fault).code()
            );
        }
        EventKind::Overrun { pending } => {
            let _ = write!(o, ",\"pending\":{pending}");
        }
        EventKind::Error { message } => {
            o.push_str(",\"message\":");
            json_str(&mut o, message);
        }
    }
    if e.count > 1 {
        let _ = write!(o, ",\"count\":{}", e.count);
    }
    o.push('}');
    o
}

/// Writes events as JSON Lines.
pub fn write_jsonl(
    m: &Module,
    events: &[Event],
    out: &mut impl std::io::Write,
) -> std::io::Result<()> {
    for e in events {
        writeln!(out, "{}", render_event(m, e))?;
    }
    Ok(())
}

/// Events as JSON Lines in one string (for snapshots).
pub fn to_jsonl(m: &Module, events: &[Event]) -> String {
    let mut s = String::new();
    for e in events {
        s.push_str(&render_event(m, e));
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_stable() {
        assert_eq!(fmt_num(0.01), "0.01");
        assert_eq!(fmt_num(3.0 * 0.01), "0.03");
        assert_eq!(fmt_num(-0.00001), "0");
        assert_eq!(fmt_num(1.23456), "1.2346");
        assert_eq!(fmt_num(2.0), "2");
    }

    #[test]
    fn an_outline_keeps_the_ends_and_the_bends() {
        let line: Vec<(f64, f64)> = (0..=100).map(|i| (f64::from(i) * 0.05, 0.0)).collect();
        assert_eq!(outline(&line, 0.01), vec![(0.0, 0.0), (5.0, 0.0)]);
        let arc: Vec<(f64, f64)> = (0..=90)
            .map(|d| {
                let a = f64::from(d).to_radians();
                (2.0 * a.sin(), 2.0 - 2.0 * a.cos())
            })
            .collect();
        let kept = outline(&arc, 0.01);
        assert!(kept.len() > 2 && kept.len() < 20, "{} points", kept.len());
        assert_eq!((kept[0], kept[kept.len() - 1]), (arc[0], arc[90]));
        for p in &arc {
            let near = kept
                .windows(2)
                .map(|w| segment_distance(*p, w[0], w[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(near <= 0.01 + 1e-12, "{p:?} is {near} m off the outline");
        }
    }

    #[test]
    fn a_path_event_lists_its_points() {
        let m = crate::bytecode::ModuleBuilder::new().into_extended().0;
        let e = Event::new(
            3,
            0.03,
            None,
            EventKind::Path {
                points: vec![(1.0, 2.0), (3.25, -0.5)],
            },
        );
        assert_eq!(
            render_event(&m, &e),
            r#"{"t":0.03,"event":"path","points":[[1,2],[3.25,-0.5]]}"#
        );
    }
}
