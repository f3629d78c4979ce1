//! Instruction profile of interactive lines: `valgrind --tool=callgrind` on this.
use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::lower::{LineOptions, lower, lower_line_into};
use ilmr_vm::bytecode::ModuleBuilder;
fn main() {
    let model = ilmr_model::RobotModel::builtin("workpartner").unwrap();
    let sources = [
        Source::new("t.ilmr", include_str!("../../examples/fetch_boxes.ilmr")),
        Source::library("b.ilms", include_str!("../../examples/skills/boxes.ilms")),
    ];
    let analysis = analyze(&sources, &model);
    let module = lower(&analysis, &model, ilmr_compiler::FileId(0)).unwrap();
    let mut b = ModuleBuilder::extending(&module);
    for _ in 0..1000 {
        lower_line_into("speed(0.2)", &mut b, &model, LineOptions::default()).unwrap();
    }
}
