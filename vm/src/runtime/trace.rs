//! The VM's trace events and their lines:
//! `{"t":0.01,"event":"start","line":3,"text":"goahead(1.2)"}` then event-specific keys.
//! A line is an [`ilmr_trace::Record`] ([`record`]), the schema every reader reads.
//!
//! A tick keeps one `issue` and one `start` event per statement and one `var` event
//! per variable and statement ([`Coalesce`]): a repeat joins the first, which then
//! carries the last value (or `while` iteration) and how many there were (`count`).
//! A tight loop runs thousands of statements a tick; without this its trace grew by
//! megabytes a second. The events of a tick are then bounded by the program's size,
//! not by the tick's budget.

use std::borrow::Cow;

use ilmr_hal::segment_distance;
use ilmr_motion::obstacle::AvoidState;
use ilmr_stdlib::Field;
use ilmr_trace as schema;
use ilmr_trace::{Num, Record, Stmt};

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

/// Numbers as the trace writes them (four decimals at most), for messages that quote
/// them.
pub use ilmr_trace::fmt_num;

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

fn avoid_state(state: AvoidState) -> schema::AvoidState {
    match state {
        AvoidState::Normal => schema::AvoidState::Normal,
        AvoidState::Avoiding => schema::AvoidState::Avoiding,
        AvoidState::Returning => schema::AvoidState::Returning,
        AvoidState::Blocked => schema::AvoidState::Blocked,
    }
}

/// The trace line of `e`, its texts borrowed from the module and the event.
pub fn record<'a>(m: &'a Module, e: &'a Event) -> Record<'a> {
    let stmt = e.stmt.and_then(|s| m.stmt(s)).map(|s| Stmt {
        line: s.line,
        text: Cow::Borrowed(&s.text),
        // The task is the module's first file: its statements go without a name.
        file: (s.file.0 != 0)
            .then(|| m.files.get(s.file.0 as usize))
            .flatten()
            .map(|f| Cow::Borrowed(f.as_str())),
    });
    let event = match &e.kind {
        EventKind::Issue => schema::Event::Issue(schema::Issue {
            stmt,
            count: e.count,
        }),
        EventKind::Start { iteration } => schema::Event::Start(schema::Start {
            stmt,
            iteration: *iteration,
            count: e.count,
        }),
        EventKind::End {
            how,
            linked,
            code,
            reason,
        } => schema::Event::End(schema::End {
            stmt,
            how: *how,
            linked: *linked,
            code: code.map(|c| Cow::Borrowed(c.code())),
            reason: reason.as_deref().map(Cow::Borrowed),
            help: code.map(|c| Cow::Borrowed(c.help())),
        }),
        EventKind::Var {
            var,
            changed,
            record,
        } => {
            let mut v = schema::Var {
                stmt,
                var: Cow::Borrowed(m.global(*var).map_or("?", |g| g.name.as_str())),
                status: None,
                x: None,
                y: None,
                h: None,
                value: None,
                dist: None,
                how: record.how.filter(|_| changed.has(Field::Status)),
                count: e.count,
            };
            for f in FIELDS {
                if changed.has(f) {
                    let slot = match f {
                        Field::Status => &mut v.status,
                        Field::X => &mut v.x,
                        Field::Y => &mut v.y,
                        Field::H => &mut v.h,
                        Field::Value => &mut v.value,
                        Field::Dist => &mut v.dist,
                    };
                    *slot = Some(Num(record.get(f)));
                }
            }
            schema::Event::Var(v)
        }
        EventKind::Pose {
            x,
            y,
            h,
            speed,
            curvature,
            truth,
        } => schema::Event::Pose(schema::Pose {
            x: Num(*x),
            y: Num(*y),
            h: Num(*h),
            v: Num(*speed),
            c: Num(*curvature),
            source: if *truth {
                schema::Source::Truth
            } else {
                schema::Source::Estimated
            },
        }),
        EventKind::Path { points } => schema::Event::Path(schema::Path {
            stmt,
            points: points.as_slice().into(),
        }),
        EventKind::Avoid { state } => schema::Event::Avoid(schema::Avoid {
            stmt,
            state: avoid_state(*state),
        }),
        EventKind::Fault { fault, message } => schema::Event::Fault(schema::Fault {
            stmt,
            fault: Cow::Borrowed(fault.name()),
            code: Cow::Borrowed(Code::Fault(*fault).code()),
            reaction: Cow::Borrowed(fault.reaction().name()),
            message: Cow::Borrowed(message),
            help: Cow::Borrowed(Code::Fault(*fault).help()),
        }),
        EventKind::Recovered { fault } => schema::Event::Recovered(schema::Recovered {
            stmt,
            fault: Cow::Borrowed(fault.name()),
            code: Cow::Borrowed(Code::Fault(*fault).code()),
        }),
        EventKind::Overrun { pending } => schema::Event::Overrun(schema::Overrun {
            stmt,
            pending: *pending,
        }),
        EventKind::Error { message } => schema::Event::Error(schema::Error {
            stmt,
            message: Cow::Borrowed(message),
        }),
    };
    Record::new(e.t, event)
}

/// One event as one line of JSON (no newline).
pub fn render_event(m: &Module, e: &Event) -> String {
    ilmr_trace::to_line(&record(m, e))
}

/// Writes events as JSON Lines (without the trace's version line: these are the
/// events of a trace, not a trace file).
pub fn write_jsonl(
    m: &Module,
    events: &[Event],
    out: &mut impl std::io::Write,
) -> std::io::Result<()> {
    for e in events {
        ilmr_trace::write_line(&mut *out, &record(m, e))?;
        out.write_all(b"\n")?;
    }
    Ok(())
}

/// Events as JSON Lines in one string (for snapshots).
pub fn to_jsonl(m: &Module, events: &[Event]) -> String {
    let mut out = Vec::new();
    // Into memory the write cannot fail.
    let _ = write_jsonl(m, events, &mut out);
    String::from_utf8(out).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

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
