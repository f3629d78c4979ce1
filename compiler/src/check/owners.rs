//! Actuators set by two blocks in one tick (W0905). `speed`, `bodypose` and
//! `actuator` (per device) act the instant they are issued and outside the movement
//! queue (the catalogue's `Sets`), and the robot keeps the last value set.
//! Two statements of one block are issued in the order written; but when two blocks
//! that run at the same time set the same thing in the same tick, the robot keeps
//! whichever the VM happens to issue last, and nothing at run time says so.
//!
//! When a statement is issued is read from the text as a chain of what its block
//! waited for since its unit started: a task's top-level blocks (and a skill's blocks,
//! and the blocks of one `if` or `while` body) start together; a block goes on in the
//! same tick until a `wait`, an `init`, or a call of a skill whose first block holds
//! (the call holds the caller until that block has issued its last statement).
//! `wait(v)` is woken in one tick for every block that waits on `v`; `wait(2)` from
//! one tick ends in one tick; a holding skill call lets its caller go when its first
//! block has gone through its waits, which are followed into the skill; the bodies of
//! guards of one condition issued at one moment start in one tick; anything else (an
//! `init`, a loop's body) is a moment of its own. Two statements with the same chain are
//! issued in the same tick. Only the last setting of each block in that tick
//! matters, so a conflict is two blocks whose last settings of one thing in one tick
//! differ. Statements are grouped by what they set and when, so the check is linear
//! in the statements plus a sort of the settings that do meet, never a comparison of
//! every pair.
//!
//! A skill call brings the settings its skill makes when it starts (the first block
//! in line, in the caller's block; the others as blocks of their own), reported at
//! the call.

use std::rc::Rc;

use ilmr_model::RobotModel;
use ilmr_stdlib::{Command, Sets};
use std::hash::{Hash, Hasher};

use rustc_hash::{FxHashMap, FxHasher};

use crate::ast::{Arg, Args, Block, Call, Expr, ExprKind, Stmt, StmtKind};
use crate::check::params;
use crate::check::schedule::{Moment, Start};
use crate::check::skills::{SkillId, Skills};
use crate::check::{FileEntry, Target, Unit};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::Kept;
use crate::span::Span;

/// A skill's settings at its start beyond this many are not followed into its callers
/// (nested skills could multiply them); the skill's own blocks are still checked.
const SKILL_SETTINGS_KEPT: usize = 256;

/// Other blocks named in one warning beyond the one it is said at.
const SECONDARY_SHOWN: usize = 3;

/// When a statement is issued: a hash of its chain of steps (`Owners::key`).
type When = u64;

/// A bijection of 64 bits that spreads every input bit over the output (MurmurHash3's
/// finalizer), so that chains differing in any step hash apart.
fn mix(mut x: u64) -> u64 {
    x ^= x >> 33;
    x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
    x ^= x >> 33;
    x = x.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    x ^ (x >> 33)
}

/// One step of the chain that says when a statement is issued.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Step {
    /// A task file's top-level blocks, or a skill's blocks, starting.
    Unit(u32, u32),
    /// A `wait(v)`: every block waiting on `v` wakes in one tick.
    Woken(u64),
    /// A `wait(seconds)` of a number written out.
    Delay(u64),
    /// The body of an `if` whose condition hashes so: guards of one condition issued at
    /// one moment are evaluated in the same ticks, so their bodies run in one tick.
    Guard(u64),
    /// A moment of its own, met by nothing else: after an `init` or a holding skill
    /// call, a guard's or a loop's body.
    Own,
}

/// A setting a skill makes when it starts, relative to a call of it.
#[derive(Debug, Clone)]
struct SkillSet {
    target: u64,
    value: u64,
    /// 0: the first block, which runs in the caller's block; others: blocks of their
    /// own, numbered within the skill's expansion.
    strand: u32,
    /// The statement inside the skill, for the message.
    file: FileId,
    span: Span,
}

enum Called {
    Command(Command),
    Skill(SkillId),
    Other,
}

#[derive(Debug, Clone, Copy)]
struct Record {
    target: u64,
    key: When,
    strand: u32,
    value: u64,
    file: FileId,
    span: Span,
    /// The skill statement behind a call's record, or the record's own.
    via: (FileId, Span),
    /// The call expansion it came from (0: written in the unit itself).
    origin: u32,
    order: u32,
}

/// What W0905 gathers as it goes, apart from what it reads: one list of fields, which
/// the streamed blocks of a task (`check/stream.rs`) hand on to the check of the other
/// files whole.
#[derive(Default)]
struct Gathered {
    /// Moments of their own handed out so far.
    owns: u64,
    /// What each target is called in messages.
    targets: FxHashMap<u64, String>,
    records: Vec<Record>,
    strands: u32,
    origins: u32,
    /// Per skill: whether a call of it holds its caller, and its settings at start.
    holds: FxHashMap<u32, bool>,
    starts: FxHashMap<u32, Rc<Vec<SkillSet>>>,
    /// Per holding skill: the waits its caller goes through (`skill_exit`).
    exits: FxHashMap<u32, Option<Rc<Vec<Step>>>>,
}

/// What the streamed blocks of a task gathered, and the calls inside skills they
/// resolved by name (`Guess`), carried into the check of the other files.
pub struct Tally {
    gathered: Gathered,
    guessed: Vec<Guess>,
}

/// A call inside a skill resolved by its name while the skill's own check had not
/// run yet (a streamed task's blocks come before it): `Owners::resume` compares it with
/// what that check resolved.
struct Guess {
    file: u32,
    slot: u32,
    at: Span,
    skill: Option<SkillId>,
}

pub struct Owners<'a, 's> {
    files: &'a [FileEntry<'s>],
    /// The skill calls the checker resolved in each task file (slot 0) and skill (its
    /// index in its file, plus 1), by statement: cheaper than looking names up again.
    calls: FxHashMap<(u32, u32), &'a FxHashMap<Span, Target>>,
    skills: &'a Skills,
    model: &'a RobotModel,
    gathered: Gathered,
    /// The commands that set something or hold their block: the others matter here
    /// only as not being skills.
    relevant: Vec<(&'static [u8], Command)>,
    buf: String,
    /// The file whose statements' moments are written down (`schedule.rs`), if any.
    recording: Option<FileId>,
    moments: Vec<Moment>,
    /// The task file being streamed and its unit's targets, lent block by block.
    streamed_file: Option<u32>,
    streamed: FxHashMap<Span, Target>,
    /// While streaming: calls inside skills resolved by name (`Guess`).
    guessed: Option<Vec<Guess>>,
}

/// The settings of one thing at one moment, as far as whether they can meet.
struct Group {
    /// The first record's block and value.
    strand: u32,
    value: u64,
    /// Whether another block, another value, is among them.
    strands: bool,
    values: bool,
}

/// What starts a list of sibling blocks.
#[derive(Debug, Clone, Copy)]
enum Opening {
    Unit { skill: bool },
    Guard(Span),
    Loop(Span),
}

impl Opening {
    fn start(self, block: usize, blocks: usize) -> Start {
        let (block, blocks) = (block as u32 + 1, blocks as u32);
        match self {
            Opening::Unit { skill } => Start::Unit {
                skill,
                block,
                blocks,
            },
            Opening::Guard(guard) => Start::Guard {
                guard,
                block,
                blocks,
            },
            Opening::Loop(guard) => Start::Loop {
                guard,
                block,
                blocks,
            },
        }
    }
}

pub fn check_owners(
    files: &[FileEntry<'_>],
    skills: &Skills,
    units: &[Unit],
    model: &RobotModel,
    diags: &mut Kept,
) {
    let records = files.iter().map(|f| f.binds).sum();
    let mut o = Owners::new(files, skills, units, model, records);
    for (i, entry) in files.iter().enumerate() {
        if !entry.library {
            o.file(FileId(i as u32));
        }
    }
    o.report(diags);
}

/// W0905 of the files from `from` on, after the streamed blocks `tally` holds, and
/// the verdicts. False when a call inside a skill that the streamed blocks resolved by
/// name is one the skill's check resolved otherwise: the caller checks as usual.
pub fn finish_owners(
    tally: Tally,
    files: &[FileEntry<'_>],
    from: usize,
    skills: &Skills,
    units: &[Unit],
    model: &RobotModel,
    diags: &mut Kept,
) -> bool {
    // The streamed blocks' records are most of them: their room is carried over.
    let mut o = Owners::new(files, skills, units, model, 0);
    for g in &tally.guessed {
        if let Some(targets) = o.calls.get(&(g.file, g.slot)) {
            let resolved = match targets.get(&g.at) {
                Some(Target::Skill(id)) => Some(*id),
                _ => None,
            };
            if resolved != g.skill {
                return false;
            }
        }
    }
    o.gathered = tally.gathered;
    for (i, entry) in files.iter().enumerate().skip(from) {
        if !entry.library {
            o.file(FileId(i as u32));
        }
    }
    o.report(diags);
    true
}

impl<'a, 's> Owners<'a, 's> {
    /// For a task streamed block by block: the skills' checks have not run yet, so
    /// calls inside skills are resolved by name and noted (`Guess`). `records` is room
    /// for the settings expected.
    pub fn streaming(
        files: &'a [FileEntry<'s>],
        skills: &'a Skills,
        model: &'a RobotModel,
        records: usize,
    ) -> Owners<'a, 's> {
        let mut o = Owners::new(files, skills, &[], model, records);
        o.guessed = Some(Vec::new());
        o
    }

    /// One top-level block (the `index`th) of the streamed task `file`, whose unit's
    /// targets are `targets` (lent for the block).
    pub fn stream_block(
        &mut self,
        file: FileId,
        index: usize,
        block: &Block<'_>,
        targets: &mut FxHashMap<Span, Target>,
    ) {
        self.streamed_file = Some(file.0);
        std::mem::swap(&mut self.streamed, targets);
        let key = self.key(0, Step::Unit(file.0, 0));
        self.block(
            file,
            block,
            key,
            0,
            Opening::Unit { skill: false },
            index,
            0,
        );
        std::mem::swap(&mut self.streamed, targets);
    }

    pub fn into_tally(self) -> Tally {
        Tally {
            gathered: self.gathered,
            guessed: self.guessed.unwrap_or_default(),
        }
    }
}

/// The moments of `file`'s statements, unsorted (`schedule::schedule`).
pub fn moments(
    files: &[FileEntry<'_>],
    skills: &Skills,
    units: &[Unit],
    model: &RobotModel,
    file: FileId,
) -> Vec<Moment> {
    let mut o = Owners::new(files, skills, units, model, 0);
    o.recording = Some(file);
    if files.get(file.0 as usize).is_some() {
        o.file(file);
    }
    o.moments
}

impl<'a, 's> Owners<'a, 's> {
    fn new(
        files: &'a [FileEntry<'s>],
        skills: &'a Skills,
        units: &'a [Unit],
        model: &'a RobotModel,
        records: usize,
    ) -> Owners<'a, 's> {
        let calls = units
            .iter()
            .filter(|u| u.special.is_none())
            .map(|u| {
                let slot = u.skill.map_or(0, |id| skills.get(id).index as u32 + 1);
                ((u.file.0, slot), &u.targets)
            })
            .collect();
        Owners {
            files,
            calls,
            skills,
            model,
            gathered: Gathered {
                // Room written only as settings are found: a large task's records would
                // otherwise be copied each time they double. There are seldom more
                // settings than statements that bind.
                records: Vec::with_capacity(records),
                ..Gathered::default()
            },
            relevant: Command::all()
                .filter(|c| c.spec().sets != Sets::Nothing || c.spec().holds_block)
                .map(|c| (c.name().as_bytes(), c))
                .collect(),
            buf: String::new(),
            recording: None,
            moments: Vec::new(),
            streamed_file: None,
            streamed: FxHashMap::default(),
            guessed: None,
        }
    }

    /// A task file's blocks and its skills' blocks, each unit from its own start.
    fn file(&mut self, file: FileId) {
        let files = self.files;
        let entry = &files[file.0 as usize];
        let key = self.key(0, Step::Unit(file.0, 0));
        let task = Opening::Unit { skill: false };
        self.blocks(file, &entry.tree.blocks, key, 0, task);
        for (s, skill) in entry.tree.skills.iter().enumerate() {
            let key = self.key(0, Step::Unit(file.0, s as u32 + 1));
            let opening = Opening::Unit { skill: true };
            self.blocks(file, &skill.blocks, key, s as u32 + 1, opening);
        }
    }
}

impl<'s> Owners<'_, 's> {
    /// The moment `step` reaches from `parent`: the same for the same chain of steps.
    /// A hash of the chain rather than a number from a table of every chain met: that
    /// table held an entry per wait and guard of the task (25,000 in the 100,000-line
    /// corpus), written fresh and looked up at random (docs/performance.md, session
    /// 13). Steps are
    /// already hashes of names and conditions (`Woken`, `Guard`), so two chains are
    /// told apart as their names are: by 64 bits of a mixed hash.
    fn key(&mut self, parent: When, step: Step) -> When {
        let (tag, a, b) = match step {
            Step::Unit(file, slot) => (1, u64::from(file), u64::from(slot)),
            Step::Woken(h) => (2, h, 0),
            Step::Delay(bits) => (3, bits, 0),
            Step::Guard(h) => (4, h, 0),
            // A moment of its own is never met again: numbered, not hashed.
            Step::Own => {
                self.gathered.owns += 1;
                (5, self.gathered.owns, 0)
            }
        };
        mix(mix(mix(mix(parent) ^ tag) ^ a) ^ b)
    }

    /// What a called name runs, as far as this check cares: a command that sets
    /// something or holds its block, a skill, or neither. Most statements are other
    /// commands, so the few relevant ones are compared first.
    fn resolve(&mut self, name: &str, at: Span, file: FileId, slot: u32) -> Called {
        let bytes = name.as_bytes();
        if let Some(&(_, c)) = self
            .relevant
            .iter()
            .find(|(n, _)| n.len() == bytes.len() && n.eq_ignore_ascii_case(bytes))
        {
            return Called::Command(c);
        }
        let targets = if slot == 0 && self.streamed_file == Some(file.0) {
            Some(&self.streamed)
        } else {
            self.calls.get(&(file.0, slot)).copied()
        };
        match targets {
            Some(targets) => match targets.get(&at) {
                Some(Target::Skill(id)) => Called::Skill(*id),
                _ => Called::Other,
            },
            // A library skill no call checked: look the name up.
            None => {
                let skill = self
                    .skills
                    .find_with(name, &mut self.buf)
                    .filter(|_| Command::from_name(name).is_none());
                if let Some(guessed) = self.guessed.as_mut() {
                    guessed.push(Guess {
                        file: file.0,
                        slot,
                        at,
                        skill,
                    });
                }
                skill.map_or(Called::Other, Called::Skill)
            }
        }
    }

    fn strand(&mut self) -> u32 {
        self.gathered.strands += 1;
        self.gathered.strands
    }

    /// Sibling blocks: each its own strand, all starting at `key`.
    fn blocks(
        &mut self,
        file: FileId,
        blocks: &[Block<'_>],
        key: When,
        slot: u32,
        opening: Opening,
    ) {
        for (b, block) in blocks.iter().enumerate() {
            self.block(file, block, key, slot, opening, b, blocks.len());
        }
    }

    /// The `b`th of `blocks` sibling blocks: a strand of its own, starting at `key`.
    #[allow(clippy::too_many_arguments)]
    fn block(
        &mut self,
        file: FileId,
        block: &Block<'_>,
        key: When,
        slot: u32,
        opening: Opening,
        b: usize,
        blocks: usize,
    ) {
        let recording = self.recording == Some(file);
        let strand = self.strand();
        let mut key = key;
        let mut queue = Queue::default();
        let mut start = opening.start(b, blocks);
        let mut first = true;
        for stmt in &block.stmts {
            if recording {
                let queued_after = queue.issue(stmt);
                self.moments.push(Moment {
                    span: stmt.span,
                    start,
                    first,
                    queued_after,
                });
            }
            let next = self.stmt(file, slot, stmt, key, strand);
            first = next != key;
            if first {
                start = Start::HeldBy { by: stmt.span };
            }
            key = next;
        }
    }

    /// Records what `stmt` sets and returns when the next statement of its block is
    /// issued.
    fn stmt(&mut self, file: FileId, slot: u32, stmt: &Stmt<'_>, key: When, strand: u32) -> When {
        let own = |o: &mut Self| o.key(key, Step::Own);
        match &stmt.kind {
            StmtKind::Call { call, .. } => self.call(file, slot, stmt.span, call, key, strand),
            StmtKind::Assign { value, .. } => match &value.kind {
                // `v = name`: a bare command or a skill call, or a copy.
                ExprKind::Name(n) => {
                    let call = Call {
                        name: *n,
                        args: None,
                    };
                    self.call(file, slot, stmt.span, &call, key, strand)
                }
                _ => key,
            },
            StmtKind::If(c) => {
                let mut h = FxHasher::default();
                hash_expr(&c.cond, &mut h);
                let body = self.key(key, Step::Guard(h.finish()));
                self.blocks(file, &c.body, body, slot, Opening::Guard(stmt.span));
                key
            }
            StmtKind::While { body, .. } => {
                let at = own(self);
                self.blocks(file, &body.body, at, slot, Opening::Loop(stmt.span));
                key
            }
            StmtKind::Check { .. }
            | StmtKind::Break { .. }
            | StmtKind::Priority
            | StmtKind::Error => key,
        }
    }

    fn call(
        &mut self,
        file: FileId,
        slot: u32,
        at: Span,
        call: &Call<'_>,
        key: When,
        strand: u32,
    ) -> When {
        let id = match self.resolve(call.name.text, at, file, slot) {
            Called::Other => return key,
            Called::Skill(id) => id,
            Called::Command(command) => {
                return self.command(file, at, command, call.args.as_ref(), key, strand);
            }
        };
        self.skill_call(file, at, id, key, strand)
    }

    fn command(
        &mut self,
        file: FileId,
        at: Span,
        command: Command,
        args: Option<&Args<'_>>,
        key: When,
        strand: u32,
    ) -> When {
        let spec = command.spec();
        if let Some((target, value)) = self.setting(file, command, args) {
            let order = self.gathered.records.len() as u32;
            self.gathered.records.push(Record {
                target,
                key,
                strand,
                value,
                file,
                span: at,
                via: (file, at),
                origin: 0,
                order,
            });
        }
        if !spec.holds_block {
            return key;
        }
        let waited = args.and_then(|a| match a.items.first() {
            Some(Arg::Positional(e)) if a.items.len() == 1 => Some(e),
            _ => None,
        });
        let step = match (command, waited.map(|e| &e.kind)) {
            (Command::Wait, Some(ExprKind::Name(n))) => Step::Woken(hash_str(n.text)),
            (Command::Wait, Some(ExprKind::Number(s))) => Step::Delay(s.to_bits()),
            _ => Step::Own,
        };
        self.key(key, step)
    }

    fn skill_call(&mut self, file: FileId, at: Span, id: SkillId, key: When, strand: u32) -> When {
        let sets = self.skill_start(id, &mut Vec::new());
        if !sets.is_empty() {
            self.gathered.origins += 1;
            let origin = self.gathered.origins;
            let mut fresh = FxHashMap::default();
            for s in sets.iter() {
                let strand = if s.strand == 0 {
                    strand
                } else {
                    *fresh.entry(s.strand).or_insert_with(|| {
                        self.gathered.strands += 1;
                        self.gathered.strands
                    })
                };
                let order = self.gathered.records.len() as u32;
                self.gathered.records.push(Record {
                    target: s.target,
                    key,
                    strand,
                    value: s.value,
                    file,
                    span: at,
                    via: (s.file, s.span),
                    origin,
                    order,
                });
            }
        }
        if !self.skill_holds(id, &mut Vec::new()) {
            return key;
        }
        match self.skill_exit(id, &mut Vec::new()) {
            Some(steps) => steps.iter().fold(key, |k, &step| self.key(k, step)),
            None => self.key(key, Step::Own),
        }
    }

    /// The waits a call of a holding skill goes through before it lets its caller go:
    /// the steps of every statement of the skill's first block that holds, through the
    /// skills it calls, so that what follows the call meets what follows the same waits
    /// elsewhere. `None` when one of them is a moment of its own (an `init`, a `wait`
    /// on a parameter, a chain too deep).
    fn skill_exit(&mut self, id: SkillId, open: &mut Vec<u32>) -> Option<Rc<Vec<Step>>> {
        if let Some(e) = self.gathered.exits.get(&id.0) {
            return e.clone();
        }
        if open.contains(&id.0) || open.len() >= max_call_depth() {
            return None;
        }
        open.push(id.0);
        let info = self.skills.get(id);
        let file = info.file;
        let files = self.files;
        let skill = &files[file.0 as usize].tree.skills[info.index];
        let mut steps = Some(Vec::new());
        for stmt in skill.blocks.first().map_or(&[][..], |b| &b.stmts) {
            let Some(out) = steps.as_mut() else { break };
            let Some((name, args)) = called(stmt) else {
                continue;
            };
            match self.resolve(name, stmt.span, file, info.index as u32 + 1) {
                Called::Other => {}
                Called::Command(c) if !c.spec().holds_block => {}
                Called::Command(c) => {
                    let waited = args.and_then(|a| match &a.items[..] {
                        [Arg::Positional(e)] => Some(&e.kind),
                        _ => None,
                    });
                    match (c, waited) {
                        (Command::Wait, Some(ExprKind::Name(n))) if !is_param(skill, n.text) => {
                            out.push(Step::Woken(hash_str(n.text)))
                        }
                        (Command::Wait, Some(ExprKind::Number(s))) => {
                            out.push(Step::Delay(s.to_bits()))
                        }
                        _ => steps = None,
                    }
                }
                Called::Skill(inner) => {
                    if self.skill_holds(inner, open) {
                        match self.skill_exit(inner, open) {
                            Some(inner) => out.extend(inner.iter().copied()),
                            None => steps = None,
                        }
                    }
                }
            }
        }
        open.pop();
        let steps = steps.map(Rc::new);
        self.gathered.exits.insert(id.0, steps.clone());
        steps
    }

    /// What a statement of `command` sets, and a value that is equal for statements
    /// that set the same: hashes of the target and of the value, made without
    /// allocating (a large task sets something in most of its blocks).
    fn setting(
        &mut self,
        file: FileId,
        command: Command,
        args: Option<&Args<'_>>,
    ) -> Option<(u64, u64)> {
        let items: &[Arg<'_>] = args.map_or(&[], |a| &a.items);
        let words = items.iter().filter_map(|a| match a {
            Arg::Positional(Expr {
                kind: ExprKind::Name(n),
                ..
            }) => Some(n.text),
            _ => None,
        });
        let (target, rest) = match command.spec().sets.applies(words) {
            Sets::Nothing => return None,
            Sets::Setting { what, .. } => {
                let target = hash_str(what);
                self.gathered
                    .targets
                    .entry(target)
                    .or_insert_with(|| what.to_string());
                (target, items)
            }
            Sets::Device => {
                let Some(Arg::Positional(first)) = items.first() else {
                    return None;
                };
                let device = match &first.kind {
                    ExprKind::Name(n) => self.model.device(n.text),
                    ExprKind::Number(n) => self.model.device_by_id(*n as i64),
                    _ => None,
                };
                let text = self.files[file.0 as usize].text;
                let written = first.span.slice(text).trim();
                let name = device.map_or(written, |d| d.name.as_str());
                let target = hash_str(name) ^ DEVICE_SEED;
                self.gathered
                    .targets
                    .entry(target)
                    .or_insert_with(|| format!("actuator `{name}`"));
                (target, &items[1..])
            }
        };
        let mut h = FxHasher::default();
        command.hash(&mut h);
        // Settings may come in any order: their hashes are summed.
        let mut settings = 0u64;
        for a in rest {
            match a {
                Arg::Positional(e) => hash_expr(e, &mut h),
                Arg::Setting { key, value: e } => {
                    let mut one = FxHasher::default();
                    hash_name(key.text, &mut one);
                    hash_expr(e, &mut one);
                    settings = settings.wrapping_add(one.finish());
                }
            }
        }
        settings.hash(&mut h);
        Some((target, h.finish()))
    }

    /// Whether a call of the skill holds its caller: its first block waits (a `wait`,
    /// an `init` or a call that holds) before it has issued its last statement.
    fn skill_holds(&mut self, id: SkillId, open: &mut Vec<u32>) -> bool {
        if let Some(&h) = self.gathered.holds.get(&id.0) {
            return h;
        }
        if open.contains(&id.0) || open.len() >= max_call_depth() {
            // Recursion (E0601) or a chain the VM refuses (E0603): say it holds,
            // which warns of less.
            return true;
        }
        open.push(id.0);
        let info = self.skills.get(id);
        let files = self.files;
        let blocks = &files[info.file.0 as usize].tree.skills[info.index].blocks;
        let mut holds = false;
        for stmt in blocks.first().map_or(&[][..], |b| &b.stmts) {
            let name = match &stmt.kind {
                StmtKind::Call { call, .. } => call.name.text,
                StmtKind::Assign { value, .. } => match &value.kind {
                    ExprKind::Name(n) => n.text,
                    _ => continue,
                },
                _ => continue,
            };
            holds = match self.resolve(name, stmt.span, info.file, info.index as u32 + 1) {
                Called::Command(c) => c.spec().holds_block,
                Called::Skill(inner) => self.skill_holds(inner, open),
                Called::Other => false,
            };
            if holds {
                break;
            }
        }
        open.pop();
        self.gathered.holds.insert(id.0, holds);
        holds
    }

    /// The settings a skill makes in the tick it is called: the statements of each of
    /// its blocks up to the first that holds, through the skills they call.
    fn skill_start(&mut self, id: SkillId, open: &mut Vec<u32>) -> Rc<Vec<SkillSet>> {
        if let Some(s) = self.gathered.starts.get(&id.0) {
            return s.clone();
        }
        if open.contains(&id.0) || open.len() >= max_call_depth() {
            return Rc::default();
        }
        open.push(id.0);
        let info = self.skills.get(id);
        let file = info.file;
        let files = self.files;
        let blocks = &files[file.0 as usize].tree.skills[info.index].blocks;
        let mut out: Vec<SkillSet> = Vec::new();
        let mut strands = 0u32;
        for (b, block) in blocks.iter().enumerate() {
            let strand = if b == 0 {
                0
            } else {
                strands += 1;
                strands
            };
            for stmt in &block.stmts {
                // Guards and loops run their bodies later; they do not hold.
                let Some((name, args)) = called(stmt) else {
                    continue;
                };
                let span = stmt.span;
                let inner = match self.resolve(name, span, file, info.index as u32 + 1) {
                    Called::Other => continue,
                    Called::Skill(inner) => inner,
                    Called::Command(command) => {
                        if let Some((target, value)) = self.setting(file, command, args) {
                            out.push(SkillSet {
                                target,
                                value,
                                strand,
                                file,
                                span,
                            });
                        }
                        if command.spec().holds_block {
                            break;
                        }
                        continue;
                    }
                };
                let nested = self.skill_start(inner, open);
                let mut fresh = FxHashMap::default();
                for s in nested.iter() {
                    let strand = if s.strand == 0 {
                        strand
                    } else {
                        *fresh.entry(s.strand).or_insert_with(|| {
                            strands += 1;
                            strands
                        })
                    };
                    out.push(SkillSet {
                        strand,
                        ..s.clone()
                    });
                }
                if self.skill_holds(inner, open) {
                    break;
                }
            }
        }
        // Only the last setting of a block in the tick is seen by the others.
        let mut seen = FxHashMap::default();
        for (i, s) in out.iter().enumerate() {
            seen.insert((s.target, s.strand), i);
        }
        let mut kept: Vec<usize> = seen.into_values().collect();
        kept.sort_unstable();
        kept.truncate(SKILL_SETTINGS_KEPT);
        let out = Rc::new(kept.into_iter().map(|i| out[i].clone()).collect::<Vec<_>>());
        open.pop();
        self.gathered.starts.insert(id.0, out.clone());
        out
    }

    fn report(&mut self, diags: &mut Kept) {
        let mut records = std::mem::take(&mut self.gathered.records);
        // Only settings of a thing that more than one block sets at one moment, to
        // more than one value, can meet: most are alone (or agree, as copies of one
        // block do), and are left out before sorting.
        let mut groups: FxHashMap<(u64, When), Group> = FxHashMap::default();
        groups.reserve(records.len());
        for r in &records {
            let g = groups.entry((r.target, r.key)).or_insert(Group {
                strand: r.strand,
                value: r.value,
                strands: false,
                values: false,
            });
            g.strands |= g.strand != r.strand;
            g.values |= g.value != r.value;
        }
        records.retain(|r| {
            let g = &groups[&(r.target, r.key)];
            g.strands && g.values
        });
        records.sort_unstable_by_key(|r| (r.target, r.key, r.strand, r.order));
        // The last setting of each block in each tick.
        let mut last: Vec<Record> = Vec::new();
        for r in records {
            match last.last_mut() {
                Some(l) if (l.target, l.key, l.strand) == (r.target, r.key, r.strand) => *l = r,
                _ => last.push(r),
            }
        }
        for group in last.chunk_by(|a, b| (a.target, a.key) == (b.target, b.key)) {
            if group.len() < 2 || group.iter().all(|r| r.value == group[0].value) {
                continue;
            }
            // A skill's own blocks are reported in the skill, not at each call.
            if group[0].origin != 0 && group.iter().all(|r| r.origin == group[0].origin) {
                continue;
            }
            let primary = group.iter().max_by_key(|r| r.order).copied().unwrap();
            let others: Vec<&Record> = group.iter().filter(|r| r.value != primary.value).collect();
            diags.push(self.diagnostic(&primary, &others));
        }
    }

    fn statement(&self, (file, span): (FileId, Span)) -> &str {
        let text = span.slice(self.files[file.0 as usize].text);
        text.lines().next().unwrap_or("").trim()
    }

    fn diagnostic(&self, primary: &Record, others: &[&Record]) -> Diagnostic {
        let what = &self.gathered.targets[&primary.target];
        let shown = |r: &Record| {
            let own = self.statement(r.via);
            if r.origin == 0 {
                format!("`{own}`")
            } else {
                format!("`{}` (through `{own}`)", self.statement((r.file, r.span)))
            }
        };
        let mut d = Diagnostic::new(
            Code::SettingRace,
            primary.file,
            primary.span,
            format!(
                "{} and {} set the robot's {what} in the same tick from blocks that run at the same time",
                shown(primary),
                shown(others[0]),
            ),
        )
        .with_label(if primary.origin == 0 {
            format!("sets {what}")
        } else {
            format!("sets {what} through the skill: `{}`", self.statement(primary.via))
        });
        for r in others.iter().take(SECONDARY_SHOWN) {
            let label = if r.origin == 0 {
                format!("also sets {what} in that tick, to another value")
            } else {
                format!(
                    "also sets {what} in that tick, through the skill: `{}`",
                    self.statement(r.via)
                )
            };
            d = d.with_secondary(r.file, r.span, label);
        }
        let more = others.len().saturating_sub(SECONDARY_SHOWN);
        let more = if more > 0 {
            format!(" ({more} more blocks set it in that tick too)")
        } else {
            String::new()
        };
        d.with_help(format!(
            "the robot keeps whichever the VM issues last, which the order of the blocks decides, not the text{more}; set it in one block, in the order meant, or hold one of them (`wait(v)`) until the other's moment has passed"
        ))
    }
}

/// The movement reservation as one block sees it: the last movement it issued that
/// may still hold the reservation when the next one is issued.
#[derive(Default)]
struct Queue<'s> {
    last: Option<(Span, Option<&'s str>)>,
}

impl<'s> Queue<'s> {
    /// Takes `stmt`: the earlier movement it queues behind, if it is a movement.
    fn issue(&mut self, stmt: &Stmt<'s>) -> Option<Span> {
        let StmtKind::Call { bind, call } = &stmt.kind else {
            return None;
        };
        let command = Command::from_name(call.name.text);
        if command == Some(Command::Wait) {
            // `wait(m)` on the last movement: it has ended before anything after.
            let waited = call.args.as_ref().and_then(|a| match a.items.first() {
                Some(Arg::Positional(Expr {
                    kind: ExprKind::Name(n),
                    ..
                })) => Some(n.text),
                _ => None,
            });
            if let (Some(w), Some((_, Some(b)))) = (waited, self.last)
                && w.eq_ignore_ascii_case(b)
            {
                self.last = None;
            }
            return None;
        }
        if !command.is_some_and(|c| c.spec().movement) {
            return None;
        }
        let before = self.last.map(|(span, _)| span);
        self.last = Some((stmt.span, bind.map(|b| b.text)));
        before
    }
}

/// The VM's skill call depth: deeper chains are refused (E0603), and following them
/// would recurse as deep as they go.
/// What a statement calls, command or skill, with its arguments: a call, or a bare
/// name assigned (`m = Pause`).
fn called<'a, 's>(stmt: &'a Stmt<'s>) -> Option<(&'s str, Option<&'a Args<'s>>)> {
    match &stmt.kind {
        StmtKind::Call { call, .. } => Some((call.name.text, call.args.as_ref())),
        StmtKind::Assign { value, .. } => match &value.kind {
            ExprKind::Name(n) => Some((n.text, None)),
            _ => None,
        },
        _ => None,
    }
}

fn max_call_depth() -> usize {
    usize::from(ilmr_vm::Config::default().max_call_depth)
}

/// Whether `name` is one of a parameterized skill's parameters, whose value each call
/// gives (`Corner(d, side=left/right):`).
fn is_param(skill: &crate::ast::Skill<'_>, name: &str) -> bool {
    skill.params.as_ref().is_some_and(|p| {
        p.items.iter().any(|a| match a {
            Arg::Positional(Expr {
                kind: ExprKind::Name(n),
                ..
            }) => n.is(name),
            Arg::Setting { key, .. } => key.is(name),
            _ => false,
        })
    })
}

/// Device targets apart from settings of the same name.
const DEVICE_SEED: u64 = 0x9e37_79b9_7f4a_7c15;

/// A name's hash, the same in any letter case.
fn hash_str(text: &str) -> u64 {
    let mut h = FxHasher::default();
    hash_name(text, &mut h);
    h.finish()
}

fn hash_name(text: &str, h: &mut FxHasher) {
    if text.is_ascii() {
        // Lower-cased a chunk at a time: per character, hashing cost more than the
        // rest of the check of a `wait`.
        let mut chunk = [0u8; 32];
        for part in text.as_bytes().chunks(chunk.len()) {
            let lower = &mut chunk[..part.len()];
            lower.copy_from_slice(part);
            lower.make_ascii_lowercase();
            h.write(lower);
        }
    } else {
        let mut utf8 = [0u8; 4];
        for c in text.chars().flat_map(char::to_lowercase) {
            h.write(c.encode_utf8(&mut utf8).as_bytes());
        }
    }
    h.write_u8(0xff);
}

/// A value's hash: numbers folded (`0.2*2` and `.4` hash alike), names in any case.
fn hash_expr(e: &Expr<'_>, h: &mut FxHasher) {
    if let Some(v) = params::number(e) {
        h.write_u8(0);
        // 0.0 and -0.0 are one value.
        h.write_u64((v + 0.0).to_bits());
        return;
    }
    match &e.kind {
        ExprKind::Number(_) => unreachable!("a number folds"),
        ExprKind::Name(n) => {
            h.write_u8(1);
            hash_name(n.text, h);
        }
        ExprKind::Neg(inner) => {
            h.write_u8(2);
            hash_expr(inner, h);
        }
        ExprKind::Binary { op, lhs, rhs } => {
            h.write_u8(3);
            h.write_u8(*op as u8);
            hash_expr(lhs, h);
            hash_expr(rhs, h);
        }
        ExprKind::Compare { op, lhs, rhs, .. } => {
            h.write_u8(4);
            h.write_u8(*op as u8);
            hash_expr(lhs, h);
            hash_expr(rhs, h);
        }
        ExprKind::Error => h.write_u8(5),
    }
}
