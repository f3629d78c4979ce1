//! What the shell prints: answers to lines and checks, the status view, and notices
//! from the event stream. Pure functions of what the engine answered.

use ilmr_compiler::render::{self, RenderFile, Style};
use ilmr_stdlib::Field;
use ilmr_vm::runtime::safety::Code;
use ilmr_vm::runtime::trace::fmt_num;

use crate::live::engine::{LineAnswer, Outcome, Status, VarState};

fn diagnostics(d: &[ilmr_compiler::Diagnostic], text: &str, style: Style) -> String {
    let files = [RenderFile {
        path: "<line>",
        text,
    }];
    render::human(d, &files, style)
}

fn lines(text: &str) -> usize {
    text.lines().filter(|l| !l.trim().is_empty()).count()
}

/// The answer to text typed to join.
pub fn joined(answer: &LineAnswer, text: &str, style: Style) -> String {
    let t = fmt_num(answer.t);
    match &answer.outcome {
        Outcome::Accepted { warnings } => {
            let what = match lines(text) {
                1 => "joined".to_string(),
                n => format!("joined {n} lines"),
            };
            format!("{}{what} at t={t} s\n", diagnostics(warnings, text, style))
        }
        Outcome::Rejected { diagnostics: d } => {
            format!("{}not joined\n", diagnostics(d, text, style))
        }
        Outcome::Failed(why) => format!("error: {why}\n"),
    }
}

/// The answer to a `check` ... `checkend` block.
pub fn checked(answer: &LineAnswer, text: &str, style: Style) -> String {
    let n = lines(text);
    match &answer.outcome {
        Outcome::Accepted { warnings } => format!(
            "{}check: {n} line(s), no errors, {} warning(s); nothing joined\n",
            diagnostics(warnings, text, style),
            warnings.len()
        ),
        Outcome::Rejected { diagnostics: d } => format!(
            "{}check: {n} line(s), {} error(s); nothing joined\n",
            diagnostics(d, text, style),
            d.iter().filter(|d| d.is_error()).count()
        ),
        Outcome::Failed(why) => format!("error: {why}\n"),
    }
}

/// The status view: time, pose, what runs, and the variables, then an empty line.
pub fn status(s: &Status) -> String {
    let a = &s.activity;
    let mut out = format!(
        "t {} s\npose x {} m, y {} m, heading {} deg; speed {} m/s, curvature {} 1/m\n",
        fmt_num(s.t),
        fmt_num(s.pose.x),
        fmt_num(s.pose.y),
        fmt_num((s.pose.h.to_degrees() * 10.0).round() / 10.0),
        fmt_num(s.speed),
        fmt_num(s.curvature)
    );
    out.push_str(&format!(
        "activity: {} running, {} queued movement(s), {} waiting guard(s), {} waiting, {} \
         block(s) issuing{}\n",
        a.running_commands,
        a.queued_movements,
        a.waiting_guards,
        a.sleeping,
        a.issuing_blocks,
        if s.finished { "; nothing is live" } else { "" }
    ));
    // What the supervisor does to the robot comes before what the task asks of it.
    for f in &s.faults {
        out.push_str(&format!(
            "supervisor: {} ({} {}): {}\n",
            crate::notice::reaction_verb(f.reaction().name()),
            Code::Fault(*f).code(),
            f.name(),
            Code::Fault(*f).help()
        ));
    }
    if s.live.is_empty() {
        out.push_str("live: none\n");
    } else {
        out.push_str("live:\n");
        for c in &s.live {
            out.push_str(&format!("  {}:{}  {}\n", c.file, c.line, c.text));
        }
    }
    if s.vars.is_empty() {
        out.push_str("variables: none\n");
    } else {
        out.push_str("variables:\n");
        let width = s.vars.iter().map(|v| v.name.len()).max().unwrap_or(0);
        for v in &s.vars {
            out.push_str(&format!("  {:width$}  {}\n", v.name, fields(v)));
        }
    }
    // A paragraph of its own, apart from the notices and answers round it.
    out.push('\n');
    out
}

/// A variable's fields that its kind produces, and how its command ended.
fn fields(v: &VarState) -> String {
    let r = &v.record;
    let mut parts: Vec<String> = v
        .kind
        .fields()
        .iter()
        .map(|f| {
            let value = match f {
                Field::Status => r.status,
                Field::X => r.x,
                Field::Y => r.y,
                Field::H => r.h,
                Field::Value => r.value,
                Field::Dist => r.dist,
            };
            format!("{} {}", f.name(), fmt_num(value))
        })
        .collect();
    if let Some(how) = r.how {
        parts.push(format!("({})", how.name()));
    }
    parts.join(", ")
}

pub const HELP: &str = "\
Type ILMR lines: each is checked against the running task and, if it has no errors,
joins it as a new block at once (diagnostics are shown otherwise, and nothing changes).
An `if(..)` or `while(..)` line collects the lines up to its `endif`/`endwhile` first.
  check ... checkend   check the lines between and join nothing
  stop / cont          halt the robot and pause movement / resume it (ILMR commands)
  break / break(pat)   end every command / those whose text contains `pat`
Shell commands:
  :status   time, pose, speed, live commands and variables
  :watch    show commands starting and ending (again: stop showing)
  :help     this text
  :quit     leave (also `exit`, `quit`, Ctrl-D); Ctrl-C drops what is being typed
Tab completes commands, keywords, robot model names, variables and skills.
";

#[cfg(test)]
mod tests {
    use super::*;
    use ilmr_vm::runtime::safety::Fault;

    #[test]
    fn the_status_says_which_hold_keeps_the_robot_standing() {
        let s = Status {
            t: 12.0,
            ticks: 1200,
            pose: ilmr_hal::Pose {
                x: 11.2,
                y: 6.3,
                h: 0.26,
            },
            speed: 0.0,
            curvature: 0.0,
            activity: ilmr_vm::Activity::default(),
            finished: false,
            longest_tick_gap: 0.01,
            faults: vec![Fault::ObstacleNear],
            live: Vec::new(),
            vars: Vec::new(),
            skills: Vec::new(),
        };
        let view = status(&s);
        assert!(
            view.contains("\nsupervisor: held (R0206 obstacle_near): clear the way"),
            "{view}"
        );
    }
}
