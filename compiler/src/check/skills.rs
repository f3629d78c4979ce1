//! Skills of a program: where each is defined, which skills each calls (to reject
//! recursion) and which variables each binds (so that a task sees the variables of the
//! skills it has called).

use rustc_hash::FxHashMap as HashMap;

use ilmr_model::RobotModel;
use ilmr_stdlib::{Command, VarKind};

use crate::ast::{Block, Call, ExprKind, FileKind, Name, StmtKind};
use crate::check::FileEntry;
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::Kept;
use crate::span::Span;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SkillId(pub u32);

#[derive(Debug)]
pub struct SkillInfo {
    pub name: String,
    pub file: FileId,
    /// Index into the file's `skills`.
    pub index: usize,
    pub header: Span,
    /// The header's parameters (`NAME(d, side=left/right):`); empty for most skills.
    pub params: Vec<super::params::Param>,
    /// Skills called directly, with the call's span.
    calls: Vec<(SkillId, Span)>,
    /// Variables bound directly in the body.
    binds: Vec<(String, VarKind)>,
    /// Variables bound by a call: its own and those of the skills it calls.
    transitive: Vec<(String, VarKind)>,
}

#[derive(Debug, Default)]
pub struct Skills {
    list: Vec<SkillInfo>,
    index: HashMap<String, SkillId>,
    called: Vec<bool>,
}

impl Skills {
    pub fn collect(files: &[FileEntry<'_>], model: &RobotModel, diags: &mut Kept) -> Skills {
        let mut skills = Skills::default();
        // User files first, so that a user's skill replaces a built-in of the same name.
        let order = files
            .iter()
            .enumerate()
            .filter(|(_, f)| !f.builtin)
            .chain(files.iter().enumerate().filter(|(_, f)| f.builtin));
        for (i, entry) in order {
            if entry.tree.kind != FileKind::Skills {
                continue;
            }
            for (index, skill) in entry.tree.skills.iter().enumerate() {
                let key = skill.name.text.to_lowercase();
                if let Some(&existing) = skills.index.get(&key) {
                    if !entry.builtin {
                        let first = &skills.list[existing.0 as usize];
                        diags.push(
                            Diagnostic::new(
                                Code::DuplicateSkill,
                                FileId(i as u32),
                                skill.header,
                                format!("skill `{}` is defined twice", skill.name.text),
                            )
                            .with_label("defined again here")
                            .with_secondary(
                                first.file,
                                first.header,
                                "first defined here",
                            ),
                        );
                    }
                    continue;
                }
                if Command::from_name(skill.name.text).is_some() {
                    diags.push(
                        Diagnostic::new(
                            Code::ReservedName,
                            FileId(i as u32),
                            skill.name.span,
                            format!("`{}` is a command and cannot name a skill", skill.name.text),
                        )
                        .with_label("choose another name"),
                    );
                    continue;
                }
                let id = SkillId(skills.list.len() as u32);
                skills.index.insert(key, id);
                skills.list.push(SkillInfo {
                    name: skill.name.text.to_string(),
                    file: FileId(i as u32),
                    index,
                    header: skill.header,
                    params: match &skill.params {
                        Some(args) if !entry.builtin => {
                            super::params::read(args, FileId(i as u32), diags)
                        }
                        Some(args) => super::params::read(args, FileId(i as u32), &mut Kept::new()),
                        None => Vec::new(),
                    },
                    calls: Vec::new(),
                    binds: Vec::new(),
                    transitive: Vec::new(),
                });
            }
        }
        skills.called = vec![false; skills.list.len()];
        for i in 0..skills.list.len() {
            let info = &skills.list[i];
            let blocks = &files[info.file.0 as usize].tree.skills[info.index].blocks;
            let mut calls = Vec::new();
            let mut binds = Vec::new();
            scan(blocks, &skills, model, &mut calls, &mut binds);
            skills.list[i].calls = calls;
            skills.list[i].binds = binds;
        }
        let heights = skills.report_recursion(diags);
        let max_depth = usize::from(ilmr_vm::Config::default().max_call_depth);
        for (i, &height) in heights.iter().enumerate() {
            // A call of a skill past the depth limit is an error already; walking its
            // whole chain from every skill on it would cost the square of its length.
            skills.list[i].transitive = if height > max_depth {
                skills.list[i].binds.clone()
            } else {
                skills.reach_binds(SkillId(i as u32))
            };
        }
        skills
    }

    /// The skills of a running program, known by name only (a line joining it may call
    /// them; their bodies were checked when the program was). `SkillId(i)` is the i-th.
    pub fn from_names<'n>(names: impl IntoIterator<Item = &'n str>) -> Skills {
        let mut skills = Skills::default();
        for name in names {
            let id = SkillId(skills.list.len() as u32);
            skills.index.insert(name.to_lowercase(), id);
            skills.list.push(SkillInfo {
                name: name.to_string(),
                file: FileId(u32::MAX),
                index: usize::MAX,
                header: Span::default(),
                params: Vec::new(),
                calls: Vec::new(),
                binds: Vec::new(),
                transitive: Vec::new(),
            });
        }
        skills.called = vec![true; skills.list.len()];
        skills
    }

    /// Marks a skill, and the skills it calls, as called: a library skill is checked only
    /// then.
    pub fn mark_called(&mut self, id: SkillId) {
        let mut todo = vec![id];
        while let Some(id) = todo.pop() {
            if !std::mem::replace(&mut self.called[id.0 as usize], true) {
                todo.extend(self.list[id.0 as usize].calls.iter().map(|c| c.0));
            }
        }
    }

    pub fn is_called(&self, id: SkillId) -> bool {
        self.called[id.0 as usize]
    }

    pub fn find(&self, name: &str) -> Option<SkillId> {
        self.find_with(name, &mut String::new())
    }

    /// As `find`, lower-casing into `buf` (reused by a caller that looks up many).
    pub fn find_with(&self, name: &str, buf: &mut String) -> Option<SkillId> {
        if self.index.is_empty() {
            return None;
        }
        self.index.get(super::constants::key(name, buf)).copied()
    }

    pub fn len(&self) -> usize {
        self.list.len()
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Every skill under its lower-cased key, in no particular order.
    pub fn keys(&self) -> impl Iterator<Item = (&str, SkillId)> {
        self.index.iter().map(|(k, id)| (k.as_str(), *id))
    }

    pub fn get(&self, id: SkillId) -> &SkillInfo {
        &self.list[id.0 as usize]
    }

    pub fn iter(&self) -> impl Iterator<Item = (SkillId, &SkillInfo)> {
        self.list
            .iter()
            .enumerate()
            .map(|(i, s)| (SkillId(i as u32), s))
    }

    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.list.iter().map(|s| s.name.as_str())
    }

    /// Every variable bound in any skill.
    pub fn all_binds(&self) -> Vec<(String, VarKind)> {
        self.list
            .iter()
            .flat_map(|s| s.binds.iter().cloned())
            .collect()
    }

    /// The variables a call of this skill binds, through the skills it calls.
    pub fn transitive_binds(&self, id: SkillId) -> &[(String, VarKind)] {
        &self.list[id.0 as usize].transitive
    }

    fn reach_binds(&self, id: SkillId) -> Vec<(String, VarKind)> {
        let mut seen = vec![false; self.list.len()];
        let mut stack = vec![id];
        let mut out = Vec::new();
        while let Some(s) = stack.pop() {
            if std::mem::replace(&mut seen[s.0 as usize], true) {
                continue;
            }
            let info = &self.list[s.0 as usize];
            out.extend(info.binds.iter().cloned());
            stack.extend(info.calls.iter().map(|c| c.0));
        }
        out
    }

    /// E0601 once per cycle, at the call that closes it; E0603 at each skill whose
    /// calls nest one deeper than the VM runs. One depth-first walk over the call graph,
    /// on a stack of its own: a chain of skills is as long as a file makes it. Returns
    /// each skill's height: the longest chain of calls a call of it makes, itself included.
    fn report_recursion(&self, diags: &mut Kept) -> Vec<usize> {
        #[derive(Clone, Copy, PartialEq)]
        enum Mark {
            New,
            Active,
            Done,
        }
        let max_depth = usize::from(ilmr_vm::Config::default().max_call_depth);
        let mut marks = vec![Mark::New; self.list.len()];
        let mut height = vec![1usize; self.list.len()];
        // The walk's path: each skill with the index of its next call to follow, and the
        // span of the call that entered the skill above it.
        let mut path: Vec<(SkillId, usize, Span)> = Vec::new();
        for root in 0..self.list.len() {
            if marks[root] != Mark::New {
                continue;
            }
            marks[root] = Mark::Active;
            path.push((SkillId(root as u32), 0, Span::default()));
            while let Some(&mut (id, ref mut next, _)) = path.last_mut() {
                let calls = &self.list[id.0 as usize].calls;
                let Some(&(callee, span)) = calls.get(*next) else {
                    marks[id.0 as usize] = Mark::Done;
                    path.pop();
                    if let Some(&(caller, _, _)) = path.last() {
                        let h = height[id.0 as usize] + 1;
                        let caller = &mut height[caller.0 as usize];
                        *caller = (*caller).max(h);
                    }
                    if height[id.0 as usize] == max_depth + 1 {
                        diags.push(self.too_deep(id, &height, max_depth));
                    }
                    continue;
                };
                *next += 1;
                match marks[callee.0 as usize] {
                    Mark::Active => diags.push(self.cycle(callee, span, &path)),
                    Mark::New => {
                        marks[callee.0 as usize] = Mark::Active;
                        path.push((callee, 0, span));
                    }
                    Mark::Done => {
                        let h = height[callee.0 as usize] + 1;
                        let caller = &mut height[id.0 as usize];
                        *caller = (*caller).max(h);
                    }
                }
            }
        }
        height
    }

    /// The cycle closed by the call at `span` (from the skill on top of `path`) of
    /// `callee`, which is on the path.
    fn cycle(&self, callee: SkillId, span: Span, path: &[(SkillId, usize, Span)]) -> Diagnostic {
        let start = path
            .iter()
            .position(|(s, _, _)| *s == callee)
            .unwrap_or(path.len());
        let on_cycle = &path[start..];
        let caller = self.get(on_cycle.last().map_or(callee, |p| p.0));
        let mut cycle: Vec<&str> = on_cycle
            .iter()
            .map(|(s, _, _)| self.get(*s).name.as_str())
            .collect();
        cycle.push(self.get(callee).name.as_str());
        cycle.dedup();
        let mut d = Diagnostic::new(
            Code::RecursiveSkill,
            caller.file,
            span,
            format!(
                "skill `{}` calls itself: {}",
                self.get(callee).name,
                cycle.join(" -> ")
            ),
        )
        .with_label("this call closes the cycle");
        // Each skill on the cycle but the last was left by a call: the span stored with
        // the skill after it.
        for pair in on_cycle.windows(2) {
            let info = self.get(pair[0].0);
            d = d.with_secondary(info.file, pair[1].2, format!("called from `{}`", info.name));
        }
        d
    }

    /// E0603 at a skill whose calls nest `max_depth + 1` deep, naming the chain.
    fn too_deep(&self, id: SkillId, height: &[usize], max_depth: usize) -> Diagnostic {
        // Down the tallest callee each time; bounded, since a cycle (reported apart)
        // leaves heights that need not fall along it.
        let mut chain = vec![id];
        while chain.len() <= max_depth
            && let Some(&(next, _)) = chain.last().and_then(|at| {
                self.list[at.0 as usize]
                    .calls
                    .iter()
                    .max_by_key(|(c, _)| height[c.0 as usize])
            })
        {
            chain.push(next);
        }
        let names: Vec<&str> = chain.iter().map(|s| self.get(*s).name.as_str()).collect();
        let shown = match names.as_slice() {
            [a, b, c, .., y, z] if names.len() > 6 => {
                format!("{a} -> {b} -> {c} -> ... -> {y} -> {z}")
            }
            all => all.join(" -> "),
        };
        let info = self.get(id);
        Diagnostic::new(
            Code::SkillsTooDeep,
            info.file,
            info.header,
            format!(
                "a call of `{}` nests {} skill calls ({shown}); the VM runs at most {max_depth}",
                info.name,
                max_depth + 1,
            ),
        )
        .with_label("calling this skill would be refused")
        .with_help("call the inner skills from the task, one after another")
    }
}

/// A quick pass over a body: which skills it calls and which variables it binds, with
/// the kind each binding will hold. It needs no variable scope, so it can run before
/// anything is checked.
fn scan(
    blocks: &[Block<'_>],
    skills: &Skills,
    model: &RobotModel,
    calls: &mut Vec<(SkillId, Span)>,
    binds: &mut Vec<(String, VarKind)>,
) {
    for block in blocks {
        for stmt in &block.stmts {
            match &stmt.kind {
                StmtKind::Call { bind, call } => {
                    let kind = call_kind(call, skills, model, calls);
                    if let (Some(b), Some(k)) = (bind, kind) {
                        binds.push((b.text.to_string(), k));
                    }
                    if let Some(cmd) = Command::from_name(call.name.text)
                        && cmd == Command::SavePos
                        && let Some(name) = first_name(call)
                    {
                        binds.push((name.text.to_string(), VarKind::Position));
                    }
                }
                StmtKind::Assign { target, value } => {
                    let kind = match &value.kind {
                        ExprKind::Name(n) if skills.find(n.text).is_some() => {
                            let call = Call {
                                name: *n,
                                args: None,
                            };
                            call_kind(&call, skills, model, calls)
                        }
                        _ => Some(VarKind::Number),
                    };
                    binds.push((target.text.to_string(), kind.unwrap_or(VarKind::Number)));
                }
                StmtKind::If(c) => scan(&c.body, skills, model, calls, binds),
                StmtKind::While { bind, body } => {
                    if let Some(b) = bind {
                        binds.push((b.text.to_string(), VarKind::Status));
                    }
                    scan(&body.body, skills, model, calls, binds);
                }
                StmtKind::Check { .. }
                | StmtKind::Break { .. }
                | StmtKind::Priority
                | StmtKind::Error => {}
            }
        }
    }
}

fn first_name<'s>(call: &Call<'s>) -> Option<Name<'s>> {
    match call.args.as_ref()?.items.first()? {
        crate::ast::Arg::Positional(e) => match e.kind {
            ExprKind::Name(n) => Some(n),
            _ => None,
        },
        crate::ast::Arg::Setting { .. } => None,
    }
}

fn call_kind(
    call: &Call<'_>,
    skills: &Skills,
    model: &RobotModel,
    calls: &mut Vec<(SkillId, Span)>,
) -> Option<VarKind> {
    if let Some(cmd) = Command::from_name(call.name.text) {
        let forms = cmd.spec().forms;
        let first = forms.first()?.produces;
        if forms.iter().all(|f| f.produces == first) {
            return Some(first);
        }
        // Only sensor and locate have forms that bind different kinds; tell them apart
        // by the shape of their arguments as the full check would.
        let args = call.args.as_ref().map_or(0, |a| a.items.len());
        return Some(match cmd {
            Command::Sensor => {
                let second = call.args.as_ref().and_then(|a| a.items.get(1));
                match second {
                    Some(crate::ast::Arg::Positional(e)) => match e.kind {
                        ExprKind::Name(n) if model.object(n.text).is_some() => VarKind::Position,
                        _ => VarKind::Reading,
                    },
                    _ => VarKind::Reading,
                }
            }
            Command::Locate if args == 1 => VarKind::Reading,
            _ => first,
        });
    }
    let id = skills.find(call.name.text)?;
    calls.push((id, call.name.span));
    Some(VarKind::Status)
}
