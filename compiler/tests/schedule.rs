//! The schedule the concurrency lens shows (`check::schedule`): each statement's start
//! read from the same walk as the actuator ownership check (W0905).

use ilmr_compiler::check::schedule::{Moment, Start, schedule};
use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::diagnostic::FileId;
use ilmr_model::RobotModel;

/// Each statement's line (from 1) with its moment, lines standing for spans.
fn moments(files: &[(&str, &str)]) -> Vec<(u32, String)> {
    let sources: Vec<Source> = files.iter().map(|(p, t)| Source::new(*p, *t)).collect();
    let model = RobotModel::builtin("moro").unwrap();
    let analysis = analyze(&sources, &model);
    let text = files[0].1;
    let line =
        |span: ilmr_compiler::Span| text[..span.start as usize].matches('\n').count() as u32 + 1;
    schedule(&analysis, &model, FileId(0))
        .into_iter()
        .map(
            |Moment {
                 span,
                 start,
                 first,
                 queued_after,
             }| {
                let start = match start {
                    Start::Unit {
                        skill,
                        block,
                        blocks,
                    } => format!("unit(skill={skill}) {block}/{blocks}"),
                    Start::HeldBy { by } => format!("held by {}", line(by)),
                    Start::Guard {
                        guard,
                        block,
                        blocks,
                    } => format!("guard {} {block}/{blocks}", line(guard)),
                    Start::Loop {
                        guard,
                        block,
                        blocks,
                    } => format!("loop {} {block}/{blocks}", line(guard)),
                };
                let queued =
                    queued_after.map_or(String::new(), |q| format!(", queued after {}", line(q)));
                let first = if first { ", first" } else { "" };
                (line(span), format!("{start}{first}{queued}"))
            },
        )
        .collect()
}

#[test]
fn blocks_waits_guards_loops_and_the_movement_queue() {
    let task = "\
m = goahead(2)
turn(left)
wait(m)
gotoxy(1,1)

d = sensor(battery)
if(d < 10)
speed(0.2)
endif
n = 0
while(n < 3)
n = n + 1
wait(1)
endwhile
";
    let got = moments(&[("task.ilmr", task)]);
    let want: Vec<(u32, String)> = vec![
        (1, "unit(skill=false) 1/2, first".into()),
        (2, "unit(skill=false) 1/2, queued after 1".into()),
        (3, "unit(skill=false) 1/2".into()),
        // `m` has ended, but `turn` may still hold the reservation.
        (4, "held by 3, first, queued after 2".into()),
        (6, "unit(skill=false) 2/2, first".into()),
        (7, "unit(skill=false) 2/2".into()),
        (8, "guard 7 1/1, first".into()),
        (10, "unit(skill=false) 2/2".into()),
        (11, "unit(skill=false) 2/2".into()),
        (12, "loop 11 1/1, first".into()),
        (13, "loop 11 1/1".into()),
    ];
    assert_eq!(got, want);
}

#[test]
fn a_wait_on_the_last_movement_empties_the_queue() {
    let got = moments(&[(
        "task.ilmr",
        "a = turn(left)\nwait(a)\ngoahead(1)\nturn(right)\n",
    )]);
    assert_eq!(
        got,
        vec![
            (1, "unit(skill=false) 1/1, first".to_string()),
            (2, "unit(skill=false) 1/1".to_string()),
            (3, "held by 2, first".to_string()),
            (4, "held by 2, queued after 3".to_string()),
        ]
    );
}

#[test]
fn a_holding_skill_call_holds_its_caller_and_a_skill_starts_when_called() {
    let task = "\
Takeoff
goahead(1)
";
    let skills = "\
Takeoff:
init()
speed(0.3)
";
    let got = moments(&[("task.ilmr", task), ("skills.ilms", skills)]);
    assert_eq!(
        got,
        vec![
            (1, "unit(skill=false) 1/1, first".to_string()),
            (2, "held by 1, first".to_string()),
        ]
    );
    // The skill's own file: its blocks start when it is called.
    let model = RobotModel::builtin("moro").unwrap();
    let sources = vec![
        Source::new("task.ilmr", task),
        Source::new("skills.ilms", skills),
    ];
    let analysis = analyze(&sources, &model);
    let inside = schedule(&analysis, &model, FileId(1));
    assert_eq!(inside.len(), 2);
    assert!(matches!(
        inside[0].start,
        Start::Unit {
            skill: true,
            block: 1,
            blocks: 1
        }
    ));
    assert!(matches!(inside[1].start, Start::HeldBy { .. }));
}

#[test]
fn nothing_inside_check_and_no_file_out_of_range() {
    let task = "check\ngoahead(1)\ncheckend\n";
    let got = moments(&[("task.ilmr", task)]);
    assert_eq!(got, vec![(1, "unit(skill=false) 1/1, first".to_string())]);
    let model = RobotModel::builtin("moro").unwrap();
    let sources = vec![Source::new("task.ilmr", task)];
    let analysis = analyze(&sources, &model);
    assert!(schedule(&analysis, &model, FileId(99)).is_empty());
}
