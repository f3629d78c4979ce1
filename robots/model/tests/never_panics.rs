//! Parsing is total: any text gives a model and warnings, never a panic, and
//! whatever was read survives writing it out and reading it again.

use ilmr_model::RobotModel;
use proptest::prelude::*;

/// Lines close to ROBO.INI, so that the interesting paths get exercised
/// far more often than with uniformly random text.
fn near_ini_line() -> impl Strategy<Value = String> {
    let tag = prop::sample::select(vec![
        "[SENSORSANDACTUATORS]",
        "[OBJECTS]",
        "[COLORS]",
        "[IDENTIFIERS]",
        "[PARAMETERS]",
        "[END]",
        "[end]",
        "[PARAMETER]",
        "[OBJECTS",
        "[]",
        "[",
        "]",
    ])
    .prop_map(str::to_string);
    let word = prop::sample::select(vec![
        "scanner",
        "gyro",
        "max_speed",
        "default_speed",
        "LowBattery",
        "battery_full",
        "scanner_timeout",
        "scanner_rate",
        "door",
        "yellow",
        "ä",
        "1x",
        "-",
        ";",
        "#",
        "//",
        "0",
        "1",
        "-1",
        "0.5",
        "1e309",
        "NaN",
        "inf",
        "0,5",
        "2147483648",
        "99999999999999999999",
    ])
    .prop_map(str::to_string);
    let entry = prop::collection::vec(word, 0..7).prop_map(|w| w.join(" "));
    prop_oneof![tag, entry, "\\PC{0,20}"]
}

fn strip_lines(mut m: RobotModel) -> RobotModel {
    m.devices.iter_mut().for_each(|d| d.line = 0);
    m.objects.iter_mut().for_each(|o| o.line = 0);
    for v in m
        .colors
        .iter_mut()
        .chain(&mut m.identifiers)
        .chain(&mut m.parameters)
    {
        v.line = 0;
    }
    m
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC*(\\n\\PC*){0,8}") {
        let (_model, warnings) = RobotModel::parse(&text, "fuzz");
        let lines = u32::try_from(text.lines().count()).unwrap_or(u32::MAX);
        for w in &warnings {
            prop_assert!(w.line.is_none_or(|l| l >= 1 && l <= lines.max(1)), "{w}");
        }
    }

    #[test]
    fn near_ini_text_never_panics_and_round_trips(
        lines in prop::collection::vec(near_ini_line(), 0..30),
        crlf in any::<bool>(),
    ) {
        let text = lines.join(if crlf { "\r\n" } else { "\n" });
        let (model, warnings) = RobotModel::parse(&text, "fuzz");
        // Warnings come sorted by line, file-level ones first.
        prop_assert!(warnings.windows(2).all(|w| w[0].line <= w[1].line));
        // Everything kept is valid, so it reads back the same.
        let (again, _) = RobotModel::parse(&model.to_ini(), "fuzz");
        prop_assert_eq!(strip_lines(again), strip_lines(model.clone()));
        // Each kept name resolves to itself.
        for (name, _) in model.names() {
            prop_assert!(model.lookup(name).is_some());
        }
        prop_assert!(model.default_speed() <= model.max_speed());
    }
}
