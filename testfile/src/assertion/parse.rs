//! One assertion from its text, by recursive descent; names (lines, commands,
//! variables, world objects) are resolved against the test's task and world as they are
//! read, so that a mistake is said where it was written, with a suggestion.

use std::cell::RefCell;
use std::ops::Range;

use ilmr_trace::How;

use super::lex::{Tok, Token, lex};
use super::*;
use crate::codes::Code;
use crate::problem::Problem;

/// What names in an assertion can refer to.
pub struct Context<'a> {
    /// The task's statements: line and text, in file order.
    pub statements: &'a [(u32, String)],
    /// Variables the task (or a test's interactive line) assigns.
    pub variables: &'a [String],
    /// The world's named places, when the robot is simulated.
    pub objects: Option<&'a [Place]>,
    /// Whether the trace has poses (a simulated or scripted robot).
    pub poses: bool,
    /// Whether it has scans (a simulated robot in a world).
    pub scans: bool,
}

/// What could come next where an assertion's text ends: what an editor completes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Want {
    /// A keyword (or a sign such as `:`), as the grammar spells it.
    Word(&'static str),
    /// The number of a line of the task that holds a statement (after `line`).
    Line,
    /// A statement's text in backticks.
    Text,
    /// A variable the task assigns.
    Variable,
    /// A field of a variable (after `.`).
    Field,
    /// A named thing of the world.
    Object,
    /// A comparison.
    Cmp,
}

/// The words an assertion starts with.
pub const STARTS: [&str; 6] = ["eventually", "always", "never", "before", "during", "at"];
/// What can follow `never:` besides a state.
pub const HAPPENINGS: [&str; 6] = ["refused", "broken", "overrun", "error", "fault", "contact"];
/// What `always:` and `never:` can say of the robot.
pub const STATES: [&str; 3] = ["speed", "clearance", "robot"];

/// Reads `text`, which is at `base` in the test file when its bytes are there as
/// written (`None`: the string had escapes, and problems point at `whole`).
pub fn parse(
    text: &str,
    base: Option<usize>,
    whole: Range<usize>,
    ctx: &Context<'_>,
) -> Result<Assertion, Problem> {
    let at = |r: Range<usize>| match base {
        Some(b) => b + r.start..b + r.end,
        None => whole.clone(),
    };
    let toks = lex(text).map_err(|(r, m)| Problem::new(Code::Syntax, at(r), m))?;
    let end = text.trim_end().len();
    let mut p = Parser {
        toks,
        pos: 0,
        end: at(end..end),
        at: &at,
        ctx,
        wants: RefCell::new(Vec::new()),
    };
    let kind = p.assertion()?;
    if let Some((tok, span)) = p.toks.get(p.pos) {
        return Err(Problem::new(
            Code::Syntax,
            at(span.clone()),
            format!("the assertion ends before {}", tok.describe()),
        ));
    }
    Ok(Assertion {
        span: at(0..end),
        text: text.trim().to_string(),
        kind,
    })
}

/// What the grammar allows after `text` (an assertion cut where an editor's cursor is,
/// less the word being typed), given what names mean in `ctx`. Empty when `text` is no
/// assertion's beginning.
pub fn wants(text: &str, ctx: &Context<'_>) -> Vec<Want> {
    let Ok(toks) = lex(text) else {
        return Vec::new();
    };
    let at = |r: Range<usize>| r;
    let mut p = Parser {
        toks,
        pos: 0,
        end: text.len()..text.len(),
        at: &at,
        ctx,
        wants: RefCell::new(Vec::new()),
    };
    let _ = p.assertion();
    let mut out = p.wants.into_inner();
    let mut seen = Vec::new();
    out.retain(|w| {
        let new = !seen.contains(w);
        seen.push(*w);
        new
    });
    out
}

/// What follows `line`, as messages name it.
const LINE_NUMBER: &str = "a line number";

struct Parser<'a, 'c> {
    /// What was looked for at the end of the text (completion).
    wants: RefCell<Vec<Want>>,
    toks: Vec<Token>,
    pos: usize,
    /// Where the end of the text is, for "expected ..., found the end".
    end: Range<usize>,
    at: &'a dyn Fn(Range<usize>) -> Range<usize>,
    ctx: &'a Context<'c>,
}

impl Parser<'_, '_> {
    /// Notes that `what` would be read here, when here is the end of the text.
    fn want(&self, what: impl IntoIterator<Item = Want>) {
        if self.pos >= self.toks.len() {
            self.wants.borrow_mut().extend(what);
        }
    }

    /// The happenings a trace records: `contact` is a word of the grammar only to be
    /// refused with a reason (A0206), so it is never offered.
    fn happenings(&self) {
        self.want(
            HAPPENINGS
                .iter()
                .filter(|h| **h != "contact")
                .map(|h| Want::Word(h)),
        );
    }

    fn words(&self, words: &[&'static str]) {
        self.want(words.iter().map(|w| Want::Word(w)));
    }

    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.pos).map(|(t, _)| t)
    }

    fn span(&self) -> Range<usize> {
        match self.toks.get(self.pos) {
            Some((_, s)) => (self.at)(s.clone()),
            None => self.end.clone(),
        }
    }

    /// The span from token `from` to the last one taken.
    fn since(&self, from: usize) -> Range<usize> {
        let first = self.toks.get(from).map(|(_, s)| s.start).unwrap_or(0);
        let last = self
            .toks
            .get(self.pos.saturating_sub(1))
            .map_or(first, |(_, s)| s.end);
        (self.at)(first..last.max(first))
    }

    fn found(&self) -> String {
        self.peek()
            .map_or("the end of the assertion".into(), |t| t.describe())
    }

    fn expected(&self, what: &str) -> Problem {
        Problem::new(
            Code::Syntax,
            self.span(),
            format!("expected {what}, found {}", self.found()),
        )
    }

    /// The next token is the keyword `word` (any case); takes it.
    fn eat(&mut self, word: &'static str) -> bool {
        self.words(&[word]);
        let yes = matches!(self.peek(), Some(Tok::Word(w)) if w.eq_ignore_ascii_case(word))
            || matches!(self.peek(), Some(Tok::Sign(s)) if *s == word);
        if yes {
            self.pos += 1;
        }
        yes
    }

    fn expect(&mut self, word: &'static str) -> Result<(), Problem> {
        if self.eat(word) {
            Ok(())
        } else {
            Err(self.expected(&format!("`{word}`")))
        }
    }

    /// The next word, lower-cased, without taking it.
    fn word(&self) -> Option<String> {
        match self.peek() {
            Some(Tok::Word(w)) => Some(w.to_ascii_lowercase()),
            _ => None,
        }
    }

    fn number(&mut self, what: &str) -> Result<f64, Problem> {
        if what == LINE_NUMBER {
            self.want([Want::Line]);
        }
        match self.peek() {
            Some(Tok::Number(n)) => {
                let n = *n;
                self.pos += 1;
                Ok(n)
            }
            _ => Err(self.expected(what)),
        }
    }

    /// A number of metres, seconds or degrees that must not be negative.
    fn amount(&mut self, what: &str) -> Result<f64, Problem> {
        let span = self.span();
        let n = self.number(what)?;
        if n < 0.0 {
            return Err(Problem::new(
                Code::Syntax,
                span,
                format!("{what} cannot be negative"),
            ));
        }
        Ok(n)
    }

    /// A word that is not one of `words`: the problem, with the nearest of them.
    fn unknown(&self, what: &str, words: &[&str]) -> Problem {
        let p = self.expected(what);
        match self.word() {
            Some(w) => p.suggest(&w, words.iter().copied()),
            None => p,
        }
    }

    fn assertion(&mut self) -> Result<Kind, Problem> {
        self.words(&STARTS);
        let Some(first) = self.word() else {
            return Err(
                self.expected("`eventually`, `always`, `never`, `before`, `during` or `at end`")
            );
        };
        match first.as_str() {
            "eventually" => {
                self.pos += 1;
                let within = if self.eat("within") {
                    let t = self.amount("a time in seconds")?;
                    self.eat("s");
                    Some(t)
                } else {
                    None
                };
                self.expect(":")?;
                Ok(Kind::Eventually {
                    within,
                    goal: self.goal()?,
                })
            }
            "always" => {
                self.pos += 1;
                let scope = self.scope()?;
                Ok(Kind::Always(scope, self.state()?))
            }
            "never" => {
                self.pos += 1;
                let scope = self.scope()?;
                Ok(Kind::Never(scope, self.never()?))
            }
            "before" | "during" => {
                self.pos += 1;
                self.expect("(")?;
                let a = self.command()?;
                self.expect(",")?;
                let b = self.command()?;
                self.expect(")")?;
                Ok(if first == "before" {
                    Kind::Before(a, b)
                } else {
                    Kind::During(a, b)
                })
            }
            "at" => {
                self.pos += 1;
                self.expect("end")?;
                self.expect(":")?;
                Ok(Kind::AtEnd(self.final_check()?))
            }
            _ => Err(self.unknown(
                "`eventually`, `always`, `never`, `before`, `during` or `at end`",
                &STARTS,
            )),
        }
    }

    /// `[from T [s]] [until T [s]] [while COMMAND] :`, in any order.
    fn scope(&mut self) -> Result<Scope, Problem> {
        let mut scope = Scope::default();
        loop {
            if self.eat("from") {
                scope.from = Some(self.amount("a time in seconds")?);
                self.eat("s");
            } else if self.eat("until") {
                scope.until = Some(self.amount("a time in seconds")?);
                self.eat("s");
            } else if self.eat("while") {
                scope.during = Some(self.command()?);
            } else if self.eat(":") {
                return Ok(scope);
            } else {
                return Err(self.unknown(
                    "`:`, or a scope: `from T s`, `until T s` or `while COMMAND`",
                    &["from", "until", "while"],
                ));
            }
        }
    }

    fn goal(&mut self) -> Result<Goal, Problem> {
        // Keywords first: a task's texts and variables may be many.
        self.words(&["line"]);
        if self.ctx.poses {
            self.words(&["robot"]);
        }
        self.happenings();
        self.want([Want::Variable, Want::Text]);
        match self.peek() {
            Some(Tok::Quoted(_)) => self.ends(),
            Some(Tok::Word(w)) if w.eq_ignore_ascii_case("line") => self.ends(),
            Some(Tok::Word(w)) if w.eq_ignore_ascii_case("robot") => Ok(Goal::Near(self.near()?)),
            Some(Tok::Word(w)) if HAPPENINGS.contains(&w.to_ascii_lowercase().as_str()) => {
                match self.never()? {
                    Never::Happening(h) => Ok(Goal::Happens(h)),
                    Never::State(_) => Err(self.expected("a happening")),
                }
            }
            Some(Tok::Word(_)) => Ok(Goal::Var(self.var_check()?)),
            _ => Err(self
                .expected("a command (`line N` or its text in backticks), a variable or `robot`")),
        }
    }

    fn ends(&mut self) -> Result<Goal, Problem> {
        let command = self.command()?;
        self.expect("ends")?;
        let how = match self.word().as_deref() {
            Some("completed") => Some(How::Completed),
            Some("broken") => Some(How::Broken),
            Some("refused") => Some(How::Refused),
            _ => None,
        };
        self.words(&["completed", "broken", "refused"]);
        if how.is_some() {
            self.pos += 1;
        } else if self.peek().is_some() {
            return Err(self.unknown(
                "`completed`, `broken`, `refused` or the end of the assertion",
                &["completed", "broken", "refused"],
            ));
        }
        Ok(Goal::Ends { command, how })
    }

    fn command(&mut self) -> Result<Command, Problem> {
        let from = self.pos;
        self.want([Want::Text]);
        let statements = self.ctx.statements;
        if let Some(Tok::Quoted(q)) = self.peek() {
            let q = q.clone();
            let span = self.span();
            self.pos += 1;
            let text = canonical(&q);
            let known = statements.iter().any(|(_, t)| same_statement(&text, t));
            if !known {
                let texts: Vec<&str> = statements.iter().map(|(_, t)| t.as_str()).collect();
                return Err(Problem::new(
                    Code::UnknownCommand,
                    span,
                    format!("the task has no statement `{q}`"),
                )
                .suggest(&q, texts));
            }
            return Ok(Command {
                span: self.since(from),
                line: None,
                text,
                shown: format!("`{}`", q.trim()),
            });
        }
        if !self.eat("line") {
            return Err(self.expected("a command: `line N` or its text in backticks"));
        }
        let span = self.span();
        let n = self.number(LINE_NUMBER)?;
        let statement = statements.iter().find(|(l, _)| f64::from(*l) == n);
        let Some((line, text)) = statement else {
            let mut p = Problem::new(
                Code::UnknownLine,
                span,
                format!("line {} of the task holds no statement", num(n)),
            );
            let nearest = statements.iter().min_by(|a, b| {
                (f64::from(a.0) - n)
                    .abs()
                    .total_cmp(&(f64::from(b.0) - n).abs())
            });
            if let Some((l, t)) = nearest {
                p = p.help(format!("the nearest statement is line {l}, `{t}`"));
            }
            return Err(p);
        };
        Ok(Command {
            span: self.since(from),
            line: Some(*line),
            text: canonical(text),
            shown: format!("line {line} `{text}`"),
        })
    }

    fn cmp(&mut self) -> Result<Cmp, Problem> {
        self.want([Want::Cmp]);
        if let Some(Tok::Sign(s)) = self.peek()
            && let Some((_, c)) = Cmp::ALL.iter().find(|(sym, _)| sym == s)
        {
            self.pos += 1;
            return Ok(*c);
        }
        Err(self.expected("a comparison (`==`, `!=`, `<`, `<=`, `>`, `>=`)"))
    }

    fn var_check(&mut self) -> Result<VarCheck, Problem> {
        self.want([Want::Variable]);
        let span = self.span();
        let Some(Tok::Word(name)) = self.peek().cloned() else {
            return Err(self.expected("a variable"));
        };
        self.pos += 1;
        let known = self
            .ctx
            .variables
            .iter()
            .find(|v| v.eq_ignore_ascii_case(&name));
        let Some(name) = known.cloned() else {
            let names: Vec<&str> = self.ctx.variables.iter().map(String::as_str).collect();
            return Err(Problem::new(
                Code::UnknownVariable,
                span,
                format!("the task assigns no variable `{name}`"),
            )
            .suggest(&name, names));
        };
        let field = if self.eat(".") {
            self.want([Want::Field]);
            let Some(f) = self.word() else {
                return Err(self.expected("a field of the variable"));
            };
            let names: Vec<&str> = Field::ALL.iter().map(|(n, _)| *n).collect();
            let Some((_, field)) = Field::ALL.iter().find(|(n, _)| *n == f) else {
                return Err(self.unknown(
                    "a field: `value`, `status`, `x`, `y`, `h` or `dist`",
                    &names,
                ));
            };
            self.pos += 1;
            *field
        } else {
            Field::Value
        };
        let cmp = self.cmp()?;
        let value = self.number("a number")?;
        Ok(VarCheck {
            name,
            field,
            cmp,
            value,
        })
    }

    /// `robot within D of PLACE`.
    fn near(&mut self) -> Result<Near, Problem> {
        self.robot_needed()?;
        self.expect("robot")?;
        self.expect("within")?;
        let distance = self.amount("a distance in metres")?;
        self.expect("of")?;
        Ok(Near {
            distance,
            place: self.place()?,
        })
    }

    /// The next words are about the robot's poses: the run must have a robot.
    fn robot_needed(&self) -> Result<(), Problem> {
        if self.ctx.poses {
            return Ok(());
        }
        Err(Problem::new(
            Code::NeedsRobot,
            self.span(),
            format!(
                "{} is known of a robot's poses; with `robot = \"none\"` the trace has none",
                self.found()
            ),
        ))
    }

    /// The next words are about scans: the run must have a simulated robot.
    fn scans_needed(&self) -> Result<(), Problem> {
        if self.ctx.scans {
            return Ok(());
        }
        Err(Problem::new(
            Code::NeedsRobot,
            self.span(),
            "the clearance is read from a simulated robot's scans; this test's robot has none",
        ))
    }

    fn place(&mut self) -> Result<Place, Problem> {
        if self.eat("(") {
            let x = self.number("x in metres")?;
            self.expect(",")?;
            let y = self.number("y in metres")?;
            self.expect(")")?;
            return Ok(Place::Point(x, y));
        }
        if self.ctx.objects.is_some() {
            self.want([Want::Object]);
        }
        let span = self.span();
        let Some(Tok::Word(name)) = self.peek().cloned() else {
            return Err(self.expected("a point `(x, y)` or the name of an object of the world"));
        };
        self.pos += 1;
        let Some(objects) = self.ctx.objects else {
            return Err(Problem::new(
                Code::NeedsRobot,
                span,
                format!(
                    "`{name}` would name a thing of the world; this test's robot has no world (give a point `(x, y)`)"
                ),
            ));
        };
        let names: Vec<&str> = objects
            .iter()
            .filter_map(|o| match o {
                Place::Object { name, .. } => Some(name.as_str()),
                Place::Point(..) => None,
            })
            .collect();
        let found = objects
            .iter()
            .find(|o| matches!(o, Place::Object { name: n, .. } if n.eq_ignore_ascii_case(&name)));
        match found {
            Some(o) => Ok(o.clone()),
            None => Err(Problem::new(
                Code::UnknownObject,
                span,
                format!("the world has no door, wall, box, target or charger `{name}`"),
            )
            .suggest(&name, names)),
        }
    }

    fn state(&mut self) -> Result<State, Problem> {
        if self.ctx.poses {
            self.words(&["speed", "robot"]);
        }
        if self.ctx.scans {
            self.words(&["clearance"]);
        }
        let Some(w) = self.word() else {
            return Err(self.expected("`speed`, `clearance` or `robot`"));
        };
        match w.as_str() {
            "speed" | "clearance" => {
                if w == "speed" {
                    self.robot_needed()?;
                } else {
                    self.scans_needed()?;
                }
                self.pos += 1;
                let cmp = self.cmp()?;
                let bound = self.number("a number")?;
                Ok(if w == "speed" {
                    State::Speed(cmp, bound)
                } else {
                    State::Clearance(cmp, bound)
                })
            }
            "robot" => {
                self.robot_needed()?;
                self.pos += 1;
                self.words(&["inside"]);
                self.pos -= 1;
                if matches!(self.toks.get(self.pos + 1), Some((Tok::Word(w), _)) if w.eq_ignore_ascii_case("inside"))
                {
                    self.pos += 2;
                    let (x0, y0) = self.point()?;
                    self.expect("..")?;
                    let (x1, y1) = self.point()?;
                    return Ok(State::Inside {
                        min: (x0.min(x1), y0.min(y1)),
                        max: (x0.max(x1), y0.max(y1)),
                    });
                }
                Ok(State::Near(self.near()?))
            }
            _ => Err(self.unknown("`speed`, `clearance` or `robot`", &STATES)),
        }
    }

    fn point(&mut self) -> Result<(f64, f64), Problem> {
        self.expect("(")?;
        let x = self.number("x in metres")?;
        self.expect(",")?;
        let y = self.number("y in metres")?;
        self.expect(")")?;
        Ok((x, y))
    }

    fn never(&mut self) -> Result<Never, Problem> {
        self.happenings();
        let w = self.word().unwrap_or_default();
        let happening = match w.as_str() {
            "refused" => Happening::Refused,
            "broken" => Happening::Broken,
            "overrun" => Happening::Overrun,
            "error" => Happening::Error,
            "fault" => {
                self.pos += 1;
                let name = match self.peek() {
                    Some(Tok::Word(f)) => Some(f.to_ascii_lowercase()),
                    _ => None,
                };
                if name.is_some() {
                    self.pos += 1;
                }
                return Ok(Never::Happening(Happening::Fault(name)));
            }
            "contact" => {
                return Err(Problem::new(
                    Code::NotTraced,
                    self.span(),
                    "contacts are not recorded in the trace, so a test cannot see them",
                )
                .help("the summary of `ilmrc run` counts them; `always: clearance > 0.1` bounds what the scanner saw"));
            }
            _ if STATES.contains(&w.as_str()) => return Ok(Never::State(self.state()?)),
            _ => {
                let words: Vec<&str> = HAPPENINGS.iter().chain(&STATES).copied().collect();
                return Err(self.unknown(
                    "`refused`, `broken`, `overrun`, `error`, `fault` or a state (`speed`, `clearance`, `robot`)",
                    &words,
                ));
            }
        };
        self.pos += 1;
        Ok(Never::Happening(happening))
    }

    fn final_check(&mut self) -> Result<Final, Problem> {
        if self.ctx.poses {
            self.words(&["robot", "heading"]);
        }
        self.words(&["completed", "broken", "refused"]);
        self.want([Want::Variable]);
        let Some(w) = self.word() else {
            return Err(
                self.expected("`robot`, `heading`, `completed`, `broken`, `refused` or a variable")
            );
        };
        match w.as_str() {
            "robot" => Ok(Final::Near(self.near()?)),
            "heading" => {
                self.robot_needed()?;
                self.pos += 1;
                self.expect("within")?;
                let within = self.amount("an angle in degrees")?;
                self.expect("of")?;
                let of = self.number("a heading in degrees")?;
                Ok(Final::Heading { within, of })
            }
            "completed" | "broken" | "refused" => {
                self.pos += 1;
                let how = match w.as_str() {
                    "completed" => How::Completed,
                    "broken" => How::Broken,
                    _ => How::Refused,
                };
                let cmp = self.cmp()?;
                let n = self.amount("a count")?;
                Ok(Final::Count(how, cmp, n))
            }
            _ => Ok(Final::Var(self.var_check()?)),
        }
    }
}
