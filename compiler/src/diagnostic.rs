//! Diagnostics are values: a stable code, a severity, a message, a primary span and
//! labelled secondary spans, and, where one exists, a fix an editor can apply.
//! `docs/diagnostics.md` is generated from [`Code::ALL`] and a test keeps it fresh.

use serde::Serialize;

use crate::span::Span;

/// Which file of a check a span points into (index into the check's file list).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct FileId(pub u32);

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Error,
    Warning,
}

macro_rules! codes {
    ($($variant:ident = $code:literal, $sev:ident, $title:literal, $doc:literal;)*) => {
        /// Stable diagnostic codes. Never renumber: tools match on them.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Code { $($variant,)* }

        impl Code {
            pub const ALL: &'static [Code] = &[$(Code::$variant,)*];

            pub fn as_str(self) -> &'static str {
                match self { $(Code::$variant => $code,)* }
            }

            pub fn severity(self) -> Severity {
                match self { $(Code::$variant => Severity::$sev,)* }
            }

            /// A few words naming the problem.
            pub fn title(self) -> &'static str {
                match self { $(Code::$variant => $title,)* }
            }

            /// What it means and how to fix it, for the reference docs.
            pub fn doc(self) -> &'static str {
                match self { $(Code::$variant => $doc,)* }
            }
        }
    };
}

codes! {
    UnreadableFile = "E0001", Error, "file cannot be read",
        "`ilmrc check` was given a file it could not read: missing, a directory, a device or FIFO, larger than the limit for a task or skill file (`MAX_SOURCE_BYTES`, docs/run.md), or refused by the system. The message says which. The other files are still checked; the exit code is 2.";
    NotUtf8 = "E0002", Error, "file is not UTF-8 text",
        "ILMR files are UTF-8 text. The diagnostic points at the line and column of the first byte that is not UTF-8 (a file saved as Latin-1 or UTF-16 by an editor, or a binary file); save the file as UTF-8. The other files are still checked; the exit code is 2.";
    TooManyErrors = "E0003", Error, "too many diagnostics, errors among those not shown",
        "A program gets at most `MAX_DIAGNOSTICS` (1,000) diagnostics, the first ones in source order; this one, after the last shown, counts the rest. Some of those not shown are errors, so the program is refused as if they were shown. Fix the first ones and check again. The limit keeps a hostile file (millions of broken lines) from exhausting memory (docs/reliability.md).";
    TooManyWarnings = "W0003", Warning, "too many diagnostics, only warnings not shown",
        "A program gets at most `MAX_DIAGNOSTICS` (1,000) diagnostics, the first ones in source order; this one, after the last shown, counts the rest, which are all warnings. The program is not refused for them.";
    Syntax = "E0101", Error, "syntax error",
        "The line does not follow ILMR's grammar. The rest of the file is still checked: each broken line gives one diagnostic.";
    UnclosedArgs = "E0102", Error, "unclosed argument list",
        "A command's argument list has no closing `)` before the end of the line.";
    UnclosedPattern = "E0103", Error, "unclosed break pattern",
        "`break(` has no closing `)` before the end of the line. The pattern is taken up to the end of the line.";
    TooComplex = "E0104", Error, "expression too complex",
        "A line holds more operators and opening parentheses than the limit (256): every tool that reads the expression would nest that deep. Split it into several assignments.";
    UnusualCharacter = "E0105", Error, "unusual character",
        "A character ILMR does not read, often one that looks like another: a non-breaking space (U+00A0) or a zero-width space copied from a web page or a word processor, a typographic dash or quote, `≥` for `>=`. The message names it by its code point; where it stands for a space or an ASCII sign, the fix writes that instead, and the rest of the line is read as if it had been.";
    UnitAfterNumber = "E0106", Error, "unit written after a number",
        "Values are plain numbers in the unit of the command's argument (metres, m/s, degrees, seconds; see the units in the command reference). The fix writes the number converted into that unit: `speed(30 km/h)` becomes `speed(8.333)`.";
    CombinedCondition = "E0107", Error, "more than one comparison in a condition",
        "A condition of `if` or `while` is one comparison (or one variable): there is no `and` or `or`. Nest the blocks for `and` (`if(x<2)` then `if(x>0)` on the next line, each with its `endif`); for `or`, repeat the block under each condition.";
    UnclosedIf = "E0201", Error, "`if` without `endif`",
        "Every `if(...)` needs an `endif` on a line of its own at the same level.";
    UnclosedWhile = "E0202", Error, "`while` without `endwhile`",
        "Every `while(...)` needs an `endwhile` on a line of its own at the same level.";
    UnclosedCheck = "E0203", Error, "`check` without `checkend`",
        "A `check` block, which is only validated, must be closed by `checkend`.";
    StrayEndIf = "E0204", Error, "`endif` without `if`",
        "An `endif` that closes no open `if`.";
    StrayEndWhile = "E0205", Error, "`endwhile` without `while`",
        "An `endwhile` that closes no open `while`.";
    StrayCheckend = "E0206", Error, "`checkend` without `check`",
        "A `checkend` that closes no open `check`.";
    MisplacedPriority = "E0207", Error, "`priority = highest` not first in its block",
        "Section 4.3: a block that must run alone starts with `priority = highest`. Anywhere else it would have no defined meaning. Put it first, after an empty line.";
    OutsideSkill = "E0208", Error, "statement outside any skill",
        "In a skill file every statement belongs to the skill whose `NAME:` header precedes it; these lines come before the first header.";
    NestedSkillHeader = "E0209", Error, "skill header inside a block",
        "A `NAME:` header starts a new skill and cannot stand inside an `if`, `while` or `check` block, or in a task file.";
    TooDeep = "E0210", Error, "blocks nested too deeply",
        "More blocks (`if`, `while`, `check`) are open inside one another than the limit (256). The lines inside the block that passes the limit are not checked. Move the inner part into a skill, or flatten the conditions.";
    UnknownCommand = "E0301", Error, "unknown command or skill",
        "The name is neither one of the 33 elementary commands nor a skill of the program (its own skill files, `--skills` and the built-in skills).";
    ArgumentCount = "E0302", Error, "wrong number of arguments",
        "The command takes a different number of arguments; the message shows its grammar.";
    ArgumentKind = "E0303", Error, "wrong kind of argument",
        "The argument is not what the command's grammar allows at that place, for example a number where a keyword is expected.";
    UnknownKeyword = "E0304", Error, "unknown keyword",
        "The word is not one of the keywords the command accepts at that place, and no variable or model name of that spelling exists.";
    BadSetting = "E0305", Error, "unknown, repeated or missing setting",
        "Named settings such as `d=` and `c=` of `turn`, or `r=`, `p=`, `rc=` of `bodypose`, must be the command's own, each given once, and the required ones present.";
    UnknownDevice = "E0401", Error, "unknown sensor or actuator",
        "The name or number is not in the `[SENSORSANDACTUATORS]` section of the robot model.";
    UnknownObject = "E0402", Error, "unknown object",
        "The name is not in the `[OBJECTS]` section of the robot model.";
    UnsupportedMode = "E0403", Error, "mode not available on this robot",
        "Movement and navigation modes must be defined in the `[IDENTIFIERS]` of the robot model: MoRo, for one, has no movement modes.";
    OutOfRange = "E0404", Error, "value outside the robot's range",
        "Requirement 9: a command that could harm the robot is rejected before it runs. The value exceeds a limit of the robot model (a speed beyond `max_speed`, a body pose beyond `max_roll`, an actuator value outside its range).";
    BeyondCapability = "W0405", Warning, "value beyond what the robot can do",
        "The robot can run the command but not as written: a curvature beyond its `max_curvature` is clipped by the position controller, so the path will be wider than asked.";
    SuspectUnit = "W0409", Warning, "number that looks like another unit",
        "A literal number is implausible in the argument's unit but plausible in another: `turn(d=1.57,c=1)` turns 1.57 degrees, which looks like radians (pi/2, 90 degrees), and `goahead(120)` drives 120 m, which looks like centimetres. The thresholds are in the units section of the command reference. The fix writes the converted value. Only a number written out is looked at: if the value is meant, write it as arithmetic (`d=3/2`).";
    ReadingIndex = "E0406", Error, "sensor reading index out of range",
        "A sensor's readings are numbered from 0 to one less than the count in the robot model.";
    Unsupported = "E0407", Error, "command not available on this robot",
        "The robot model lacks what the command needs (for example `bodypose` needs the body-pose limits `max_roll`, `max_pitch`, `max_clearance`).";
    UnknownService = "E0408", Error, "unknown sensor or service",
        "`init` takes sensors and services named in the robot model's `[SENSORSANDACTUATORS]` or `[IDENTIFIERS]`.";
    UnboundVariable = "E0501", Error, "variable used before anything binds it",
        "No statement before this one (in the task, its blocks or the skills that run before it) gives the variable a value.";
    WrongVariableKind = "E0502", Error, "variable of the wrong kind",
        "Each command knows which fields of a variable it uses (Table 8): `gotoxy(v)` needs a position, but a number or a plain status has none.";
    ReservedName = "E0503", Error, "name cannot be a variable",
        "Command names, reserved words and names of the robot model cannot be bound as variables.";
    RecursiveSkill = "E0601", Error, "recursive skill",
        "A skill calls itself, directly or through other skills. Skills are expanded as call frames; recursion would never end.";
    DuplicateSkill = "E0602", Error, "skill defined twice",
        "Two skills have the same name (names ignore case).";
    SkillsTooDeep = "E0603", Error, "skill calls nested too deeply",
        "A chain of skills calling skills is deeper than the VM runs (64 calls inside one another); the VM would refuse the innermost call. Call the inner skills from the task instead.";
    PatternMatchesNothing = "W0701", Warning, "break pattern matches no statement",
        "`break(pattern)` ends the live commands whose text contains the pattern. No statement of the program contains it, so the break can end nothing.";
    PatternMatchesSeveral = "W0702", Warning, "break pattern matches several statements",
        "The pattern is found in more than one statement; the break will end all of them that are live. Make it longer if one was meant.";
    RobotModel = "W0801", Warning, "robot model problem",
        "The robot model file is missing or has lines that could not be read; defaults are used in their place.";
    FrozenLoop = "W0901", Warning, "loop that cannot end by itself",
        "A `while` whose condition reads only variables that nothing can change while the loop runs: no statement in its body changes them, no command is bound to them, and no assignment can run at the same time (after the loop in its block, in a guard, in another block or a skill). Only the assignments made before the loop, one after another, set them, so the condition never turns false and the loop runs until a `break` ends it or a typed line changes the variable. Figure 27's `claps=0` / `while(claps<2)` / `clap_hands` / `endwhile` is one: count in the body (`claps = claps + 1`).";
    StarvingLoop = "W0902", Warning, "loop that never gives the tick back",
        "A `while` whose body holds only statements that end the instant they are issued (assignments and the commands the command reference marks \"ends when issued\": settings, `record`, `actuator`, `stop` ...) and that change nothing its condition reads. The VM looks at the condition again as soon as a pass has ended, so while the condition holds each pass starts the next at once, in the same tick, until the tick's budget (200,000 operations, `Config::budget_ops`, every 10 ms tick) is spent; the VM suspends the loop and resumes it next tick, where the same happens. The robot's control still runs, but the blocks queued behind the loop wait for the next tick, and the trace shows an `overrun` every tick. The message gives the operations a pass costs at least and the passes a tick that makes. Give the tick back in the body (`wait(0.1)`), or wait for the condition with a guard `if(...)` or `wait(v)`.";
    PathNeverRecorded = "W0903", Warning, "path followed but never recorded",
        "`followpath(P)` drives a path the robot holds by name: recorded with `record(P)` (up to `record(close)`), made with `createpath(P, x1, y1, ...)`, or taught beforehand in a scenario's `paths` (`ilmrc run --scenario`, which tells the check). No statement of the program that can run records or creates `P` (one inside `check` ... `checkend` never runs), and nothing gave it, so the movement is refused when it starts. Record it before the `followpath` in its block, or give it in the scenario. A `record(P)` anywhere in the program silences the warning, even one that may come too late.";
    WaitNeverWakes = "W0904", Warning, "wait that never wakes",
        "`wait(v)` holds its block until `v`'s status is 1, which the command bound to `v` sets when it ends. Every statement that sets `v` is one that never ends by itself (`followwall`, `goahead()` without a distance, a `while` whose condition is a constant other than 0: the command reference says which), and the program holds nothing that could end it: no bare `break`, no `break(pattern)` whose pattern is found in it or in the `if` or `while` round it, no `priority` block. Only a refusal, or a line typed while the task runs, would wake the wait. End the command with a `break` in a guard (`if(w > 5)` / `break(followwall)` / `endif`), or wait for something that ends.";
    SettingRace = "W0905", Warning, "two blocks set one actuator in the same tick",
        "`speed` (without `w`), `bodypose` and `actuator` for each device act the instant they are issued, outside the movement queue, and the robot keeps the last value set (the command reference marks them). Two statements of one block are issued in the order written. But these two stand in blocks that run at the same time and are issued in the same tick: both leading statements of top-level blocks (or of the blocks of one skill, or of one `if` or `while` body), or both after a `wait` on the same variable or for the same time from the same moment (a call of a skill whose first block waits counts as its waits), or both in the bodies of guards of one condition issued at one moment, or one in a skill called there. The robot keeps whichever the VM issues last, which the order it runs the blocks in decides, and nothing at run time says that the other was overridden. Statements held by different waits, in a guard's or loop's body against those outside it (or in guards of different conditions), or of one block are not compared; nor are two that set the same value. Set it in one block in the order meant, or hold one of them with `wait(v)`. The rule is in docs/language.md, \"Actuators outside the movement queue\".";
    UnusedVariable = "W0502", Warning, "variable never used",
        "A variable is bound but nothing reads it. Its command still runs.";
}

/// A text edit that resolves a diagnostic (did-you-mean, a missing `endif`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fix {
    pub title: String,
    pub span: Span,
    pub replacement: String,
}

/// Secondary places [`Diagnostic::with_places`] shows.
pub const MAX_PLACES_SHOWN: usize = 5;

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Label {
    pub file: FileId,
    pub span: Span,
    pub message: String,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub code: Code,
    pub message: String,
    pub file: FileId,
    pub span: Span,
    /// What the primary span shows; the message is used when empty.
    pub label: String,
    pub secondary: Vec<Label>,
    pub help: Option<String>,
    pub fix: Option<Fix>,
}

impl Diagnostic {
    pub fn new(code: Code, file: FileId, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            code,
            message: message.into(),
            file,
            span,
            label: String::new(),
            secondary: Vec::new(),
            help: None,
            fix: None,
        }
    }

    pub fn severity(&self) -> Severity {
        self.code.severity()
    }

    pub fn is_error(&self) -> bool {
        self.severity() == Severity::Error
    }

    pub fn with_label(mut self, label: impl Into<String>) -> Diagnostic {
        self.label = label.into();
        self
    }

    pub fn with_secondary(mut self, file: FileId, span: Span, message: impl Into<String>) -> Self {
        self.secondary.push(Label {
            file,
            span,
            message: message.into(),
        });
        self
    }

    /// A secondary label at each of `places`, the first [`MAX_PLACES_SHOWN`] of them, the
    /// last saying how many more there are. A warning about a statement that shares its
    /// cause with thousands of others would otherwise list them all, once for each it
    /// warns at: output that grows as the square of the file. `places` may go on past
    /// what is shown; `total` is how many it holds.
    pub fn with_places(
        mut self,
        places: impl IntoIterator<Item = (FileId, Span)>,
        total: usize,
        label: &str,
    ) -> Diagnostic {
        let more = total.saturating_sub(MAX_PLACES_SHOWN);
        for (file, span) in places.into_iter().take(MAX_PLACES_SHOWN) {
            self = self.with_secondary(file, span, label);
        }
        if more > 0
            && let Some(last) = self.secondary.last_mut()
        {
            last.message = format!("{label} (and {more} more like it)");
        }
        self
    }

    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }

    pub fn with_fix(
        mut self,
        title: impl Into<String>,
        span: Span,
        replacement: impl Into<String>,
    ) -> Self {
        self.fix = Some(Fix {
            title: title.into(),
            span,
            replacement: replacement.into(),
        });
        self
    }
}

impl Serialize for Code {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

/// Renders the code table of `docs/diagnostics.md`.
pub fn reference_markdown() -> String {
    let mut out = String::from(
        "# Diagnostic codes\n\n\
         Generated from `compiler/src/diagnostic.rs` by `cargo test -p ilmr-compiler` \
         (`UPDATE_DOCS=1` rewrites it). Codes are stable: tools may match on them.\n\n\
         | code | severity | title |\n| --- | --- | --- |\n",
    );
    let mut codes = Code::ALL.to_vec();
    codes.sort_by_key(|c| c.as_str());
    for c in &codes {
        let sev = match c.severity() {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        out.push_str(&format!(
            "| [{0}](#{1}) | {sev} | {2} |\n",
            c.as_str(),
            c.as_str().to_lowercase(),
            c.title()
        ));
    }
    for c in &codes {
        out.push_str(&format!(
            "\n## {}\n\n**{}**\n\n{}\n",
            c.as_str(),
            c.title(),
            c.doc()
        ));
    }
    out
}
