//! Assertions evaluated on a run's trace, read back as `ilmr_trace` records.

use ilmr_trace::{Event, How, Record};

use super::assertion::{
    Assertion, Command, Field, Final, Goal, Happening, Kind, Near, Never, Scope, State, VarCheck,
    num,
};

/// Why an assertion does not hold: when, and what was seen.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// Seconds of logical time at which it was seen not to hold.
    pub t: f64,
    pub message: String,
}

/// The facts of a run the assertions read, gathered in one pass over its trace.
pub struct Run<'r> {
    records: &'r [Record<'r>],
    /// The time of the last record: the run's end.
    end: f64,
    /// The times samples and happenings are read from (a scope of `always`/`never`).
    window: (f64, f64),
}

impl<'r> Run<'r> {
    pub fn new(records: &'r [Record<'r>]) -> Run<'r> {
        let end = records.iter().map(|r| r.t.0).fold(0.0, f64::max);
        Run {
            records,
            end,
            window: (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    /// The run seen only within the scope. A scope `while C` of a command that never
    /// ran is a failure: the assertion would hold of nothing.
    fn scoped(&self, scope: &Scope) -> Result<Run<'r>, Failure> {
        let mut lo = scope.from.unwrap_or(f64::NEG_INFINITY);
        let mut hi = scope.until.unwrap_or(f64::INFINITY);
        if let Some(c) = &scope.during {
            let (started, ends) = self.life(c);
            let Some(s) = started.or(ends.first().map(|e| e.0)) else {
                return Err(Failure {
                    t: self.end,
                    message: format!("{} never ran", c.shown),
                });
            };
            lo = lo.max(s);
            hi = hi.min(ends.first().map_or(self.end, |e| e.0));
        }
        Ok(Run {
            records: self.records,
            end: self.end,
            window: (lo, hi),
        })
    }

    fn in_window(&self, t: f64) -> bool {
        self.window.0 - 1e-9 <= t && t <= self.window.1 + 1e-9
    }

    pub fn check(&self, a: &Assertion) -> Result<(), Failure> {
        match &a.kind {
            Kind::Eventually { within, goal } => self.eventually(*within, goal),
            Kind::Always(scope, state) => self.scoped(scope)?.always(state),
            Kind::Never(scope, Never::State(state)) => self.scoped(scope)?.never_state(state),
            Kind::Never(scope, Never::Happening(h)) => self.scoped(scope)?.never_happens(h),
            Kind::Before(x, y) => self.before(x, y),
            Kind::During(x, y) => self.during(x, y),
            Kind::AtEnd(f) => self.at_end(f),
        }
    }

    fn poses(&self) -> impl Iterator<Item = (f64, &ilmr_trace::Pose)> {
        self.records.iter().filter_map(|r| match &r.event {
            Event::Pose(p) if self.in_window(r.t.0) => Some((r.t.0, p)),
            _ => None,
        })
    }

    /// The nearest hit of each scan, metres from the scanner.
    fn clearances(&self) -> impl Iterator<Item = (f64, f64)> {
        self.records.iter().filter_map(|r| match &r.event {
            Event::Scan(s) if self.in_window(r.t.0) => {
                let (x, y) = (s.x.0, s.y.0);
                let nearest = s
                    .hits
                    .0
                    .iter()
                    .map(|(hx, hy)| (hx - x).hypot(hy - y))
                    .fold(f64::INFINITY, f64::min);
                Some((r.t.0, nearest))
            }
            _ => None,
        })
    }

    /// When the command first started, and `(t, how)` of every end of it. A command
    /// starts at its first `start` event (a movement getting the reservation, an `if`
    /// body, a `while` iteration), or, having none, when it was first issued: a
    /// movement issued behind another waits in the queue until it starts.
    fn life(&self, c: &Command) -> (Option<f64>, Vec<(f64, How)>) {
        let (mut issued, mut started) = (None, None);
        let mut ends = Vec::new();
        for r in self.records {
            let (stmt, first) = match &r.event {
                Event::Issue(i) => (i.stmt.as_ref(), &mut issued),
                Event::Start(s) => (s.stmt.as_ref(), &mut started),
                Event::End(e) => {
                    if e.stmt.as_ref().is_some_and(|s| c.is(s)) {
                        ends.push((r.t.0, e.how));
                    }
                    continue;
                }
                _ => continue,
            };
            if stmt.is_some_and(|s| c.is(s)) {
                first.get_or_insert(r.t.0);
            }
        }
        (started.or(issued), ends)
    }

    fn eventually(&self, within: Option<f64>, goal: &Goal) -> Result<(), Failure> {
        let deadline = within.unwrap_or(f64::INFINITY);
        let by = |t: f64| t <= deadline + 1e-9;
        let when = match within {
            Some(w) => format!("within {} s", num(w)),
            None => "by the end of the run".to_string(),
        };
        let t_fail = deadline.min(self.end);
        match goal {
            Goal::Ends { command, how } => {
                let (started, ends) = self.life(command);
                if ends
                    .iter()
                    .any(|(t, h)| by(*t) && how.is_none_or(|w| w == *h))
                {
                    return Ok(());
                }
                let wanted = how.map_or(String::new(), |h| format!(" {}", h.name()));
                let seen = match (started, ends.first()) {
                    (None, None) => "it never ran".to_string(),
                    (_, Some((t, h))) => format!("it ended {} at t={}", h.name(), num(*t)),
                    (Some(s), None) => format!("it started at t={} and never ended", num(s)),
                };
                Err(Failure {
                    t: t_fail,
                    message: format!("{} did not end{wanted} {when}: {seen}", command.shown),
                })
            }
            Goal::Var(v) => {
                let mut last = None;
                for (t, value) in self.var_values(v) {
                    if !by(t) {
                        break;
                    }
                    if v.cmp.holds(value, v.value) {
                        return Ok(());
                    }
                    last = Some((t, value));
                }
                let seen = match last {
                    Some((t, value)) => format!("it was {} from t={}", num(value), num(t)),
                    None => format!("its {} never changed", v.field.name()),
                };
                Err(Failure {
                    t: t_fail,
                    message: format!("{} never {} {when}: {seen}", var_name(v), wanted(v)),
                })
            }
            Goal::Happens(h) => match self.happenings(h).next() {
                Some((t, _)) if by(t) => Ok(()),
                Some((t, seen)) => Err(Failure {
                    t: t_fail,
                    message: format!("it happened only at t={}: {seen}", num(t)),
                }),
                None => Err(Failure {
                    t: t_fail,
                    message: format!("it did not happen {when}"),
                }),
            },
            Goal::Near(n) => {
                let mut nearest: Option<(f64, f64)> = None;
                for (t, p) in self.poses() {
                    if !by(t) {
                        break;
                    }
                    let d = n.place.distance(p.x.0, p.y.0);
                    if d <= n.distance + 1e-9 {
                        return Ok(());
                    }
                    if nearest.is_none_or(|(_, best)| d < best) {
                        nearest = Some((t, d));
                    }
                }
                let seen = match nearest {
                    Some((t, d)) => format!("it came nearest at t={}, {} m away", num(t), num(d)),
                    None => "the trace has no pose".to_string(),
                };
                Err(Failure {
                    t: t_fail,
                    message: format!(
                        "the robot did not come within {} m of {} {when}: {seen}",
                        num(n.distance),
                        n.place.describe()
                    ),
                })
            }
        }
    }

    /// `(t, value)` of the variable's field at each `var` event that sets it.
    fn var_values<'a>(&'a self, v: &'a VarCheck) -> impl Iterator<Item = (f64, f64)> + 'a {
        self.records.iter().filter_map(move |r| match &r.event {
            Event::Var(var) if var.var.eq_ignore_ascii_case(&v.name) => {
                let field = match v.field {
                    Field::Value => var.value,
                    Field::Status => var.status,
                    Field::X => var.x,
                    Field::Y => var.y,
                    Field::H => var.h,
                    Field::Dist => var.dist,
                };
                field.map(|n| (r.t.0, n.0))
            }
            _ => None,
        })
    }

    /// The first sample at which the state holds (`want`) or does not (`!want`).
    fn first(&self, state: &State, want: bool) -> Option<(f64, String)> {
        match state {
            State::Speed(cmp, bound) => self
                .poses()
                .find(|(_, p)| cmp.holds(p.v.0.abs(), *bound) == want)
                .map(|(t, p)| (t, format!("speed {} m/s", num(p.v.0.abs())))),
            State::Clearance(cmp, bound) => self
                .clearances()
                .find(|(_, d)| cmp.holds(*d, *bound) == want)
                .map(|(t, d)| (t, format!("the nearest scanner hit {} m away", num(d)))),
            State::Inside { min, max } => self
                .poses()
                .find(|(_, p)| {
                    let (x, y) = (p.x.0, p.y.0);
                    (min.0 <= x && x <= max.0 && min.1 <= y && y <= max.1) == want
                })
                .map(|(t, p)| (t, format!("the robot at ({}, {})", num(p.x.0), num(p.y.0)))),
            State::Near(n) => self
                .poses()
                .find(|(_, p)| near(n, p) == want)
                .map(|(t, p)| {
                    let d = n.place.distance(p.x.0, p.y.0);
                    (
                        t,
                        format!(
                            "the robot at ({}, {}), {} m from {}",
                            num(p.x.0),
                            num(p.y.0),
                            num(d),
                            n.place.describe()
                        ),
                    )
                }),
        }
    }

    /// Whether the trace has the samples the state is read from.
    fn samples(&self, state: &State) -> Result<(), Failure> {
        let none = match state {
            State::Clearance(..) => self.clearances().next().is_none().then_some("scan"),
            _ => self.poses().next().is_none().then_some("pose"),
        };
        let (lo, hi) = self.window;
        let scope = if lo.is_finite() || hi.is_finite() {
            format!(
                " from t={} to t={}",
                num(lo.max(0.0)),
                num(hi.min(self.end))
            )
        } else {
            String::new()
        };
        match none {
            Some(what) => Err(Failure {
                t: lo.max(0.0),
                message: format!("the trace has no {what} line{scope} to check this on"),
            }),
            None => Ok(()),
        }
    }

    fn always(&self, state: &State) -> Result<(), Failure> {
        self.samples(state)?;
        match self.first(state, false) {
            None => Ok(()),
            Some((t, seen)) => Err(Failure {
                t,
                message: format!("at t={}: {seen}", num(t)),
            }),
        }
    }

    fn never_state(&self, state: &State) -> Result<(), Failure> {
        self.samples(state)?;
        match self.first(state, true) {
            None => Ok(()),
            Some((t, seen)) => Err(Failure {
                t,
                message: format!("at t={}: {seen}", num(t)),
            }),
        }
    }

    fn never_happens(&self, h: &Happening) -> Result<(), Failure> {
        match self.happenings(h).next() {
            Some((t, seen)) => Err(Failure {
                t,
                message: format!("at t={}: {seen}", num(t)),
            }),
            None => Ok(()),
        }
    }

    /// Each time the happening happened, and what it was.
    fn happenings<'a>(&'a self, h: &'a Happening) -> impl Iterator<Item = (f64, String)> + 'a {
        self.records.iter().filter_map(move |r| {
            let t = r.t.0;
            if !self.in_window(t) {
                return None;
            }
            let seen = match (&r.event, h) {
                (Event::End(e), Happening::Refused) if e.how == How::Refused => {
                    let why = e
                        .code
                        .as_ref()
                        .map(|c| {
                            format!(
                                " ({c}{})",
                                e.reason
                                    .as_ref()
                                    .map_or(String::new(), |r| format!(": {r}"))
                            )
                        })
                        .unwrap_or_default();
                    Some(format!("{} was refused{why}", statement(e.stmt.as_ref())))
                }
                (Event::End(e), Happening::Broken) if e.how == How::Broken => {
                    Some(format!("{} ended broken", statement(e.stmt.as_ref())))
                }
                (Event::Overrun(o), Happening::Overrun) => Some(format!(
                    "the block of {} overran the tick's budget with {} statement(s) pending",
                    statement(o.stmt.as_ref()),
                    o.pending
                )),
                (Event::Error(e), Happening::Error) => Some(format!(
                    "runtime error at {}: {}",
                    statement(e.stmt.as_ref()),
                    e.message
                )),
                (Event::Fault(f), Happening::Fault(name))
                    if name
                        .as_ref()
                        .is_none_or(|n| f.fault.eq_ignore_ascii_case(n)) =>
                {
                    Some(format!("fault {} {}: {}", f.code, f.fault, f.message))
                }
                _ => None,
            };
            seen.map(|s| (t, s))
        })
    }

    fn before(&self, a: &Command, b: &Command) -> Result<(), Failure> {
        let (_, a_ends) = self.life(a);
        let (b_start, _) = self.life(b);
        let fail = |t: f64, message: String| Err(Failure { t, message });
        match (a_ends.first(), b_start) {
            (Some((ta, _)), Some(tb)) if *ta <= tb + 1e-9 => Ok(()),
            (Some((ta, _)), Some(tb)) => fail(
                tb,
                format!(
                    "{} started at t={}, before {} ended at t={}",
                    b.shown,
                    num(tb),
                    a.shown,
                    num(*ta)
                ),
            ),
            (None, Some(tb)) => fail(
                tb,
                format!(
                    "{} started at t={}; {} never ended",
                    b.shown,
                    num(tb),
                    a.shown
                ),
            ),
            (_, None) => fail(self.end, format!("{} never ran", b.shown)),
        }
    }

    fn during(&self, a: &Command, b: &Command) -> Result<(), Failure> {
        let (a_start, a_ends) = self.life(a);
        let (b_start, b_ends) = self.life(b);
        let Some(sa) = a_start.or(a_ends.first().map(|e| e.0)) else {
            return Err(Failure {
                t: self.end,
                message: format!("{} never ran", a.shown),
            });
        };
        let Some(sb) = b_start.or(b_ends.first().map(|e| e.0)) else {
            return Err(Failure {
                t: self.end,
                message: format!("{} never ran", b.shown),
            });
        };
        let ea = a_ends.first().map_or(self.end, |e| e.0);
        let eb = b_ends.first().map_or(self.end, |e| e.0);
        let span = |s: f64, e: f64| format!("t={}..{}", num(s), num(e));
        if sa + 1e-9 >= sb && ea <= eb + 1e-9 {
            return Ok(());
        }
        Err(Failure {
            t: if sa < sb { sa } else { eb },
            message: format!(
                "{} ran {}, {} ran {}",
                a.shown,
                span(sa, ea),
                b.shown,
                span(sb, eb)
            ),
        })
    }

    fn at_end(&self, f: &Final) -> Result<(), Failure> {
        let t = self.end;
        let fail = |message: String| Err(Failure { t, message });
        let last = self.poses().last().map(|(_, p)| *p);
        match f {
            Final::Near(n) => match last {
                Some(p) if near(n, &p) => Ok(()),
                Some(p) => fail(format!(
                    "the robot ended at ({}, {}), {} m from {}",
                    num(p.x.0),
                    num(p.y.0),
                    num(n.place.distance(p.x.0, p.y.0)),
                    n.place.describe()
                )),
                None => fail("the trace has no pose".into()),
            },
            Final::Heading { within, of } => match last {
                Some(p) => {
                    let h = p.h.0.to_degrees();
                    let off = (h - of + 180.0).rem_euclid(360.0) - 180.0;
                    if off.abs() <= within + 1e-9 {
                        Ok(())
                    } else {
                        fail(format!(
                            "the robot ended heading {} deg, {} deg from {} deg",
                            num(h),
                            num(off.abs()),
                            num(*of)
                        ))
                    }
                }
                None => fail("the trace has no pose".into()),
            },
            Final::Count(how, cmp, n) => {
                let count = self
                    .records
                    .iter()
                    .filter(|r| matches!(&r.event, Event::End(e) if e.how == *how))
                    .count() as f64;
                if cmp.holds(count, *n) {
                    Ok(())
                } else {
                    fail(format!("{} command(s) ended {}", num(count), how.name()))
                }
            }
            Final::Var(v) => match self.var_values(v).last() {
                Some((_, value)) if v.cmp.holds(value, v.value) => Ok(()),
                Some((at, value)) => fail(format!(
                    "{} ended {} (set at t={})",
                    var_name(v),
                    num(value),
                    num(at)
                )),
                None => fail(format!("{} was never set", var_name(v))),
            },
        }
    }
}

fn near(n: &Near, p: &ilmr_trace::Pose) -> bool {
    n.place.distance(p.x.0, p.y.0) <= n.distance + 1e-9
}

fn var_name(v: &VarCheck) -> String {
    match v.field {
        Field::Value => format!("`{}`", v.name),
        f => format!("`{}.{}`", v.name, f.name()),
    }
}

fn wanted(v: &VarCheck) -> String {
    format!("became {} {}", v.cmp.symbol(), num(v.value))
}

fn statement(s: Option<&ilmr_trace::Stmt<'_>>) -> String {
    match s {
        Some(s) => format!("line {} `{}`", s.line, s.text),
        None => "an interactive line".to_string(),
    }
}
