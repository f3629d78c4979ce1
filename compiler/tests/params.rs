//! Skills with parameters are lowered as specializations: each distinct argument list
//! of a call is a skill unit of its own, with the arguments in place of the parameters,
//! and nothing else of the module changes.

use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::diagnostic::FileId;
use ilmr_compiler::lower::lower;
use ilmr_model::RobotModel;
use ilmr_vm::bytecode::{disassemble, file::encode};

const CORNER: &str = "Corner(d, side=left/right):\nspeed(0.3)\nm = goahead(d)\nwait(m)\nturn(side)\n\nTwice(n):\nCorner(n, right)\nCorner(n, left)\n";

fn module(task: &str, skills: &str) -> ilmr_vm::Module {
    let model = RobotModel::builtin("moro").unwrap();
    let sources = vec![
        Source::new("task.ilmr", task),
        Source::new("skills.ilms", skills),
    ];
    let analysis = analyze(&sources, &model);
    assert!(!analysis.has_errors(), "{:?}", analysis.diagnostics);
    lower(&analysis, &model, FileId(0)).expect("lowers")
}

#[test]
fn each_argument_list_is_one_skill_unit_with_the_arguments_in_place() {
    let m = module("Corner(1.5, left)\nTwice(2)\nCorner(1.5, LEFT)\n", CORNER);
    let text = disassemble(&m);
    for unit in [
        "Corner(1.5,left)",
        "Twice(2)",
        "Corner(2,right)",
        "Corner(2,left)",
    ] {
        assert_eq!(
            text.matches(&format!("== skill {unit} ==")).count(),
            1,
            "{unit} once:\n{text}"
        );
    }
    assert_eq!(text.matches("== skill").count(), 4, "{text}");
    for line in [
        "ISSUE     goahead 1.5 => m",
        "ISSUE     turn left",
        "ISSUE     goahead 2 => m",
        "ISSUE     turn right",
        "CALL      Corner(2,right)",
    ] {
        assert!(text.contains(line), "no `{line}` in\n{text}");
    }
}

/// A skill with parameters beside plain skills changes nothing of a task that calls
/// only the plain ones: the module's bytes are those without it.
#[test]
fn plain_skills_lower_byte_identically_beside_one_with_parameters() {
    let plain = "TURN1:\nspeed(-0.4)\nt1=turn(d=90,c=0.25)\nwait(t1)\n";
    let task = "TURN1\ngoahead(1)\n";
    let without = module(task, plain);
    let with = module(task, &format!("{plain}\n{CORNER}"));
    assert_eq!(encode(&without), encode(&with));
}

/// A variable given to a number parameter is read where the skill uses it, as if
/// written there.
#[test]
fn a_variable_argument_is_read_where_the_skill_uses_it() {
    let m = module("dist = 2\nCorner(dist, right)\n", CORNER);
    let text = disassemble(&m);
    assert!(text.contains("== skill Corner(dist,right) =="), "{text}");
    assert!(text.contains("ISSUE     goahead dist.value => m"), "{text}");
}
