//! The programs the VM benchmarks tick, shared by `vm.rs` (divan, wall time) and
//! `ticks.rs` (a fixed number of ticks, for instruction counts under callgrind).
//!
//! - `Searches`: every command is a `sensor(scanner,door,forever)` stepped each tick
//!   (the kind of command that costs something every tick).
//! - `Guards`: every command is an `if(t<0)` woken each tick by `t` changing.
//! - `Sleepers`: every command is a `wait(1000)` (costs nothing until it wakes).
//! - `Counting`: every block is `cN=0` / `while(cN<1e9)` / `cN=cN+1` / `wait(0.01)` /
//!   `endwhile` with a variable of its own (issue 14's general path, the workload of
//!   `tools/blocks_vs_lua.sh`): all of them run one shared frame program.

use ilmr_hal::{Limits, ScriptedRobot};
use ilmr_stdlib::{Command, Field, VarKind};
use ilmr_vm::bytecode::{Arg, ExprOp, Instr, Op};
use ilmr_vm::{Config, Module, ModuleBuilder, SimClock, TraceLevel, Vm};

#[derive(Clone, Copy)]
pub enum Shape {
    Searches,
    Guards,
    Sleepers,
    Counting,
}

pub fn module(shape: Shape, n: usize) -> Module {
    let mut b = ModuleBuilder::new();
    let file = b.file("bench.ilmr").expect("file");
    let stmt = |b: &mut ModuleBuilder, text: &str| b.stmt(file, 1, (0, 0), text).expect("stmt");
    let mut blocks = Vec::new();
    let code: Vec<Instr> = match shape {
        Shape::Searches => {
            let s = stmt(&mut b, "sensor(scanner,door,forever)");
            let args = [
                Arg::Word(b.name("scanner").expect("name")),
                Arg::Word(b.name("door").expect("name")),
                Arg::Word(b.name("forever").expect("name")),
            ];
            let args = b.args(&args).expect("args");
            let op = Op::Issue {
                command: Command::Sensor,
                args,
                bind: None,
            };
            vec![Instr::new(op, s); n]
        }
        Shape::Guards => {
            let t = b.global("t", VarKind::Number).expect("var");
            let zero = b.constant(0.0).expect("const");
            let cond = b
                .expr(&[
                    ExprOp::Field(t, Field::Value),
                    ExprOp::Const(zero),
                    ExprOp::Lt,
                ])
                .expect("expr");
            let s = stmt(&mut b, "if(t<0)");
            let body = b.block(&[]).expect("block");
            // The clock: t = t + 1 every tick.
            let one = b.constant(1.0).expect("const");
            let inc = b
                .expr(&[
                    ExprOp::Field(t, Field::Value),
                    ExprOp::Const(one),
                    ExprOp::Add,
                ])
                .expect("expr");
            let tick = b.num(0.01).expect("num");
            let st = stmt(&mut b, "t=t+1");
            let sw = stmt(&mut b, "wait(0.01)");
            let loop_body = b
                .block(&[
                    Instr::new(
                        Op::WaitTime {
                            seconds: tick,
                            bind: None,
                        },
                        sw,
                    ),
                    Instr::new(Op::Assign { var: t, expr: inc }, st),
                ])
                .expect("block");
            let always = b.num(1.0).expect("num");
            let sl = stmt(&mut b, "while(1)");
            let clock = b
                .block(&[Instr::new(
                    Op::While {
                        cond: always,
                        body: loop_body,
                        bind: None,
                    },
                    sl,
                )])
                .expect("block");
            blocks.push(clock);
            vec![
                Instr::new(
                    Op::If {
                        cond,
                        body,
                        bind: None,
                    },
                    s
                );
                n
            ]
        }
        Shape::Sleepers => {
            let s = stmt(&mut b, "wait(1000)");
            let secs = b.num(1000.0).expect("num");
            // Each wait holds its own block, so one block per wait.
            for _ in 0..n {
                let blk = b
                    .block(&[Instr::new(
                        Op::WaitTime {
                            seconds: secs,
                            bind: None,
                        },
                        s,
                    )])
                    .expect("block");
                blocks.push(blk);
            }
            Vec::new()
        }
        Shape::Counting => {
            let (zero, bound, one) = (
                b.constant(0.0).expect("const"),
                b.constant(1e9).expect("const"),
                b.constant(1.0).expect("const"),
            );
            let tick = b.num(0.01).expect("num");
            for i in 0..n {
                let c = b.global(&format!("c{i}"), VarKind::Number).expect("var");
                let set = b.expr(&[ExprOp::Const(zero)]).expect("expr");
                let cond = b
                    .expr(&[
                        ExprOp::Field(c, Field::Value),
                        ExprOp::Const(bound),
                        ExprOp::Lt,
                    ])
                    .expect("expr");
                let inc = b
                    .expr(&[
                        ExprOp::Field(c, Field::Value),
                        ExprOp::Const(one),
                        ExprOp::Add,
                    ])
                    .expect("expr");
                let s0 = stmt(&mut b, &format!("c{i}=0"));
                let sl = stmt(&mut b, &format!("while(c{i}<1e9)"));
                let si = stmt(&mut b, &format!("c{i}=c{i}+1"));
                let sw = stmt(&mut b, "wait(0.01)");
                let body = b
                    .block(&[
                        Instr::new(Op::Assign { var: c, expr: inc }, si),
                        Instr::new(
                            Op::WaitTime {
                                seconds: tick,
                                bind: None,
                            },
                            sw,
                        ),
                    ])
                    .expect("block");
                let blk = b
                    .block(&[
                        Instr::new(Op::Assign { var: c, expr: set }, s0),
                        Instr::new(
                            Op::While {
                                cond,
                                body,
                                bind: None,
                            },
                            sl,
                        ),
                    ])
                    .expect("block");
                blocks.push(blk);
            }
            Vec::new()
        }
    };
    if !code.is_empty() {
        blocks.push(b.block(&code).expect("block"));
    }
    let main = b.declare_unit("task", false).expect("unit");
    b.define_unit(main, &blocks);
    b.set_main(main);
    b.finish().expect("valid")
}

pub fn vm(shape: Shape, n: usize) -> Vm<ScriptedRobot, SimClock> {
    let cfg = Config {
        trace: TraceLevel::Off,
        budget_ops: 50_000_000,
        ..Config::default()
    };
    let mut vm = Vm::new(
        module(shape, n),
        ScriptedRobot::new(Limits::default()),
        SimClock,
        cfg,
    )
    .expect("valid");
    // Issue everything and let the queues settle.
    for _ in 0..3 {
        vm.tick();
    }
    assert!(vm.live() >= n, "{} live of {n}", vm.live());
    vm
}
