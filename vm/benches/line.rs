//! Joining an interactive line to a live module, against the size of the program:
//! `ModuleBuilder::extending` + one statement + `finish_fragment` + `Module::append`
//! (the VM's share of `compiler/benches/line.rs`), and the in-place `Vm::add_line`.
//! Run with `cargo bench -p ilmr-vm --bench line`.

use divan::{Bencher, black_box};
use ilmr_hal::{Limits, ScriptedRobot};
use ilmr_stdlib::{Command, VarKind};
use ilmr_vm::bytecode::{Arg, BlockId, Instr, Op};
use ilmr_vm::{Config, Module, ModuleBuilder, SimClock, TraceLevel, Vm};

fn main() {
    divan::main();
}

const SIZES: [usize; 3] = [100, 10_000, 100_000];

/// A program of `n` statements `v<i> = sensor(battery)` in blocks of ten.
fn program(n: usize) -> Module {
    let mut b = ModuleBuilder::new();
    let file = b.file("big.ilmr").expect("file");
    let battery = b.name("battery").expect("name");
    let mut blocks = Vec::new();
    let mut code = Vec::new();
    for i in 0..n {
        let text = format!("v{i}=sensor(battery)");
        let s = b.stmt(file, i as u32 + 1, (0, 0), &text).expect("stmt");
        let v = b.global(&format!("v{i}"), VarKind::Reading).expect("var");
        let args = b.args(&[Arg::Word(battery)]).expect("args");
        code.push(Instr::new(
            Op::Issue {
                command: Command::Sensor,
                args,
                bind: Some(v),
            },
            s,
        ));
        if code.len() == 10 {
            blocks.push(b.block(&code).expect("block"));
            code.clear();
        }
    }
    let main = b.declare_unit("task", false).expect("unit");
    b.define_unit(main, &blocks);
    b.set_main(main);
    b.finish().expect("valid")
}

/// The lowering's share of `speed(0.2)` into `b`.
fn line(b: &mut ModuleBuilder) -> Vec<BlockId> {
    let file = b.file("<line>").expect("file");
    let s = b.stmt(file, 1, (0, 10), "speed(0.2)").expect("stmt");
    let e = b.num(0.2).expect("num");
    let args = b.args(&[Arg::Num(e)]).expect("args");
    let op = Op::Issue {
        command: Command::Speed,
        args,
        bind: None,
    };
    vec![b.block(&[Instr::new(op, s)]).expect("block")]
}

fn vm(n: usize) -> Vm<ScriptedRobot, SimClock> {
    let cfg = Config {
        trace: TraceLevel::Off,
        ..Config::default()
    };
    Vm::new(
        program(n),
        ScriptedRobot::new(Limits::default()),
        SimClock,
        cfg,
    )
    .expect("valid")
}

#[divan::bench(args = SIZES, sample_count = 20)]
fn extending_and_add_block(bencher: Bencher, n: usize) {
    bencher.with_inputs(|| vm(n)).bench_local_values(|mut vm| {
        let mut b = ModuleBuilder::extending(vm.module());
        let start = line(&mut b);
        let fragment = b.finish_fragment(&start).expect("valid line");
        vm.add_block(black_box(&fragment)).expect("joins");
        vm
    });
}

#[divan::bench(args = SIZES, sample_count = 20)]
fn add_line_in_place(bencher: Bencher, n: usize) {
    bencher.with_inputs(|| vm(n)).bench_local_values(|mut vm| {
        vm.add_line(|b| Ok::<_, ()>(line(b))).expect("joins");
        vm
    });
}
