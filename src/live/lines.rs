//! The thread that compiles incoming ILMR text, so that the tick never waits for it: it
//! checks and lowers each line into its own copy of the running module (lent to the
//! lowering, as `Vm::add_line` lends the VM's, so a line costs its own size, not the
//! program's) and hands the engine the [`Fragment`] it added, which costs the engine
//! the line's size to join. The copy follows the module: a line stays in it once the
//! engine joined it and is taken out otherwise, and fragments the engine joined itself
//! (the emergency stop) are appended to it.

use std::sync::mpsc::{Receiver, Sender};

use ilmr_compiler::check::Source;
use ilmr_compiler::lower::{LineOptions, lower_line_with};
use ilmr_model::RobotModel;
use ilmr_vm::bytecode::Fragment;
use ilmr_vm::{Module, ModuleBuilder};

use super::engine::{Job, LineAnswer, Outcome};
use super::guard::guarded;
use super::reply::Reply;

/// How much the line compiler's thread gives way (its `nice`, 0 to 19): under a flood
/// of lines on a busy machine the scheduler runs the VM's thread, and the network's,
/// before it, so that the tick and the emergency stop keep their time.
const COMPILER_NICENESS: i32 = 10;

/// Times a line is lowered again when the module changed under it (an emergency stop
/// joined meanwhile); more means the copy lost step, and the line is refused.
const ATTEMPTS: usize = 3;

/// Text for this thread, forwarded by the engine in the order the front ends sent it.
pub enum Work {
    Line {
        text: String,
        reply: Reply<LineAnswer>,
    },
    Check {
        text: String,
        reply: Reply<LineAnswer>,
    },
}

/// What this thread made of a text, for the engine to join (or not), answer and
/// publish. Only `live` builds one.
pub struct Lowered {
    pub(super) text: String,
    pub(super) outcome: Outcome,
    /// What to join: an accepted line's.
    pub(super) fragment: Option<Fragment>,
    /// Whether subscribers see a `line` event (not for a check).
    pub(super) publish: bool,
    pub(super) reply: Reply<LineAnswer>,
    /// Where the engine says what became of `fragment`.
    pub(super) verdict: Option<Sender<Verdict>>,
}

pub(super) enum Verdict {
    Joined,
    /// The module changed since the copy this was lowered against: lower again.
    Stale(Reply<LineAnswer>),
    /// Answered as failed; nothing joined.
    Refused,
}

pub(super) struct Compiler {
    copy: Module,
    /// The task's statements before any line, and how many lines may add.
    task_statements: u32,
    max_line_statements: u32,
    /// Bytes of text joined so far, and how many may be.
    joined_bytes: u64,
    max_joined_bytes: u64,
    model: RobotModel,
    engine: Sender<Job>,
    /// Fragments the engine joined on its own.
    news: Receiver<Fragment>,
    /// The skill files the task was started with (`--skills DIR`), which lines may
    /// call although the task did not.
    library: Vec<Source>,
}

impl Compiler {
    pub(super) fn new(
        copy: Module,
        model: RobotModel,
        engine: Sender<Job>,
        news: Receiver<Fragment>,
    ) -> Compiler {
        Compiler {
            task_statements: copy.counts().stmts,
            max_line_statements: u32::MAX,
            joined_bytes: 0,
            max_joined_bytes: u64::MAX,
            copy,
            model,
            engine,
            news,
            library: Vec::new(),
        }
    }

    /// Lines may call the skills of `library` (and the built-in ones) that the running
    /// task never called, parameterized ones with arguments of their own.
    pub(super) fn with_library(mut self, library: Vec<Source>) -> Compiler {
        self.library = library;
        self
    }

    /// Refuses lines once they would have added more than `statements` statements or
    /// joined more than `bytes` bytes of text.
    pub(super) fn limited_to(mut self, statements: u32, bytes: u64) -> Compiler {
        self.max_line_statements = statements;
        self.max_joined_bytes = bytes;
        self
    }

    /// Runs until the engine stops forwarding work.
    pub(super) fn run(mut self, work: Receiver<Work>) {
        give_way();
        for item in work {
            let alive = match item {
                Work::Line { text, reply } => self.line(text, reply),
                Work::Check { text, reply } => {
                    self.catch_up();
                    let (outcome, _) = self.lower(&text, false);
                    self.hand_over(text, outcome, None, false, reply, None)
                }
            };
            if !alive {
                return;
            }
        }
    }

    /// Lowers `text` and has the engine join it; `false` once the engine is gone.
    fn line(&mut self, text: String, mut reply: Reply<LineAnswer>) -> bool {
        if self.joined_bytes + text.len() as u64 > self.max_joined_bytes {
            let why = format!(
                "the running task has taken {} bytes of text from lines, its limit; nothing \
                 more can join (restart the server to go on)",
                self.max_joined_bytes
            );
            return self.hand_over(text, Outcome::Failed(why), None, true, reply, None);
        }
        for _ in 0..ATTEMPTS {
            self.catch_up();
            let (outcome, fragment) = self.lower(&text, true);
            let Some(fragment) = fragment else {
                return self.hand_over(text, outcome, None, true, reply, None);
            };
            let base = fragment.base;
            let added = self.copy.counts().stmts - self.task_statements;
            if added > self.max_line_statements {
                self.copy.truncate(&base);
                let why = format!(
                    "the running task has taken {} statements from lines, its limit; \
                     nothing more can join (restart the server to go on)",
                    self.max_line_statements
                );
                return self.hand_over(text, Outcome::Failed(why), None, true, reply, None);
            }
            let (verdict, heard) = std::sync::mpsc::channel();
            if !self.hand_over(
                text.clone(),
                outcome,
                Some(fragment),
                true,
                reply,
                Some(verdict),
            ) {
                return false;
            }
            match heard.recv() {
                Ok(Verdict::Joined) => {
                    self.joined_bytes += text.len() as u64;
                    return true;
                }
                Ok(Verdict::Refused) => {
                    self.copy.truncate(&base);
                    return true;
                }
                Ok(Verdict::Stale(back)) => {
                    self.copy.truncate(&base);
                    reply = back;
                }
                Err(_) => return false,
            }
        }
        let why = "the running task kept changing while the line was compiled; send it again";
        self.hand_over(text, Outcome::Failed(why.into()), None, true, reply, None)
    }

    fn hand_over(
        &self,
        text: String,
        outcome: Outcome,
        fragment: Option<Fragment>,
        publish: bool,
        reply: Reply<LineAnswer>,
        verdict: Option<Sender<Verdict>>,
    ) -> bool {
        let lowered = Lowered {
            text,
            outcome,
            fragment,
            publish,
            reply,
            verdict,
        };
        self.engine.send(Job::Lowered(Box::new(lowered))).is_ok()
    }

    /// The outcome of `text` against the copy, and what it adds when accepted. An
    /// accepted line stays in the copy when `keep` (until the engine's verdict); all
    /// else is taken out again.
    fn lower(&mut self, text: &str, keep: bool) -> (Outcome, Option<Fragment>) {
        let base = self.copy.counts();
        let lent = std::mem::replace(&mut self.copy, ModuleBuilder::new().into_extended().0);
        let mut b = ModuleBuilder::lent(lent);
        let mut warnings = Vec::new();
        let options = LineOptions { robotless: false };
        let model = &self.model;
        let library = &self.library[..];
        let doing = if keep {
            "compiling the line"
        } else {
            "checking the line"
        };
        let lowered = guarded(doing, || {
            lower_line_with(text, &mut b, model, options, Some(library), &mut warnings)
        });
        let (module, counts) = b.into_extended();
        self.copy = module;
        if counts != Some(base) {
            // `lower_line_warned` keeps the builder it is lent; were it to replace it,
            // the copy would be lost and every later line would come back stale.
            eprintln!("error: the line compiler lost its copy of the running task");
        }
        let outcome = match lowered {
            Ok(Ok(start)) => {
                let mut fragment = added_since(&self.copy, base);
                fragment.start = start;
                if keep {
                    return (Outcome::Accepted { warnings }, Some(fragment));
                }
                Outcome::Accepted { warnings }
            }
            Ok(Err(diagnostics)) => Outcome::Rejected { diagnostics },
            Err(why) => Outcome::Failed(why),
        };
        self.copy.truncate(&base);
        (outcome, None)
    }

    fn catch_up(&mut self) {
        while let Ok(fragment) = self.news.try_recv() {
            self.follow(&fragment);
        }
    }

    fn follow(&mut self, fragment: &Fragment) {
        // Appending validates what the fragment adds, which the engine did already; it
        // costs the fragment's size, as the engine's join did.
        if let Err(e) = self.copy.append(fragment) {
            // The engine joined it, so this cannot be; if it is, lines come back stale
            // and are refused rather than joined against a wrong copy.
            eprintln!("error: the line compiler lost step with the running task: {e}");
        }
    }
}

/// Lowers this thread's priority to `COMPILER_NICENESS`; where that cannot be done the
/// thread runs as it is, only less politely.
#[cfg(target_os = "linux")]
fn give_way() {
    // SAFETY: two system calls about this thread only; nothing is read or written
    // through a pointer.
    let rc = unsafe {
        let tid = libc::gettid();
        libc::setpriority(libc::PRIO_PROCESS, tid as libc::id_t, COMPILER_NICENESS)
    };
    if rc != 0 {
        eprintln!("warning: the line compiler could not lower its priority");
    }
}

#[cfg(not(target_os = "linux"))]
fn give_way() {}

/// What `module` gained since it had `base`, as the fragment that would add it.
pub(super) fn added_since(module: &Module, base: ilmr_vm::bytecode::Counts) -> Fragment {
    fn tail<T: Clone>(v: &[T], from: u32) -> Vec<T> {
        v.get(from as usize..).unwrap_or_default().to_vec()
    }
    let added = Module {
        header: Default::default(),
        files: tail(&module.files, base.files),
        stmts: tail(&module.stmts, base.stmts),
        consts: tail(&module.consts, base.consts),
        names: tail(&module.names, base.names),
        globals: tail(&module.globals, base.globals),
        units: tail(&module.units, base.units),
        main: module.main,
        blocks: tail(&module.blocks, base.blocks),
        code: tail(&module.code, base.code),
        args: tail(&module.args, base.args),
        exprs: tail(&module.exprs, base.exprs),
        expr_code: tail(&module.expr_code, base.expr_code),
    };
    Fragment {
        base,
        added,
        start: Vec::new(),
    }
}
