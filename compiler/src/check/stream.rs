//! `ilmrc check` (`Detail::Diagnostics`) on task files read block by block: each
//! top-level block of a task is walked, then seen by W0901, W0903 and W0905, and
//! dropped before the next is parsed, as `luac` compiles one function at a time. The
//! tree of a large task is most of what a check writes to memory (docs/performance.md,
//! sessions 11-14), and the passes after the walk used to read all of it again.
//!
//! What those passes judge only once the whole program is known is gathered as the
//! blocks go: W0901 keeps each loop's condition names with the assignments its block
//! issued before it (`loops::Frozen`), W0903 the paths made and followed
//! (`paths::Paths`), W0905 its records and what it learnt of each skill
//! (`owners::Tally`). The diagnostics are those of the whole-tree check, in the same
//! order: whatever this path cannot reproduce exactly makes it give the file back
//! (`None`), and [`super::analyze_given`] checks as before. It gives up on a task with
//! a skill header, a task file given after a skill file, a diagnostic of the parser, a
//! `break(pattern)` or a statement that never ends in any file (W0701/W0702 and W0904
//! search the whole program), a loop that may starve (W0902 weighs it by the whole
//! program's variables), a call inside a skill that W0905 resolved by name otherwise
//! than the skill's check did, or as many diagnostics as the limit (past it, which are
//! kept depends on the order they come).

use super::*;

/// The top-level blocks each pass meets in turn before the next pass: enough that a
/// pass's code stays in the instruction cache from block to block, few enough that
/// the batch's tree (the corpus's blocks take about 1.5 KB each: 120 MB for the 10x
/// corpus's 83,340 in session 13) stays in the second-level cache for the next pass.
/// 32, 128 and 512 measured alike (docs/performance.md, session 15); 8 gave back half
/// the gain.
const BATCH: usize = 128;

/// The analysis of `sources`, or `None` where the whole-tree check must do it.
pub(super) fn analyze<'s>(
    sources: &'s [Source],
    model: &RobotModel,
    given: &Given,
) -> Option<Analysis<'s>> {
    let detail = Detail::Diagnostics;
    // The task files given first: every pass meets their blocks first, as it would in
    // the whole tree. A file named as a skill file is left to the usual check.
    let lead = sources
        .iter()
        .take_while(|s| !s.library && !s.path.ends_with(".ilms"))
        .count();
    if lead == 0 {
        return None;
    }
    let mut diagnostics = Kept::new();
    let mut files: Vec<FileEntry<'s>> = Vec::with_capacity(sources.len() + 1);
    for s in &sources[..lead] {
        files.push(FileEntry {
            path: &s.path,
            text: &s.text,
            tree: SourceFile {
                kind: FileKind::Task,
                blocks: Box::default(),
                skills: Vec::new(),
                comments: Vec::new(),
                span: Span::new(0, s.text.len()),
            },
            builtin: false,
            library: false,
            break_patterns: false,
            syntax_errors: 0,
            binds: 0,
            seen: parser::Seen::default(),
        });
    }
    let builtins = ilmr_stdlib::skills::BUILTIN_SKILL_FILES
        .iter()
        .map(|b| (b.path, b.source, true, true));
    let rest = sources[lead..]
        .iter()
        .map(|s| (s.path.as_str(), s.text.as_str(), false, s.library));
    for (i, (path, text, builtin, library)) in rest.chain(builtins).enumerate() {
        let file = FileId((lead + i) as u32);
        let (entry, found, past) = FileEntry::parse(path, text, file, builtin, library);
        if !builtin {
            diagnostics.extend(found);
            diagnostics.add_past(past);
        }
        files.push(entry);
    }
    // A task file after a skill file would be walked whole: the usual check does that.
    let task_after = |f: &FileEntry| f.tree.kind == FileKind::Task && !f.library;
    if files
        .iter()
        .any(|f| f.break_patterns || f.seen.never_ending)
        || files[lead..].iter().any(task_after)
    {
        return None;
    }

    let mut skills = skills::Skills::collect(&files, model, &mut diagnostics);
    let mut specials = params::Specials::default();
    let constants = constants::Constants::new(model);
    let names = names::Names::new(&constants, &skills);
    let mut units = Vec::new();
    let mut frozen = loops::Frozen::with_capacity(0);
    let mut paths = paths::Paths::new(&given.paths);
    // Statements that bind are fewer than lines: room for them, written only as they
    // come (untouched room costs no fresh memory).
    let lines: Vec<usize> = sources[..lead].iter().map(|s| lines_in(&s.text)).collect();
    let mut owners = owners::Owners::streaming(&files, &skills, model, lines.iter().sum());
    let mut found = Vec::with_capacity(lead);
    let mut buf = String::new();
    let mut spare = Vec::new();
    for (i, &lines) in lines.iter().enumerate() {
        let file = FileId(i as u32);
        let text = files[i].text;
        let vars = Vars::with_capacity(lines).with_detail(detail);
        let mut unit = Unit::new(file, None, None, vars);
        let mut index = 0;
        let mut batch: Vec<(Block<'s>, bool)> = Vec::with_capacity(BATCH);
        // Each skill the task calls, at one of its calls. The walk's targets of skill
        // calls are W0905's for the batch only (each call's own statement); past the
        // stream only which skills are called matters (the library skills checked),
        // and a table of every call grew with the task (833,000 at 100x).
        let mut called: FxHashMap<SkillId, Span> = FxHashMap::default();
        // Each pass in turn over a batch of blocks, then the batch dropped: the passes
        // in turn over each block ran through more code than the instruction cache
        // holds, for every block (docs/performance.md, session 15). Every pass still
        // meets the blocks in order, and only the walk reports as it goes.
        let mut run = |batch: &mut Vec<(Block<'s>, bool)>| {
            for (block, _) in batch.iter() {
                let mut walker = Walker::new(
                    model,
                    &constants,
                    &names,
                    &skills,
                    &mut unit,
                    &mut diagnostics,
                    detail,
                    &mut specials,
                );
                walker.buf = std::mem::take(&mut buf);
                walker.spare = std::mem::take(&mut spare);
                walker.blocks(std::slice::from_ref(block));
                buf = std::mem::take(&mut walker.buf);
                spare = std::mem::take(&mut walker.spare);
            }
            for (block, _) in batch.iter() {
                if !frozen.block(file, block, &skills) {
                    return false;
                }
            }
            // W0903's scan finds nothing in a block the builder saw no path call in.
            for (block, _) in batch.iter().filter(|(_, paths_seen)| *paths_seen) {
                paths.block(file, block);
            }
            for (block, _) in batch.iter() {
                owners.stream_block(file, index, block, &mut unit.targets);
                index += 1;
            }
            for (at, target) in unit.targets.drain() {
                if let Target::Skill(id) = target {
                    called.entry(id).or_insert(at);
                }
            }
            batch.clear();
            !diagnostics.near_limit()
        };
        let parsed = parser::parse_streamed(text, file, |block, paths_seen| {
            batch.push((block, paths_seen));
            batch.len() < BATCH || run(&mut batch)
        })?;
        if !run(&mut batch) {
            return None;
        }
        unit.targets
            .extend(called.into_iter().map(|(id, at)| (at, Target::Skill(id))));
        found.push((parsed.binds, parsed.seen));
        units.push(unit);
    }
    let tally = owners.into_tally();
    for (entry, (binds, seen)) in files.iter_mut().zip(found) {
        entry.binds = binds;
        entry.seen = seen;
    }
    let special_blocks = check_skills(
        &files,
        &mut skills,
        &mut specials,
        &mut units,
        &mut diagnostics,
        model,
        &constants,
        &names,
        detail,
    );

    breaks::check_patterns(&files, &skills, &mut diagnostics);
    frozen.finish(&files, lead, &skills, &mut diagnostics);
    wakes::check_waits(&files, &mut diagnostics);
    paths.finish(&files, lead, &mut diagnostics);
    let owned = owners::finish_owners(
        tally,
        &files,
        lead,
        &skills,
        &units,
        model,
        &mut diagnostics,
    );
    if !owned {
        return None;
    }
    unused_variables(&files, &units, &mut diagnostics);
    if diagnostics.near_limit() {
        return None;
    }
    Some(Analysis {
        files,
        skills,
        specials: specials.list,
        special_blocks,
        units,
        diagnostics: diagnostics.into_reported(),
    })
}

/// The lines of `text`, counted in runs of 255 bytes whose count fits a byte, which
/// the compiler turns into wide compares: a plain count took 4.7 instructions a byte
/// (7 M on the 1x corpus).
fn lines_in(text: &str) -> usize {
    let runs = text.as_bytes().chunks(255);
    let breaks: usize = runs
        .map(|run| usize::from(run.iter().fold(0u8, |n, &b| n + u8::from(b == b'\n'))))
        .sum();
    breaks + 1
}
