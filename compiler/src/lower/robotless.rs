//! `--robot none`: a program that runs without a robot may use control flow,
//! arithmetic, waits and skills, but no command that reaches the robot.

use ilmr_vm::Module;
use ilmr_vm::bytecode::{Instr, Op};

use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::span::Span;

/// The name of what `instr` asks of the robot, if anything: every issued catalogue
/// command (movement, sensors, actuators, and the define commands that set up the next
/// movement or the localisation), and `stop`/`cont`, which act on the drive.
fn robot_use(instr: &Instr) -> Option<&'static str> {
    match instr.op {
        Op::Issue { command, .. } => Some(command.name()),
        Op::Stop => Some("stop"),
        Op::Cont => Some("cont"),
        _ => None,
    }
}

/// One E0407 for every statement of `module` that needs a robot. Statement files are
/// the checker's file numbers (the lowering keeps them).
pub fn robot_uses(module: &Module) -> Vec<Diagnostic> {
    uses_in(module, &module.code, |f| FileId(f.0))
}

pub(crate) fn uses_in(
    module: &Module,
    code: &[Instr],
    file: impl Fn(ilmr_vm::bytecode::FileId) -> FileId,
) -> Vec<Diagnostic> {
    code.iter()
        .filter_map(|i| Some((i, robot_use(i)?)))
        .filter_map(|(i, what)| {
            let stmt = module.stmt(i.stmt)?;
            Some(
                Diagnostic::new(
                    Code::Unsupported,
                    file(stmt.file),
                    Span {
                        start: stmt.span.0,
                        end: stmt.span.1,
                    },
                    format!("`{what}` needs a robot, and this task runs with `--robot none`"),
                )
                .with_label("no robot to run this")
                .with_help("run it with `--robot scripted` or a robot model"),
            )
        })
        .collect()
}
