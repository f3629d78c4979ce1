//! The task generator (tests/support/taskgen.rs): every generated task checks with no
//! diagnostic on the robots it was generated for, and a handful of them run to a
//! clean end on both simulated robots.

mod support;

use ilmr_compiler::check::{Source, analyze};
use ilmr_model::RobotModel;
use support::taskgen::{Generated, Generator, Shape};

/// Seeds checked per generator; three generators (each robot, and both at once).
const SEEDS: u64 = 300;

fn sources(g: &Generated) -> Vec<Source> {
    let mut sources = vec![Source::new("generated.ilmr", g.task.clone())];
    if let Some(skills) = &g.skills {
        sources.push(Source::library("generated.ilms", skills.clone()));
    }
    sources
}

/// Every diagnostic of the generated program on `model`, rendered, or "".
fn diagnostics(g: &Generated, model: &RobotModel) -> String {
    let sources = sources(g);
    let analysis = analyze(&sources, model);
    if analysis.diagnostics.is_empty() {
        String::new()
    } else {
        support::human(&analysis)
    }
}

#[test]
fn generated_tasks_check_clean_on_the_robots_they_were_made_for() {
    let moro = support::model("moro");
    let workpartner = support::model("workpartner");
    let sets: [&[&RobotModel]; 3] = [&[&moro], &[&workpartner], &[&moro, &workpartner]];
    let mut lines = 0;
    let mut with_skills = 0;
    for models in sets {
        let generator = Generator::new(models, Shape::default());
        for seed in 0..SEEDS {
            let g = generator.generate(seed);
            lines += g.task.lines().count();
            with_skills += usize::from(g.skills.is_some());
            for model in models {
                let found = diagnostics(&g, model);
                assert!(
                    found.is_empty(),
                    "seed {seed} on {}:\n{}\n{}\n{found}",
                    model.name,
                    g.task,
                    g.skills.as_deref().unwrap_or("")
                );
            }
        }
    }
    // The generator is not trivially small: tasks have substance, some call skills.
    assert!(lines > 3 * SEEDS as usize * 5, "{lines} lines");
    assert!(with_skills > SEEDS as usize, "{with_skills} with skills");
}

#[test]
fn a_seed_always_gives_the_same_task() {
    let moro = support::model("moro");
    let generator = Generator::new(&[&moro], Shape::default());
    for seed in [0, 1, 99, u64::MAX] {
        assert_eq!(generator.generate(seed), generator.generate(seed));
    }
    assert_ne!(generator.generate(1).task, generator.generate(2).task);
}

#[test]
fn generated_tasks_use_every_family_of_commands() {
    let moro = support::model("moro");
    let workpartner = support::model("workpartner");
    let generator = Generator::new(&[&moro, &workpartner], Shape::default());
    let text: String = (0..SEEDS)
        .map(|s| generator.generate(s).task.to_lowercase())
        .collect();
    for needle in [
        "speed(",
        "obsavoid(",
        "savepos(",
        "createpath(",
        "record(",
        "goahead(",
        "turn(",
        "followpath(",
        "followwall(",
        "gotoxy(",
        "gotorelxy(",
        "approach(",
        "sensor(",
        "findtarget(",
        "init",
        "wait(",
        "clear(",
        "if(",
        "while(",
        "break(",
        "stop",
        "cont",
        "priority = highest",
        "skill",
    ] {
        assert!(text.contains(needle), "no generated task has `{needle}`");
    }
}

/// Generated tasks run on both simulated robots: `ilmrc run` exits 0 (the task ran)
/// without a panic; most end by themselves before `--max-time`.
#[test]
fn generated_tasks_run_on_both_simulated_robots() {
    let moro = support::model("moro");
    let workpartner = support::model("workpartner");
    // Without searches, which in the empty world would look for ever, tasks end.
    let shape = Shape {
        searches: false,
        ..Shape::default()
    };
    let generator = Generator::new(&[&moro, &workpartner], shape);
    let dir = std::env::temp_dir().join(format!("ilmr-taskgen-{}", std::process::id()));
    let skills = dir.join("skills");
    std::fs::create_dir_all(&skills).expect("temp dir");
    let mut ended = 0;
    for seed in 0..3 {
        let g = generator.generate(seed);
        let task = dir.join(format!("task{seed}.ilmr"));
        std::fs::write(&task, &g.task).expect("write task");
        std::fs::write(
            skills.join("generated.ilms"),
            g.skills.as_deref().unwrap_or(""),
        )
        .expect("write skills");
        for robot in support::ROBOTS {
            let (code, stdout, stderr) = support::ilmrc(&[
                "run",
                "--robot",
                robot,
                "--world",
                "empty",
                "--seed",
                &seed.to_string(),
                "--max-time",
                "60",
                "--skills",
                skills.to_str().expect("utf-8 temp path"),
                task.to_str().expect("utf-8 temp path"),
            ]);
            // It ran, however it ended: cleanly (0), with refusals (3), on a hold (4)
            // or at --max-time (5); never rejected (1, 2) or crashed.
            assert!(
                matches!(code, 0 | 3 | 4 | 5) && !stderr.contains("panicked"),
                "seed {seed} on {robot}: exit {code}\n{}\n{stdout}\n{stderr}",
                g.task
            );
            eprintln!(
                "seed {seed} on {robot}: {}",
                stdout.lines().next().unwrap_or("")
            );
            ended += usize::from(stdout.contains("finished"));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        ended >= 2,
        "only {ended} of 6 generated runs ended by themselves"
    );
}
