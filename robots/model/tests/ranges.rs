//! Every number of a ROBO.INI has a range (issue 12): each known parameter
//! past either end of its range, NaN and infinity in every numeric field,
//! huge device readings and values. Each gives one warning in the form
//! `key: value out of range (expected ...)` (or "not a number") on its line,
//! and the model that comes back holds only values in range.

use ilmr_model::{
    MAX_MAGNITUDE, MAX_READINGS, MAX_SECTION_ENTRIES, PARAMETER_SPECS, RobotModel, Valid,
};

fn parse(text: &str) -> (RobotModel, Vec<String>) {
    let (model, warnings) = RobotModel::parse(text, "test");
    (model, warnings.iter().map(ToString::to_string).collect())
}

/// Values just past each end of a range, and the hostile ones.
fn outside(valid: Valid) -> Vec<f64> {
    let (lo, hi) = match valid {
        Valid::PositiveAtMost(max) => (0.0, max),
        Valid::Between(min, max) => (min, max),
    };
    let below = if matches!(valid, Valid::PositiveAtMost(_)) {
        0.0
    } else {
        lo - 1.0
    };
    vec![below, -1e308, hi * 1.5 + 1.0, 1e308]
}

#[test]
fn every_known_parameter_out_of_range_is_named_with_its_range() {
    for spec in PARAMETER_SPECS {
        for v in outside(spec.valid) {
            let text = format!("[PARAMETERS]\n{} {v:e}\n[END]\n", spec.name);
            let (model, warnings) = parse(&text);
            assert_eq!(warnings.len(), 1, "{text}: {warnings:?}");
            let w = &warnings[0];
            let expected = format!(
                "line 2: {}: {} out of range (expected {} {})",
                spec.name,
                if (1e-6..1e9).contains(&v.abs()) || v == 0.0 {
                    v.to_string()
                } else {
                    format!("{v:e}")
                },
                spec.valid.describe(),
                spec.unit
            );
            assert!(w.starts_with(&expected), "{w}\nexpected {expected}");
            if let Some(kept) = model.parameter_or_default(spec.name) {
                assert!(spec.valid.admits(kept), "{}: kept {kept}", spec.name);
            }
        }
    }
}

#[test]
fn the_issue_s_stop_margin_falls_back_to_its_default() {
    let (model, warnings) = parse("[PARAMETERS]\nstop_margin 1e308\n[END]\n");
    assert_eq!(
        warnings,
        [
            "line 2: stop_margin: 1e308 out of range (expected > 0 and <= 10 m); the default 0.2 is used"
        ]
    );
    assert_eq!(model.stop_margin(), 0.2);
}

#[test]
fn nan_and_infinity_are_not_numbers_in_any_field() {
    for bad in [
        "NaN",
        "nan",
        "inf",
        "-inf",
        "infinity",
        "+Infinity",
        "1e400",
    ] {
        let lines = [
            format!("[SENSORSANDACTUATORS]\nscanner 1 {bad} 30000 361"),
            format!("[SENSORSANDACTUATORS]\nscanner 1 0 {bad} 361"),
            format!("[SENSORSANDACTUATORS]\nscanner {bad} 0 30000 361"),
            format!("[SENSORSANDACTUATORS]\nscanner 1 0 30000 {bad}"),
            format!("[COLORS]\nyellow {bad}"),
            format!("[IDENTIFIERS]\noff {bad}"),
            format!("[PARAMETERS]\nmy_gain {bad}"),
        ];
        let params = PARAMETER_SPECS
            .iter()
            .map(|s| format!("[PARAMETERS]\n{} {bad}", s.name));
        for text in lines.into_iter().chain(params) {
            let (model, warnings) = parse(&format!("{text}\n[END]\n"));
            assert_eq!(warnings.len(), 1, "{text}: {warnings:?}");
            assert!(warnings[0].starts_with("line 2: "), "{text}: {warnings:?}");
            for v in model
                .colors
                .iter()
                .chain(&model.identifiers)
                .chain(&model.parameters)
            {
                assert!(v.value.is_finite(), "{text}: {v:?}");
            }
            for d in &model.devices {
                assert!(d.min.is_finite() && d.max.is_finite(), "{text}: {d:?}");
            }
        }
    }
}

#[test]
fn a_hundred_million_readings_are_refused() {
    let (model, warnings) = parse("[SENSORSANDACTUATORS]\nscanner 1 0 30000 100000000\n[END]\n");
    assert_eq!(
        warnings,
        [
            "line 2: scanner readings: 100000000 out of range (expected 1 to 4096); the default `scanner 1 0 30000 361` is used"
        ]
    );
    assert_eq!(model.device("scanner").map(|d| d.readings), Some(361));
    let (model, warnings) = parse(&format!(
        "[SENSORSANDACTUATORS]\nsonar 9 0 1 {}\nscanner 1 0 30000 99999999999999999999999\n[END]\n",
        MAX_READINGS + 1
    ));
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(
        warnings[0].contains("sonar readings: 4097 out of range"),
        "{warnings:?}"
    );
    assert!(model.device("sonar").is_none());
    let (model, warnings) = parse(&format!(
        "[SENSORSANDACTUATORS]\nsonar 9 0 1 {MAX_READINGS}\n[END]\n"
    ));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(
        model.device("sonar").map(|d| d.readings),
        Some(MAX_READINGS)
    );
}

#[test]
fn huge_values_elsewhere_are_out_of_range() {
    let text = "[SENSORSANDACTUATORS]
sonar 9 -1e12 1 4
laser 2 0 1e308 1
[OBJECTS]
door 0.8 1e300
[COLORS]
yellow 1e300
[IDENTIFIERS]
off -2e9
[PARAMETERS]
my_gain 1e10
my_other 1e9
[END]
";
    let (model, warnings) = parse(text);
    assert_eq!(
        warnings,
        [
            "line 2: sonar minimum: -1e12 out of range (expected -1e9 to 1e9); the line is ignored",
            "line 3: laser maximum: 1e308 out of range (expected -1e9 to 1e9); the default `laser 2 0 30000 1` is used",
            "line 5: door parameter: 1e300 out of range (expected -1e9 to 1e9); the default `door 0.8 1.2` is used",
            "line 7: yellow: 1e300 out of range (expected -1e9 to 1e9); the default `yellow 18` is used",
            "line 9: off: -2e9 out of range (expected -1e9 to 1e9); the default `off 0` is used",
            "line 11: my_gain: 1e10 out of range (expected -1e9 to 1e9); the line is ignored",
        ]
    );
    assert_eq!(model.parameter("my_other"), Some(MAX_MAGNITUDE));
    assert_eq!(model.parameter("my_gain"), None);
    assert_eq!(
        model.object("door").map(|o| o.params.clone()),
        Some(vec!["0.8".to_string(), "1.2".to_string()])
    );
}

#[test]
fn the_shipped_robots_are_inside_every_range() {
    for name in RobotModel::builtin_names() {
        let model = RobotModel::builtin(name).expect("shipped");
        for spec in PARAMETER_SPECS {
            if let Some(v) = model.parameter(spec.name) {
                assert!(spec.valid.admits(v), "{name}: {} {v}", spec.name);
            }
        }
    }
}

#[test]
fn a_section_holds_at_most_its_limit_of_entries() {
    let mut text = String::from("[SENSORSANDACTUATORS]\n");
    for i in 0..MAX_SECTION_ENTRIES + 500 {
        text.push_str(&format!("d{i} {} 0 1 1\n", i + 100));
    }
    text.push_str("[PARAMETERS]\n");
    for i in 0..MAX_SECTION_ENTRIES + 1 {
        text.push_str(&format!("p{i} 1\n"));
    }
    text.push_str("[END]\n");
    let (model, warnings) = parse(&text);
    assert_eq!(model.devices.len(), MAX_SECTION_ENTRIES);
    assert_eq!(model.parameters.len(), MAX_SECTION_ENTRIES);
    let first = MAX_SECTION_ENTRIES + 2;
    assert_eq!(
        warnings,
        [
            format!(
                "line {first}: [SENSORSANDACTUATORS]: more than 1024 entries, out of range (expected at most 1024); 500 lines from here on are ignored"
            ),
            format!(
                "line {}: [PARAMETERS]: more than 1024 entries, out of range (expected at most 1024); 1 line from here on is ignored",
                first + 500 + 1 + MAX_SECTION_ENTRIES
            ),
        ]
    );
}
