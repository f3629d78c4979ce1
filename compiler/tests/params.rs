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

/// A line joining a running task may call a parameterized skill with arguments the
/// task never gave, given the skill files (`lower_line_with`): the new specialization
/// joins as a unit of its own, one the module has is called where it is, and a bad
/// argument gets the diagnostic a task file gets. Without the files the module alone
/// knows no `Corner` (E0301).
#[test]
fn a_line_specializes_a_skill_of_the_library() {
    use ilmr_compiler::lower::{LineOptions, lower_line_warned, lower_line_with};
    use ilmr_vm::ModuleBuilder;

    let model = RobotModel::builtin("moro").unwrap();
    let live = module("Corner(1.5, left)\n", CORNER);
    let library = [Source::library("skills.ilms", CORNER)];
    let line = |text: &str| {
        let mut b = ModuleBuilder::extending(&live);
        let mut warnings = Vec::new();
        let options = LineOptions::default();
        lower_line_with(text, &mut b, &model, options, Some(&library), &mut warnings)
            .map(|start| (b.finish_fragment(&start).expect("a fragment"), warnings))
    };

    let (fragment, warnings) = line("Twice(2)").expect("Twice joins");
    assert!(warnings.is_empty(), "{warnings:?}");
    let units: Vec<&str> = fragment
        .added
        .units
        .iter()
        .map(|u| u.name.as_str())
        .collect();
    assert_eq!(units, ["Twice(2)", "Corner(2,right)", "Corner(2,left)"]);
    let mut joined = live.clone();
    joined.append(&fragment).unwrap();
    let text = disassemble(&joined);
    assert!(text.contains("CALL      Twice(2)"), "{text}");
    assert!(text.contains("ISSUE     goahead 2 => m"), "{text}");

    let (fragment, _) = line("Corner(1.5, left)").expect("the task's own joins");
    assert!(
        fragment.added.units.is_empty(),
        "{:?}",
        fragment.added.units
    );

    let in_a_file = |call: &str| {
        let sources = vec![
            Source::new("task.ilmr", format!("{call}\n")),
            Source::library("skills.ilms", CORNER),
        ];
        analyze(&sources, &model).diagnostics
    };
    for call in ["Corner(2, up)", "Corner(2)", "Twice(left)"] {
        let Err(said) = line(call) else {
            panic!("{call} joined");
        };
        let file: Vec<_> = in_a_file(call)
            .into_iter()
            .filter(|d| d.is_error())
            .collect();
        assert!(!file.is_empty(), "{call}");
        assert_eq!(said, file, "{call}");
    }

    let mut b = ModuleBuilder::extending(&live);
    let unknown = lower_line_warned(
        "Corner(2, right)",
        &mut b,
        &model,
        LineOptions::default(),
        &mut Vec::new(),
    );
    assert!(unknown.is_err_and(|d| d[0].code.as_str() == "E0301"));
}
