use ilmr_stdlib::{CATALOGUE, Category, Command, Occurs, ParamKind, Syntax};

#[test]
fn catalogue_order_matches_the_command_enum() {
    for (i, spec) in CATALOGUE.iter().enumerate() {
        assert_eq!(spec.command as usize, i, "{} is out of place", spec.name);
        assert_eq!(Command::from_name(spec.name), Some(spec.command));
    }
}

#[test]
fn table_7_has_33_commands_in_four_categories() {
    let count = |c: Category| CATALOGUE.iter().filter(|s| s.category == c).count();
    assert_eq!(CATALOGUE.len(), 33);
    assert_eq!(count(Category::Define), 11);
    assert_eq!(count(Category::Movement), 8);
    assert_eq!(count(Category::Action), 5);
    assert_eq!(count(Category::ControlFlow), 9);
}

#[test]
fn exactly_the_movement_category_takes_the_movement_reservation() {
    for spec in &CATALOGUE {
        assert_eq!(
            spec.movement,
            spec.category == Category::Movement,
            "{}",
            spec.name
        );
    }
}

#[test]
fn names_are_lowercase_and_found_in_any_case() {
    for spec in &CATALOGUE {
        assert_eq!(spec.name, spec.name.to_ascii_lowercase());
        assert_eq!(
            Command::from_name(&spec.name.to_ascii_uppercase()),
            Some(spec.command)
        );
        assert_eq!(Command::from_name(spec.title), Some(spec.command));
    }
    assert_eq!(Command::from_name("goaheadx"), None);
}

#[test]
fn call_commands_have_forms_and_structural_ones_do_not() {
    for spec in &CATALOGUE {
        match spec.syntax {
            Syntax::Call => assert!(!spec.forms.is_empty(), "{}", spec.name),
            Syntax::Structural => assert!(spec.forms.is_empty(), "{}", spec.name),
        }
        assert!(!spec.summary.is_empty() && !spec.grammar.is_empty());
        assert!(!spec.examples.is_empty(), "{} has no example", spec.name);
    }
}

#[test]
fn min_args_never_exceeds_the_parameters_of_its_form() {
    for spec in &CATALOGUE {
        for form in spec.forms {
            let required = form
                .params
                .iter()
                .filter(|p| p.occurs == Occurs::One)
                .count();
            assert!(
                form.min_args as usize >= required
                    || form
                        .params
                        .iter()
                        .all(|p| matches!(p.kind, ParamKind::Setting { .. })),
                "{}",
                spec.name
            );
            assert!(
                form.min_args as usize <= form.params.len().max(1)
                    || form
                        .params
                        .iter()
                        .any(|p| matches!(p.occurs, Occurs::Many | Occurs::Pairs)),
                "{}",
                spec.name
            );
        }
    }
}

#[test]
fn keywords_are_collected_from_the_grammars() {
    let words = ilmr_stdlib::all_keywords();
    for w in [
        "left",
        "right",
        "middle",
        "forever",
        "backwards",
        "reverse",
        "w",
        "r",
        "on",
        "off",
        "goalpos",
        "take",
    ] {
        assert!(words.contains(&w), "{w}");
    }
    assert!(Command::Turn.spec().has_keyword("LEFT"));
    assert!(!Command::Turn.spec().has_keyword("middle"));
}

#[test]
fn command_reference_is_fresh() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/commands.md");
    let expected = ilmr_stdlib::reference::reference_markdown();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(&path, &expected).unwrap();
    }
    let actual = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        actual == expected,
        "docs/commands.md is stale: run `UPDATE_DOCS=1 cargo test -p ilmr-stdlib`"
    );
}

/// A setting acts the instant it is issued and outside the movement queue: that is what
/// makes two of them in one tick a race (W0905). Its exception is a keyword of its own
/// grammar, and a device setter's first argument names a device.
#[test]
fn settings_end_at_issue_outside_the_movement_queue() {
    use ilmr_stdlib::{ModelNames, Sets};
    let mut setters = 0;
    for spec in &CATALOGUE {
        match spec.sets {
            Sets::Nothing => continue,
            Sets::Setting { unless, .. } => {
                if let Some(k) = unless {
                    assert!(
                        spec.has_keyword(k),
                        "{}: `{k}` is not its keyword",
                        spec.name
                    );
                }
            }
            Sets::Device => {
                for form in spec.forms {
                    assert!(matches!(
                        form.params[0].kind,
                        ParamKind::Model {
                            names: ModelNames::Device
                        }
                    ));
                }
            }
        }
        setters += 1;
        assert!(!spec.movement, "{} is queued", spec.name);
        assert!(
            spec.ends.at_issue(std::iter::empty()),
            "{} lasts past its issue",
            spec.name
        );
    }
    assert_eq!(setters, 3);
}
