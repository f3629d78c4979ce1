//! The statements each `break(pattern)` of the module can end, found once for all its
//! patterns (`ilmr_stdlib::pattern::Needles`, the checker's automaton). Reading every
//! live statement's text at every break cost live nodes x text per break: 20,000
//! `break(zzN)` beside 20,000 counting loops took 9.5 s of a 0.5 s run. A break now
//! looks its statements up, ends nothing at once when none of them can be live, and
//! otherwise tests each live node against a bit per statement, paying for them from the
//! tick's budget ([`NODES_PER_OP`]).

use ilmr_stdlib::pattern::Needles;
use rustc_hash::FxHashMap;

use crate::bytecode::{Module, Op};

/// Statement-pattern pairs a module's targets may hold (8 bytes each while they are
/// found, 4 kept). A pattern found in every statement of a program of millions of
/// statements, or thousands of patterns each found in thousands, come near; past it
/// the breaks read the live statements' texts as they did before.
pub const BREAK_TARGETS: u64 = 4_000_000;

/// Live nodes a break that looks at them pays one op of the tick's budget for (as a
/// pattern's statements are marked, eight of them one op). A node looked at costs a
/// few nanoseconds, an op of the budget tens.
pub const NODES_PER_OP: usize = 8;

pub(crate) struct Targets {
    /// The module's size when they were found: a joined line may bring new patterns.
    code: usize,
    stmts: usize,
    /// A pattern's name to its distinct needle; an empty needle has none.
    needle: FxHashMap<u32, u32>,
    /// The statements of needle `i` are `stmts_of[from[i]..from[i + 1]]`.
    from: Vec<u32>,
    stmts_of: Vec<u32>,
    /// [`BREAK_TARGETS`] was reached: no pattern's statements are known.
    whole: bool,
}

/// What a break knows of the statements it can end.
pub(crate) enum Found<'a> {
    /// The statements (in increasing order); none when the needle is empty.
    Statements(&'a [u32]),
    /// Past [`BREAK_TARGETS`]: each live statement's text must be read.
    Unknown,
}

impl Targets {
    pub fn new(module: &Module) -> Targets {
        // Statements a break can end: those run by an instruction other than a break
        // (a break's own text holds its pattern, yet it is never live).
        let mut runs = vec![false; module.stmts.len()];
        let mut patterns: Vec<(u32, &str)> = Vec::new();
        for instr in &module.code {
            match instr.op {
                Op::Break { pattern } => patterns.push((pattern.0, module.name(pattern).trim())),
                _ => {
                    if let Some(r) = runs.get_mut(instr.stmt.index()) {
                        *r = true;
                    }
                }
            }
        }
        patterns.sort_unstable_by_key(|&(name, _)| name);
        patterns.dedup_by_key(|&mut (name, _)| name);
        let needles = Needles::new(patterns.iter().map(|&(_, p)| p), BREAK_TARGETS);
        let needle: FxHashMap<u32, u32> = (patterns.iter().enumerate())
            .filter_map(|(i, &(name, _))| needles.id(i).map(|id| (name, id)))
            .collect();
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let mut seen = Vec::new();
        let mut whole = true;
        for (s, stmt) in module.stmts.iter().enumerate() {
            if !runs[s] {
                continue;
            }
            let found = needles.each_in(&stmt.text, &mut seen, |id| pairs.push((id, s as u32)));
            if found.is_none() {
                whole = false;
                pairs = Vec::new();
                break;
            }
        }
        // Grouped by needle; each needle's statements stay in increasing order.
        let mut from = vec![0u32; needles.distinct() + 1];
        for &(id, _) in &pairs {
            from[id as usize + 1] += 1;
        }
        for i in 1..from.len() {
            from[i] += from[i - 1];
        }
        let mut next = from.clone();
        let mut stmts_of = vec![0u32; pairs.len()];
        for &(id, s) in &pairs {
            stmts_of[next[id as usize] as usize] = s;
            next[id as usize] += 1;
        }
        Targets {
            code: module.code.len(),
            stmts: module.stmts.len(),
            needle,
            from,
            stmts_of,
            whole,
        }
    }

    /// Whether they were found for this module as it is now.
    pub fn current(&self, module: &Module) -> bool {
        self.code == module.code.len() && self.stmts == module.stmts.len()
    }

    /// The statements the pattern named `name` can end.
    pub fn of(&self, name: u32) -> Found<'_> {
        if !self.whole {
            return Found::Unknown;
        }
        Found::Statements(match self.needle.get(&name) {
            Some(&id) => {
                &self.stmts_of[self.from[id as usize] as usize..self.from[id as usize + 1] as usize]
            }
            None => &[],
        })
    }
}

/// One bit per statement, set for a break's statements while it looks at the live
/// nodes, and cleared after.
#[derive(Default)]
pub(crate) struct Marks(Vec<u64>);

impl Marks {
    pub fn set(&mut self, stmts: &[u32], of: usize) {
        self.0.resize(of.div_ceil(64).max(self.0.len()), 0);
        for &s in stmts {
            self.0[s as usize / 64] |= 1 << (s % 64);
        }
    }

    pub fn has(&self, stmt: u32) -> bool {
        self.0
            .get(stmt as usize / 64)
            .is_some_and(|w| w & (1 << (stmt % 64)) != 0)
    }

    pub fn clear(&mut self, stmts: &[u32]) {
        for &s in stmts {
            self.0[s as usize / 64] = 0;
        }
    }
}
