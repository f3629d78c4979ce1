//! Compact frames (`vm/src/runtime/frame.rs`) against the tree of nodes they stand
//! for: random programs of blocks that compute and sleep, mixed with guards, waits on
//! variables, `break(pattern)`, a bare `break` and small budgets, run with
//! `Config::frames` on and off. The traces must be byte for byte the same, and after
//! every tick so must be what a runner sees (`activity`, `live`, `live_statements`).

mod common;

use common::{Asm, X, config, robot, trace, vm};
use ilmr_vm::bytecode::{BlockId, ExprOp, Instr, Op};
use ilmr_vm::{Config, TraceLevel};

/// xorshift64*: seeded, so a failing seed is reproduced by its number.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn pick<'a>(&mut self, of: &[&'a str]) -> &'a str {
        of[self.below(of.len() as u64) as usize]
    }
}

const VARS: [&str; 4] = ["a", "b", "c", "d"];

/// `VARS` with each suffix from 0 to `copies`: every variable blocks of one shape may
/// hold.
fn copies_of_vars(copies: u64) -> Vec<String> {
    (0..copies)
        .flat_map(|i| VARS.iter().map(move |v| format!("{v}{i}")))
        .collect()
}

/// What tree and frames must agree on after every tick: what runs, what has ended, and
/// the variables `names`.
fn state<N: AsRef<str>>(
    v: &common::TestVm,
    names: &[N],
) -> impl PartialEq + std::fmt::Debug + use<N> {
    let vars: Vec<_> = names.iter().map(|n| v.var(n.as_ref())).collect();
    (
        v.activity(),
        v.live(),
        v.live_statements(),
        v.finished(),
        format!("{vars:?}"),
    )
}

/// `module` run with the trace off on the tree and on frames for up to `ticks` ticks,
/// the two asserted to agree on [`state`] after every tick.
fn tree_and_frames_off(
    module: ilmr_vm::Module,
    budget: u32,
    names: &[String],
    ticks: u32,
    seed: u64,
) -> (common::TestVm, common::TestVm) {
    let cfg = |frames| Config {
        budget_ops: budget,
        frames,
        trace: TraceLevel::Off,
        ..config()
    };
    let mut tree = vm(module.clone(), robot(), cfg(false));
    let mut flat = vm(module, robot(), cfg(true));
    let what = |v: &common::TestVm| state(v, names);
    for tick in 0..ticks {
        if tree.finished() && flat.finished() {
            break;
        }
        tree.tick();
        flat.tick();
        assert_eq!(what(&tree), what(&flat), "seed {seed}, tick {tick}");
    }
    (tree, flat)
}

/// A number from the environment (`FRAMES_SEEDS`, `FRAMES_FROM`), to run more seeds
/// or one.
fn env_or(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

struct Gen {
    rng: Rng,
    /// Distinct statement texts, so that break patterns name what they mean to.
    n: u32,
    /// Appended to every variable's name: blocks of one shape with variables of
    /// their own.
    suffix: String,
}

impl Gen {
    /// Ops per tick: a third of programs run out of budget within a tick (2 up to
    /// `2 + tight`), the rest never do.
    fn budget(&mut self, tight: u64) -> u32 {
        match self.rng.below(3) {
            0 => 2 + self.rng.below(tight) as u32,
            _ => 200_000,
        }
    }

    /// One of [`VARS`], with the suffix.
    fn var(&mut self) -> String {
        format!("{}{}", self.rng.pick(&VARS), self.suffix)
    }

    fn tag(&mut self) -> u32 {
        self.n += 1;
        self.n
    }

    /// A statement that only computes or sleeps.
    fn simple(&mut self, a: &mut Asm) -> Instr {
        let (v, w) = (self.var(), self.var());
        let (v, w) = (v.as_str(), w.as_str());
        let t = self.tag();
        match self.rng.below(8) {
            0 => a.assign(
                &format!("{v}={v}+1 #{t};"),
                v,
                &[X::V(v), X::N(1.0), X::Op(ExprOp::Add)],
            ),
            1 => a.assign(
                &format!("{v}={w}*2 #{t};"),
                v,
                &[X::V(w), X::N(2.0), X::Op(ExprOp::Mul)],
            ),
            2 => a.assign(
                &format!("{v}=({v}+{w})/{w} #{t};"),
                v,
                &[
                    X::V(v),
                    X::V(w),
                    X::Op(ExprOp::Add),
                    X::V(w),
                    X::Op(ExprOp::Div),
                ],
            ),
            3 => a.assign(&format!("{v}=0 #{t};"), v, &[X::N(0.0)]),
            // A subtraction, which the trace-off path runs with its operands inline.
            7 => a.assign(
                &format!("{v}={w}-3 #{t};"),
                v,
                &[X::V(w), X::N(3.0), X::Op(ExprOp::Sub)],
            ),
            4 => a.wait(&format!("wait(0.01) #{t};"), 0.01),
            5 => a.wait(&format!("wait(0.03) #{t};"), 0.03),
            _ => a.wait_bound(&format!("z{t}=wait(0.02)"), 0.02, &format!("z{t}")),
        }
    }

    /// A frame-shaped block: simple statements, then perhaps a loop of depth `depth`.
    fn frame_block(&mut self, a: &mut Asm, depth: u32) -> Vec<Instr> {
        let mut code: Vec<Instr> = (0..self.rng.below(3)).map(|_| self.simple(a)).collect();
        if depth > 0 && self.rng.below(4) != 0 {
            let (v, w) = (self.var(), self.var());
            let (v, w) = (v.as_str(), w.as_str());
            let k = 2 + self.rng.below(8) as i32;
            let t = self.tag();
            let bind = (self.rng.below(3) == 0).then(|| format!("l{t}"));
            let (text, cond): (String, Vec<X>) = if self.rng.below(3) == 0 {
                (
                    format!("while({v}+{w}<{k}) #{t};"),
                    vec![
                        X::V(v),
                        X::V(w),
                        X::Op(ExprOp::Add),
                        X::N(f64::from(k)),
                        X::Op(ExprOp::Lt),
                    ],
                )
            } else {
                (
                    format!("while({v}<{k}) #{t};"),
                    vec![X::V(v), X::N(f64::from(k)), X::Op(ExprOp::Lt)],
                )
            };
            let cond: Vec<X> = cond;
            let text = match &bind {
                Some(b) => format!("{b}={text}"),
                None => text,
            };
            let instr = a.while_(&text, &cond, bind.as_deref(), |a| {
                let t = self.tag();
                let step = a.assign(
                    &format!("{v}={v}+1 #{t};"),
                    v,
                    &[X::V(v), X::N(1.0), X::Op(ExprOp::Add)],
                );
                let mut body = vec![step];
                body.extend(self.frame_block(a, depth - 1));
                body
            });
            code.push(instr);
        }
        code
    }

    /// A block that keeps the tree: a guard, a wait on a variable, a break.
    fn other_block(&mut self, a: &mut Asm) -> Vec<Instr> {
        let mut code = vec![a.wait(&format!("wait(0.05) #{};", self.tag()), 0.05)];
        let v = self.var();
        let d = format!("d{}", self.suffix);
        let t = self.tag();
        match self.rng.below(8) {
            5 => code.push(a.op(&format!("break #{t};"), Op::BreakAll)),
            6 => {
                // `priority = highest` must come first in its block.
                code.insert(0, a.op(&format!("priority=highest #{t};"), Op::Priority));
            }
            7 => {
                // A skill of two frame-shaped blocks: the first runs in line (the
                // tree), the second starts as a strand of its own (a frame).
                let skill = a.skill(&format!("Skill{t}"));
                let first = self.frame_block(a, 1);
                let b1 = a.block(first);
                a.blank();
                let second = self.frame_block(a, 2);
                let b2 = a.block(second);
                a.define(skill, &[b1, b2]);
                let bind = format!("s{t}");
                code.push(a.call(&format!("{bind}=Skill{t} #{t};"), skill, Some(&bind)));
            }
            0 => {
                let k = self.rng.below(6) as f64;
                let g = a.if_(
                    &format!("if({v}>{k}) #{t};"),
                    &[X::V(&v), X::N(k), X::Op(ExprOp::Gt)],
                    |a| {
                        vec![a.assign(
                            &format!("{d}={d}+10 #{t};"),
                            &d,
                            &[X::V(&d), X::N(10.0), X::Op(ExprOp::Add)],
                        )]
                    },
                );
                code.push(g);
            }
            1..=3 => {
                // One statement by its tag: a pattern that ends what several frames
                // stand for ends them in the frames' order (docs/performance.md).
                let k = 1 + self.rng.below(u64::from(self.n));
                code.push(a.brk(&format!("break(#{k};) #{t};"), &format!("#{k};")));
            }
            _ => {
                let w = self.var();
                code.push(a.wait_var(&format!("wait({w}) #{t};"), &w));
            }
        }
        // A loop in a block that keeps the tree: its body may be a frame, parked
        // under the tree's `while` between iterations.
        if self.rng.below(2) == 0 {
            code.extend(self.frame_block(a, 2));
        }
        code
    }
}

fn program(seed: u64) -> (ilmr_vm::Module, u32) {
    let mut g = Gen {
        rng: Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1),
        n: 0,
        suffix: String::new(),
    };
    let mut a = Asm::new();
    let mut blocks: Vec<BlockId> = Vec::new();
    for _ in 0..1 + g.rng.below(5) {
        let code = if g.rng.below(4) == 0 {
            g.other_block(&mut a)
        } else {
            let depth = 1 + g.rng.below(3) as u32;
            g.frame_block(&mut a, depth)
        };
        if !blocks.is_empty() {
            a.blank();
        }
        blocks.push(a.block(code));
    }
    let budget = g.budget(20);
    (a.task(&blocks), budget)
}

#[test]
fn frames_trace_byte_for_byte_as_the_tree() {
    let mut framed = 0;
    let seeds: u64 = env_or("FRAMES_SEEDS", 150);
    let from: u64 = env_or("FRAMES_FROM", 0);
    for seed in from..seeds {
        let (module, budget) = program(seed);
        let cfg = |frames| Config {
            budget_ops: budget,
            frames,
            ..config()
        };
        // FRAMES_FROM=N FRAMES_SEEDS=N+1 FRAMES_VERBOSE=1: one program, listed.
        if std::env::var_os("FRAMES_VERBOSE").is_some() {
            eprintln!("seed {seed}\n{}", ilmr_vm::bytecode::disassemble(&module));
        }
        let mut tree = vm(module.clone(), robot(), cfg(false));
        let mut flat = vm(module.clone(), robot(), cfg(true));
        // With the trace off a frame wakes on a shorter path: the same states.
        let quiet = |frames| Config {
            trace: TraceLevel::Off,
            ..cfg(frames)
        };
        let mut tree_off = vm(module.clone(), robot(), quiet(false));
        let mut flat_off = vm(module, robot(), quiet(true));
        let what = |v: &common::TestVm| state(v, &VARS);
        for tick in 0..200 {
            if tree.finished() && flat.finished() {
                break;
            }
            for v in [&mut tree, &mut flat, &mut tree_off, &mut flat_off] {
                v.tick();
            }
            assert_eq!(what(&tree), what(&flat), "seed {seed}, tick {tick}");
            assert_eq!(what(&tree), what(&tree_off), "seed {seed}, tick {tick}");
            assert_eq!(what(&tree_off), what(&flat_off), "seed {seed}, tick {tick}");
        }
        assert_eq!(trace(&tree), trace(&flat), "seed {seed}");
        framed += usize::from(flat.footprint() != tree.footprint());
    }
    assert!(framed > 40, "only {framed} programs ran frames");
}

/// Blocks of one shape, each with variables of its own (`a0`, `a1`, ...): their
/// frames share one program and address their variables from a base. Guards, waits
/// on variables and breaks of the other blocks read and end them.
fn cloned_program(seed: u64) -> (ilmr_vm::Module, u32, Vec<String>) {
    let mut g = Gen {
        rng: Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1),
        n: 0,
        suffix: String::new(),
    };
    let mut a = Asm::new();
    let mut blocks: Vec<BlockId> = Vec::new();
    let clones = 2 + g.rng.below(5);
    let depth = 1 + g.rng.below(2) as u32;
    let template = g.rng.next() | 1;
    for i in 0..clones {
        g.suffix = i.to_string();
        g.rng = Rng(template);
        let code = g.frame_block(&mut a, depth);
        if !blocks.is_empty() {
            a.blank();
        }
        blocks.push(a.block(code));
    }
    g.rng = Rng(template.rotate_left(17) | 1);
    for _ in 0..g.rng.below(3) {
        g.suffix = g.rng.below(clones).to_string();
        let code = g.other_block(&mut a);
        a.blank();
        blocks.push(a.block(code));
    }
    let budget = g.budget(20);
    let names = copies_of_vars(clones);
    (a.task(&blocks), budget, names)
}

#[test]
fn blocks_of_one_shape_run_as_the_tree() {
    let seeds: u64 = env_or("FRAMES_SEEDS", 60);
    let mut framed = 0;
    for seed in 0..seeds {
        let (module, budget, names) = cloned_program(seed);
        let cfg = |frames, trace| Config {
            budget_ops: budget,
            frames,
            trace,
            ..config()
        };
        let full = config().trace;
        let mut tree = vm(module.clone(), robot(), cfg(false, full));
        let mut flat = vm(module.clone(), robot(), cfg(true, full));
        let mut tree_off = vm(module.clone(), robot(), cfg(false, TraceLevel::Off));
        let mut flat_off = vm(module, robot(), cfg(true, TraceLevel::Off));
        let what = |v: &common::TestVm| state(v, &names);
        for tick in 0..200 {
            if tree.finished() && flat.finished() {
                break;
            }
            for v in [&mut tree, &mut flat, &mut tree_off, &mut flat_off] {
                v.tick();
            }
            assert_eq!(what(&tree), what(&flat), "seed {seed}, tick {tick}");
            assert_eq!(what(&tree_off), what(&flat_off), "seed {seed}, tick {tick}");
            assert_eq!(what(&tree), what(&tree_off), "seed {seed}, tick {tick}");
        }
        assert_eq!(trace(&tree), trace(&flat), "seed {seed}");
        framed += usize::from(flat.footprint() != tree.footprint());
    }
    assert!(framed > 20, "only {framed} programs ran frames");
}

#[test]
fn a_parked_frame_under_a_tree_loop_ends_with_it() {
    // `clear` keeps the block on the tree; the loop's body is a frame, parked
    // between iterations. A bare `break` ends the loop while its body is parked or
    // queued: the frame ends with it (this once hung in `end_subtree`).
    let program = || {
        let mut a = Asm::new();
        let code = vec![
            a.clear("clear(q)", "q"),
            a.while_(
                "while(x<1000000)",
                &[X::V("x"), X::N(1e6), X::Op(ExprOp::Lt)],
                None,
                |a| vec![a.assign("x=x+1", "x", &[X::V("x"), X::N(1.0), X::Op(ExprOp::Add)])],
            ),
        ];
        let b1 = a.block(code);
        a.blank();
        let code = vec![a.wait("wait(0.05)", 0.05), a.op("break", Op::BreakAll)];
        let b2 = a.block(code);
        a.task(&[b1, b2])
    };
    let cfg = |frames| Config {
        budget_ops: 1_000,
        frames,
        ..config()
    };
    let mut tree = vm(program(), robot(), cfg(false));
    let mut flat = vm(program(), robot(), cfg(true));
    assert!(
        tree.run_for(1.0) && flat.run_for(1.0),
        "the break ends the loop"
    );
    assert_eq!(trace(&tree), trace(&flat));
    assert_eq!(flat.live(), 0);
}

/// Frame-shaped blocks and nothing else, each on variables of its own (`a0`, `a1`,
/// ...), or all on the same: the ready queue of a tick is then
/// often run in one go (`Vm::rounds_fused`), each frame's visits one after the other
/// rather than round by round. Small budgets, loops that end, bound waits and
/// divisions (which the one-go path refuses) mixed in.
fn independent_program(seed: u64) -> (ilmr_vm::Module, u32, Vec<String>) {
    let mut g = Gen {
        rng: Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1),
        n: 0,
        suffix: String::new(),
    };
    let mut a = Asm::new();
    let mut blocks: Vec<BlockId> = Vec::new();
    let count = 1 + g.rng.below(6);
    // Half the programs: every block on the same four variables, which must keep
    // the tree's order.
    let shared = g.rng.below(2) == 0;
    for i in 0..count {
        g.suffix = if shared { "0".into() } else { i.to_string() };
        let depth = 1 + g.rng.below(2) as u32;
        let code = g.frame_block(&mut a, depth);
        if !blocks.is_empty() {
            a.blank();
        }
        blocks.push(a.block(code));
    }
    let budget = g.budget(40);
    let names = copies_of_vars(count);
    (a.task(&blocks), budget, names)
}

#[test]
fn frames_run_in_one_go_as_the_tree() {
    let seeds: u64 = env_or("FRAMES_SEEDS", 150);
    let (mut fused, mut programs) = (0, 0);
    // Frames whose visits of such a round ran as one step along a plan
    // (`Vm::plans_run`), and the programs where some did.
    let (mut planned, mut planned_programs) = (0, 0);
    // Rounds run straight from the wheel's due slot (`Vm::slot_rounds`), and the
    // programs where some were.
    let (mut slot, mut slot_programs) = (0, 0);
    for seed in 0..seeds {
        let (module, budget, names) = independent_program(seed);
        let (tree, flat) = tree_and_frames_off(module, budget, &names, 200, seed);
        assert_eq!(tree.rounds_fused(), 0, "the tree has no frames");
        fused += flat.rounds_fused();
        programs += usize::from(flat.rounds_fused() > 0);
        assert_eq!(tree.plans_run(), 0, "the tree has no frames");
        planned += flat.plans_run();
        planned_programs += usize::from(flat.plans_run() > 0);
        assert_eq!(tree.slot_rounds(), 0, "the tree has no frames");
        slot += flat.slot_rounds();
        slot_programs += usize::from(flat.slot_rounds() > 0);
    }
    assert!(
        slot_programs > 10 && slot > 300,
        "{slot} rounds from the due slot in {slot_programs} programs"
    );
    assert!(
        programs > 20 && fused > 400,
        "{fused} rounds in one go in {programs} programs"
    );
    assert!(
        planned_programs > 10 && planned > 50,
        "{planned} frames run along a plan in {planned_programs} programs"
    );
}

#[test]
fn a_frame_that_reads_what_another_writes_keeps_the_tree_order() {
    // The second block's check reads `a`, which the first block's body writes: in
    // the tree's order the check comes first (a turn of the queue before the body),
    // so at a=4 it still holds and `b` counts once more. Run in one go it would not.
    let program = || {
        let mut a = Asm::new();
        let count = |a: &mut Asm, var: &str, tag: &str| {
            let step = format!("{var}={var}+1 #{tag}");
            vec![a.while_(
                &format!("while(a<5) #{tag}"),
                &[X::V("a"), X::N(5.0), X::Op(ExprOp::Lt)],
                None,
                |a| {
                    vec![
                        a.assign(&step, var, &[X::V(var), X::N(1.0), X::Op(ExprOp::Add)]),
                        a.wait(&format!("wait(0.01) #{tag}"), 0.01),
                    ]
                },
            )]
        };
        let first = count(&mut a, "a", "1");
        let b1 = a.block(first);
        a.blank();
        let second = count(&mut a, "b", "2");
        let b2 = a.block(second);
        a.task(&[b1, b2])
    };
    let cfg = |frames| Config {
        frames,
        trace: TraceLevel::Off,
        ..config()
    };
    let mut tree = vm(program(), robot(), cfg(false));
    let mut flat = vm(program(), robot(), cfg(true));
    for tick in 0..20 {
        tree.tick();
        flat.tick();
        assert_eq!(
            (
                tree.var("a").map(|r| r.value),
                tree.var("b").map(|r| r.value)
            ),
            (
                flat.var("a").map(|r| r.value),
                flat.var("b").map(|r| r.value)
            ),
            "tick {tick}"
        );
    }
    assert_eq!(flat.rounds_fused(), 0, "the two frames share `a`");
    assert_eq!(tree.var("b").map(|r| r.value), Some(5.0));
}

#[test]
fn frames_that_sleep_in_different_turns_keep_the_tree_order() {
    // Woken together, the first frame sleeps again in the third turn of the queue
    // (its body's end, its check, its body) and the second in the first (`b=b+1`
    // and its wait): the tree sets the second's alarm first, and they wake in that
    // order next tick, where a budget that runs out decides which body runs. Run
    // in one go they would be set the other way round.
    let program = || {
        let mut a = Asm::new();
        let first = vec![a.while_(
            "while(a<100) #1",
            &[X::V("a"), X::N(100.0), X::Op(ExprOp::Lt)],
            None,
            |a| {
                vec![
                    a.assign("a=a+1 #1", "a", &[X::V("a"), X::N(1.0), X::Op(ExprOp::Add)]),
                    a.wait("wait(0.01) #1", 0.01),
                ]
            },
        )];
        let b1 = a.block(first);
        a.blank();
        let second = vec![a.while_(
            "while(b<100) #2",
            &[X::V("b"), X::N(100.0), X::Op(ExprOp::Lt)],
            None,
            |a| {
                vec![
                    a.wait("wait(0.01) #2", 0.01),
                    a.assign("b=b+1 #2", "b", &[X::V("b"), X::N(1.0), X::Op(ExprOp::Add)]),
                    a.wait("wait(0.01) #3", 0.01),
                    a.assign(
                        "c=(c+b)/b #2",
                        "c",
                        &[
                            X::V("c"),
                            X::V("b"),
                            X::Op(ExprOp::Add),
                            X::V("b"),
                            X::Op(ExprOp::Div),
                        ],
                    ),
                ]
            },
        )];
        let b2 = a.block(second);
        a.task(&[b1, b2])
    };
    for budget in 12..=26 {
        let cfg = |frames| Config {
            frames,
            budget_ops: budget,
            trace: TraceLevel::Off,
            ..config()
        };
        let mut tree = vm(program(), robot(), cfg(false));
        let mut flat = vm(program(), robot(), cfg(true));
        let values = |v: &common::TestVm| ["a", "b", "c"].map(|n| v.var(n).map(|r| r.value));
        for tick in 0..40 {
            tree.tick();
            flat.tick();
            assert_eq!(values(&tree), values(&flat), "budget {budget}, tick {tick}");
        }
    }
}

/// Counting blocks as the benchmark has them (`cN=0`, `while(cN<L)`, `cN=cN+1`,
/// `wait(w)`), each on a variable of its own, of several bounds and wait times:
/// rounds run straight from the wheel's due slot (`Vm::slot_rounds`), with the
/// new alarms written back into the due slot's buffer for the first tick they
/// fall on and set one by one for the others, and a loop that ends sending its
/// tick back to the queue. Tree against frames with the trace off, small budgets
/// in a third of the programs: the same variables, `activity`, `live` and
/// `live_statements` after every tick.
///
/// `shared`: every block of the first one's bound and wait, so that many frames
/// sit at one pc (the one pass's batches).
fn counting_program(seed: u64, shared: bool) -> (ilmr_vm::Module, u32, Vec<String>) {
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let mut a = Asm::new();
    let mut blocks = Vec::new();
    let mut names = Vec::new();
    let count = 1 + rng.below(8);
    let mut first = None;
    for i in 0..count {
        let c = format!("c{i}");
        let bound = (1 + rng.below(6)) as f64;
        let wait = [0.01, 0.01, 0.02, 0.03][rng.below(4) as usize];
        let (bound, wait) = match first {
            Some(bw) if shared => bw,
            _ => (bound, wait),
        };
        first = first.or(Some((bound, wait)));
        let mut code = Vec::new();
        if rng.below(4) == 0 && !shared {
            code.push(a.wait(&format!("wait(0.02) #{i}"), 0.02));
        }
        code.push(a.assign(&format!("{c}=0 #{i}"), &c, &[X::N(0.0)]));
        code.push(a.while_(
            &format!("while({c}<{bound}) #{i}"),
            &[X::V(&c), X::N(bound), X::Op(ExprOp::Lt)],
            None,
            |a| {
                vec![
                    a.assign(
                        &format!("{c}={c}+1 #{i}"),
                        &c,
                        &[X::V(&c), X::N(1.0), X::Op(ExprOp::Add)],
                    ),
                    a.wait(&format!("wait({wait}) #{i}"), wait),
                ]
            },
        ));
        if i > 0 {
            a.blank();
        }
        blocks.push(a.block(code));
        names.push(c);
    }
    let budget = match rng.below(3) {
        0 => 2 + rng.below(40) as u32,
        _ => 200_000,
    };
    // In a third of the programs a block of the tree guards one of the counters
    // (`if(cJ>K)`): a frame that writes a variable something hears is not run
    // in one go, by the look ahead or by the one pass's batches. The guard moves
    // another counter on by 2, so that frames at one pc reach their bound on
    // different ticks.
    if rng.below(3) == 0 {
        let j = rng.below(count);
        let k = rng.below(4) as f64;
        let c = format!("c{j}");
        let m = format!("c{}", rng.below(count));
        let guard = a.if_(
            &format!("if({c}>{k}) #g"),
            &[X::V(&c), X::N(k), X::Op(ExprOp::Gt)],
            |a| {
                vec![
                    a.assign(
                        "d=d+10 #g",
                        "d",
                        &[X::V("d"), X::N(10.0), X::Op(ExprOp::Add)],
                    ),
                    a.assign(
                        &format!("{m}={m}+2 #g"),
                        &m,
                        &[X::V(&m), X::N(2.0), X::Op(ExprOp::Add)],
                    ),
                ]
            },
        );
        a.blank();
        blocks.push(a.block(vec![guard]));
        names.push("d".to_string());
    }
    (a.task(&blocks), budget, names)
}

#[test]
fn counting_blocks_run_from_the_due_slot_as_the_tree() {
    let seeds: u64 = env_or("FRAMES_SEEDS", 150);
    let (mut slot, mut programs) = (0, 0);
    for seed in 0..seeds {
        let (module, budget, names) = counting_program(seed, false);
        let (_, flat) = tree_and_frames_off(module, budget, &names, 60, seed);
        slot += flat.slot_rounds();
        programs += usize::from(flat.slot_rounds() > 0);
    }
    assert!(
        programs > seeds as usize / 2 && slot > 2 * seeds,
        "{slot} rounds from the due slot in {programs} programs"
    );
}

#[test]
fn counting_blocks_run_in_one_pass_or_taken_back_as_the_tree() {
    // The due slot's round in one pass (`Vm::slot_once`), where every woken frame
    // goes along its plan to one tick; where a later frame cannot (a loop that
    // ends, a wait of another length, a budget too small), what the frames before
    // it did taken back (`Vm::slot_undone`) and the round run by the look ahead.
    // Half the programs' blocks share one shape, so that frames at one pc run in
    // batches. Tree against frames after every tick, as above.
    let seeds: u64 = env_or("FRAMES_SEEDS", 150);
    let (mut once, mut undone, mut both) = (0, 0, 0);
    for seed in 0..seeds {
        for shared in [false, true] {
            let (module, budget, names) = counting_program(seed, shared);
            let (_, flat) = tree_and_frames_off(module, budget, &names, 60, seed);
            once += flat.slot_once();
            undone += flat.slot_undone();
            both += usize::from(flat.slot_once() > 0 && flat.slot_undone() > 0);
        }
    }
    assert!(
        once > seeds && undone > seeds / 4 && both > seeds as usize / 10,
        "{once} rounds in one pass, {undone} taken back, {both} programs with both"
    );
}

#[test]
fn frames_whose_variables_overlap_keep_the_tree_order() {
    // The second block's variables start below the first's (`a` is declared before
    // `b`) and its check reads `b`, which the first block (counting `b` to 100)
    // writes right after its wait, in its first visit of a tick: in the tree's
    // order the second check comes a turn later and sees b=5, so `a` stops at 5.
    // A look ahead that found the second check true (b=4) before the first frame
    // ran would count `a` to 6. The frames' variables do not lie one above the
    // other along the due alarms, so neither the queue's round nor the due slot's
    // runs them in one go (once the second has ended, the first alone does).
    let program = || {
        let mut a = Asm::new();
        a.var("a", ilmr_stdlib::VarKind::Number);
        a.var("b", ilmr_stdlib::VarKind::Number);
        let count = |a: &mut Asm, var: &str, tag: &str, wait_first: bool| {
            let step = format!("{var}={var}+1 #{tag}");
            let bound = if wait_first { 100.0 } else { 5.0 };
            vec![a.while_(
                &format!("while(b<{bound}) #{tag}"),
                &[X::V("b"), X::N(bound), X::Op(ExprOp::Lt)],
                None,
                |a| {
                    let step = a.assign(&step, var, &[X::V(var), X::N(1.0), X::Op(ExprOp::Add)]);
                    let wait = a.wait(&format!("wait(0.01) #{tag}"), 0.01);
                    match wait_first {
                        true => vec![wait, step],
                        false => vec![step, wait],
                    }
                },
            )]
        };
        let first = count(&mut a, "b", "1", true);
        let b1 = a.block(first);
        a.blank();
        let second = count(&mut a, "a", "2", false);
        let b2 = a.block(second);
        a.task(&[b1, b2])
    };
    let cfg = |frames| Config {
        frames,
        trace: TraceLevel::Off,
        ..config()
    };
    let mut tree = vm(program(), robot(), cfg(false));
    let mut flat = vm(program(), robot(), cfg(true));
    let values = |v: &common::TestVm| ["a", "b"].map(|n| v.var(n).map(|r| r.value));
    for tick in 0..20 {
        tree.tick();
        flat.tick();
        assert_eq!(values(&tree), values(&flat), "tick {tick}");
    }
    assert_eq!(tree.var("a").map(|r| r.value), Some(5.0));
}
