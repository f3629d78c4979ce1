//! One line for an operator from a trace event: what happened, when, to which
//! statement, why, and the way out where there is one. `run` prints these on stderr
//! as they happen and `shell` above its prompt, so both say the same thing.

use ilmr_trace::{AvoidState, Event, How, Record, Stmt};
use ilmr_vm::runtime::trace::fmt_num;

/// How much of the notices an operator asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Detail {
    /// Refusals, faults and their clearing, overruns and runtime errors.
    Trouble,
    /// Also commands starting and ending, and obstacle avoidance (the shell's `:watch`).
    Watch,
}

/// Seconds of logical time within which notices of one kind (a statement's refusal,
/// a fault, overruns, errors) are said once: a loop refused every tick must not flood the
/// terminal. The ones held back are counted in the next notice of that kind.
pub const REPEAT_EVERY: f64 = 1.0;

/// Lets through at most one notice of a kind per [`REPEAT_EVERY`].
#[derive(Debug, Default)]
pub struct Gate {
    /// Per kind: when it was last said, and how many were held back since.
    said: Vec<(String, f64, u64)>,
}

impl Gate {
    /// The notice for `r` at `detail`, if it passes; only trouble is gated.
    pub fn pass(&mut self, r: &Record<'_>, detail: Detail) -> Option<String> {
        let text = for_event(r, detail)?;
        let trouble = detail == Detail::Trouble || for_event(r, Detail::Trouble).is_some();
        if !trouble {
            return Some(text);
        }
        self.admit(r, text)
    }

    /// `text`, trouble's notice for `r`, if it passes, with how many of its kind were
    /// held back before it.
    pub fn admit(&mut self, r: &Record<'_>, text: String) -> Option<String> {
        let t = r.t.0;
        let kind = kind_of(&r.event);
        match self.said.iter_mut().find(|(k, ..)| *k == kind) {
            None => {
                self.said.push((kind, t, 0));
                Some(text)
            }
            Some((_, last, held)) if t - *last < REPEAT_EVERY => {
                *held += 1;
                None
            }
            Some((_, last, held)) => {
                let more = std::mem::take(held);
                let since = fmt_num(*last);
                *last = t;
                Some(if more > 0 {
                    format!("{text} (and {more} more like it since t={since})")
                } else {
                    text
                })
            }
        }
    }
}

/// What makes two notices the same kind: the event, its code and its line.
fn kind_of(e: &Event<'_>) -> String {
    let line = |s: &Option<Stmt<'_>>| s.as_ref().map_or(0, |s| s.line);
    let (name, code, line) = match e {
        Event::End(e) => ("end", e.code.as_deref().unwrap_or(""), line(&e.stmt)),
        Event::Fault(f) => ("fault", f.code.as_ref(), line(&f.stmt)),
        Event::Recovered(r) => ("recovered", r.code.as_ref(), line(&r.stmt)),
        Event::Overrun(o) => ("overrun", "", line(&o.stmt)),
        Event::Error(e) => ("error", "", line(&e.stmt)),
        Event::Start(s) => ("start", "", line(&s.stmt)),
        Event::Avoid(a) => ("avoid", "", line(&a.stmt)),
        _ => ("other", "", 0),
    };
    format!("{name} {code} {line}")
}

/// The notice for a trace event line; `None` for events the detail leaves out.
#[cfg(test)]
fn for_line(event: &str, detail: Detail) -> Option<String> {
    let r: Record<'_> = serde_json::from_str(event).ok()?;
    for_event(&r, detail)
}

pub fn for_event(r: &Record<'_>, detail: Detail) -> Option<String> {
    let watch = detail == Detail::Watch;
    let t = fmt_num(r.t.0);
    let at = |s: &Option<Stmt<'_>>| {
        s.as_ref()
            .map(|s| format!(" `{}`", s.text))
            .unwrap_or_default()
    };
    let way_out = |help: Option<&str>| help.map(|h| format!("; way out: {h}")).unwrap_or_default();
    match &r.event {
        Event::End(e) if e.how == How::Refused => {
            let mut tags: Vec<String> = e
                .stmt
                .as_ref()
                .map(|s| format!("line {}", s.line))
                .into_iter()
                .collect();
            tags.extend(e.code.as_deref().map(str::to_string));
            let tags = if tags.is_empty() {
                String::new()
            } else {
                format!(" ({})", tags.join(", "))
            };
            let reason = e
                .reason
                .as_deref()
                .map(|r| format!(": {r}"))
                .unwrap_or_default();
            Some(format!(
                "[t={t}] refused{}{tags}{reason}{}",
                at(&e.stmt),
                way_out(e.help.as_deref())
            ))
        }
        Event::Fault(f) => Some(format!(
            "[t={t}] {} ({} {}): {}{}",
            reaction_verb(&f.reaction),
            f.code,
            f.fault,
            f.message,
            way_out(Some(&f.help))
        )),
        Event::Recovered(c) => Some(format!("[t={t}] cleared ({} {})", c.code, c.fault)),
        Event::Overrun(o) => Some(format!(
            "[t={t}] overrun: a block ran out of the tick's time budget with {} statement(s) left; it goes on next tick",
            o.pending
        )),
        Event::Error(e) => Some(format!("[t={t}] error{}: {}", at(&e.stmt), e.message)),
        Event::End(e) if watch => Some(format!(
            "[t={t}] ended{}: {}{}",
            at(&e.stmt),
            e.how.name(),
            if e.linked { " (linked)" } else { "" }
        )),
        Event::Start(s) if watch => Some(format!("[t={t}] started{}", at(&s.stmt))),
        Event::Avoid(a) if watch => Some(format!(
            "[t={t}] obstacle avoidance{}: {}",
            at(&a.stmt),
            match a.state {
                AvoidState::Normal => "normal",
                AvoidState::Avoiding => "avoiding",
                AvoidState::Returning => "returning",
                AvoidState::Blocked => "blocked",
            }
        )),
        _ => None,
    }
}

/// What the supervisor's reaction (its `name()`) does to the robot, as the operator
/// sees it.
pub fn reaction_verb(reaction: &str) -> &'static str {
    match reaction {
        "hold" => "held",
        "lockout" => "movement locked",
        "end_movement" => "movement ended",
        "give_up" => "gave up",
        "slow_down" => "slowed down",
        _ => "fault",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refusals_faults_and_errors_are_trouble_the_rest_is_watching() {
        let refused = r#"{"t":1.98,"event":"end","line":2,"text":"gotoxy(1,1)","how":"refused","code":"R0110","reason":"the path needs curvature 8.497 1/m but the robot turns at most 1.333 1/m","help":"give a heading the robot can reach (gotoxy(x,y,h))"}"#;
        assert_eq!(
            for_line(refused, Detail::Trouble).as_deref(),
            Some(
                "[t=1.98] refused `gotoxy(1,1)` (line 2, R0110): the path needs curvature 8.497 1/m but the robot turns at most 1.333 1/m; way out: give a heading the robot can reach (gotoxy(x,y,h))"
            )
        );
        let checked = r#"{"t":1.5,"event":"end","line":1,"text":"sensor(sonar)","how":"refused","reason":"no such sensor"}"#;
        assert_eq!(
            for_line(checked, Detail::Trouble).as_deref(),
            Some("[t=1.5] refused `sensor(sonar)` (line 1): no such sensor")
        );
        let held = r#"{"t":11.84,"event":"fault","fault":"obstacle_near","code":"R0206","reaction":"hold","message":"an obstacle 0.25 m ahead is inside the stopping distance 0.26 m","help":"clear the way"}"#;
        assert_eq!(
            for_line(held, Detail::Trouble).as_deref(),
            Some(
                "[t=11.84] held (R0206 obstacle_near): an obstacle 0.25 m ahead is inside the stopping distance 0.26 m; way out: clear the way"
            )
        );
        let cleared = r#"{"t":13,"event":"recovered","fault":"obstacle_near","code":"R0206"}"#;
        assert_eq!(
            for_line(cleared, Detail::Trouble).as_deref(),
            Some("[t=13] cleared (R0206 obstacle_near)")
        );
        let error = r#"{"t":2,"event":"error","message":"division by zero"}"#;
        assert_eq!(
            for_line(error, Detail::Trouble).as_deref(),
            Some("[t=2] error: division by zero")
        );
        let ended =
            r#"{"t":3,"event":"end","line":1,"text":"goahead(1)","how":"completed","linked":true}"#;
        assert_eq!(for_line(ended, Detail::Trouble), None);
        assert_eq!(
            for_line(ended, Detail::Watch).as_deref(),
            Some("[t=3] ended `goahead(1)`: completed (linked)")
        );
        let pose = r#"{"t":3,"event":"pose","x":1,"y":2,"h":0,"v":0,"c":0,"source":"true"}"#;
        assert_eq!(for_line(pose, Detail::Watch), None);
        assert_eq!(for_line("not json", Detail::Watch), None);
    }

    #[test]
    fn a_kind_repeated_within_a_second_is_held_back_and_counted() {
        let overrun = |t: f64| serde_json::json!({"t": t, "event": "overrun", "pending": 3});
        let refused_on = |t: f64, line: u32| serde_json::json!({"t": t, "event": "end", "line": line, "text": "gotoxy(9,9)", "how": "refused", "code": "R0105", "reason": "in a wall"});
        let refused = |t: f64| refused_on(t, 1);
        let mut gated = Gate::default();
        let mut gate = |v: &serde_json::Value, detail| {
            let line = v.to_string();
            let r: Record<'_> = serde_json::from_str(&line).expect("a trace record");
            gated.pass(&r, detail)
        };
        let said: Vec<Option<String>> = [0.0, 0.01, 0.5, 0.99]
            .iter()
            .map(|&t| gate(&overrun(t), Detail::Trouble))
            .collect();
        assert!(said[0].is_some() && said[1..].iter().all(Option::is_none));
        assert!(
            gate(&refused(0.5), Detail::Trouble).is_some(),
            "another kind is said"
        );
        let other = refused_on(0.5, 2);
        assert!(
            gate(&other, Detail::Trouble).is_some(),
            "so is another statement's"
        );
        assert!(gate(&refused(0.6), Detail::Trouble).is_none());
        let again = gate(&overrun(1.2), Detail::Trouble).unwrap();
        assert!(again.ends_with("(and 3 more like it since t=0)"), "{again}");
        let quiet = gate(&overrun(2.5), Detail::Trouble).unwrap();
        assert!(!quiet.contains("more like it"), "{quiet}");
        let ended = serde_json::json!({"t": 3, "event": "end", "line": 1, "text": "goahead(1)", "how": "completed"});
        for _ in 0..3 {
            assert!(
                gate(&ended, Detail::Watch).is_some(),
                "watching is not gated"
            );
        }
    }
}
