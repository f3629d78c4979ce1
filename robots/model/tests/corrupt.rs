//! Corrupt text still gives a usable model; each problem is one warning with
//! its line that says what was wrong and what stood in. Each case is the
//! text and the warnings rendered one per line.

use ilmr_model::RobotModel;

/// Parses `text` and compares the rendered warnings with `expected`
/// (one `line N: message` per line, trimmed; empty for none).
fn check(text: &str, expected: &str) -> RobotModel {
    let (model, warnings) = RobotModel::parse(text, "test");
    let actual: Vec<String> = warnings.iter().map(ToString::to_string).collect();
    let expected: Vec<&str> = expected
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    assert_eq!(actual, expected, "\nwarnings of:\n{text}");
    model
}

#[test]
fn wrong_field_counts_fall_back_to_defaults_or_drop_the_line() {
    let m = check(
        "[SENSORSANDACTUATORS]
scanner 1 0 30000
sonar 9 0 1
gyro 0 -180 180 1
[PARAMETERS]
max_speed
my_gain 1 2
curinc 0.9
[END]",
        "line 2: [SENSORSANDACTUATORS] expects 5 fields (name id min max readings), found 4 fields; the default `scanner 1 0 30000 361` is used
         line 3: [SENSORSANDACTUATORS] expects 5 fields (name id min max readings), found 4 fields; the line is ignored
         line 6: [PARAMETERS] expects 2 fields (name value), found 1 field; the default 0.6 is used
         line 7: [PARAMETERS] expects 2 fields (name value), found 3 fields; the line is ignored",
    );
    let names: Vec<(&str, u32)> = m
        .devices
        .iter()
        .map(|d| (d.name.as_str(), d.line))
        .collect();
    assert_eq!(names, vec![("scanner", 2), ("gyro", 4)]);
    assert_eq!(m.device("scanner").map(|d| d.readings), Some(361));
    assert_eq!(m.parameter("max_speed"), Some(0.6));
    assert_eq!(m.parameter("my_gain"), None);
    assert_eq!(m.curinc(), 0.9);
}

#[test]
fn non_numbers_and_bad_ranges_are_explained() {
    let m = check(
        "[SENSORSANDACTUATORS]
laser two 0 30000 1
ptu 3 100 0 2
[COLORS]
yellow bright
[IDENTIFIERS]
odo four
wheels 5
[PARAMETERS]
max_speed fast
default_speed 0,2
max_roll 120
deadreckoning_rate -1
robot_width 0
[END]",
        "line 2: device id `two` is not an integer from 0 to 2147483647; the default `laser 2 0 30000 1` is used
         line 3: minimum 100 is greater than maximum 0; the default `ptu 3 0 100 2` is used
         line 5: value `bright` is not a number; the default `yellow 18` is used
         line 7: value `four` is not a number; the default `odo 4` is used
         line 10: value `fast` is not a number; the default 0.6 is used
         line 11: value `0,2` is not a number (write `.` as the decimal point); the default 0.2 is used
         line 12: max_roll: 120 out of range (expected 0 to 90 deg); the line is ignored
         line 13: deadreckoning_rate: -1 out of range (expected 0.1 to 100 Hz); the line is ignored, so the value of `odometry_rate` is used
         line 14: robot_width: 0 out of range (expected 0.05 to 10 m); the default 1 is used",
    );
    assert_eq!(m.identifier("wheels"), Some(5.0));
    assert_eq!(m.identifier("odo"), Some(4.0));
    assert_eq!(m.max_roll(), None);
    assert_eq!(m.robot_width(), 1.0);
    assert_eq!(m.deadreckoning_rate(), m.odometry_rate());
}

#[test]
fn unknown_sections_are_skipped_with_a_hint() {
    let m = check(
        "[PARAMETER]
max_speed 0.5
curinc 0.7
[COLOURS]
[Parameters]
max_speed 0.4
[END]",
        "line 1: unknown section [PARAMETER] (did you mean [PARAMETERS]?); the sections are [SENSORSANDACTUATORS], [OBJECTS], [COLORS], [IDENTIFIERS], [PARAMETERS], [ROS2] and [END]; its 2 lines are ignored
         line 4: unknown section [COLOURS] (did you mean [COLORS]?); the sections are [SENSORSANDACTUATORS], [OBJECTS], [COLORS], [IDENTIFIERS], [PARAMETERS], [ROS2] and [END]; it holds no entries",
    );
    assert_eq!(m.parameters.len(), 1);
    assert_eq!(m.max_speed(), 0.4);
}

#[test]
fn missing_end_keeps_everything_read() {
    let m = check(
        "[PARAMETERS]
max_speed 0.5

; trailing comment",
        "line 4: the file ends without [END]; everything up to line 4 was read",
    );
    assert_eq!(m.max_speed(), 0.5);
}

#[test]
fn duplicates_keep_the_first() {
    let m = check(
        "[SENSORSANDACTUATORS]
gyro 0 -180 180 1
GYRO 5 0 1 1
compass 0 0 360 1
[OBJECTS]
door 0.8 1.2
Door 1 2
[PARAMETERS]
max_speed 0.5
MAX_SPEED 0.9
max_speed oops
[END]",
        "line 3: duplicate device `GYRO` (first defined on line 2); the line is ignored
         line 4: device `compass` has id 0, already used by `gyro` on line 2; the line is ignored
         line 7: duplicate object `Door` (first defined on line 6); the line is ignored
         line 10: duplicate parameter `MAX_SPEED` (first defined on line 9); the line is ignored
         line 11: duplicate parameter `max_speed` (first defined on line 9); the line is ignored",
    );
    assert_eq!(m.devices.len(), 1);
    assert_eq!(m.object("door").map(|o| o.line), Some(6));
    assert_eq!(m.max_speed(), 0.5);
}

#[test]
fn text_outside_sections_is_reported_once_per_place() {
    let m = check(
        "robot model for the lab
version 2
[PARAMETERS]
max_speed 0.5
[END]
scratch notes
more notes
; a comment after [END] is fine",
        "line 1: 2 lines before the first section tag are ignored
         line 6: 2 lines after [END] are ignored",
    );
    assert_eq!(m.max_speed(), 0.5);
}

#[test]
fn malformed_tags_still_open_their_section() {
    let m = check(
        "[PARAMETERS
max_speed 0.5
[END] trailing",
        "line 1: section tag `[PARAMETERS` lacks its closing `]`
         line 3: text `trailing` after the section tag [END] is ignored",
    );
    assert_eq!(m.max_speed(), 0.5);
}

#[test]
fn comments_must_be_on_their_own_line() {
    check(
        "# hash comment
; semicolon comment
   ; indented comment
[PARAMETERS]
max_speed 0.5 ; m/s
// not a comment here
[END]",
        "line 5: [PARAMETERS] expects 2 fields (name value), found 4 fields (comments must be on a line of their own); the default 0.6 is used
         line 6: `//` is not a valid parameter name (a letter, then letters, digits or `_`) (comment lines start with `;` or `#`); the line is ignored",
    );
}

#[test]
fn cross_checks_between_parameters() {
    let m = check(
        "[PARAMETERS]
max_speed 0.5
default_speed 0.8
LowBattery 26
battery_full 25
scanner_rate 2
scanner_timeout 0.1
[END]",
        "line 3: default_speed 0.8 exceeds max_speed 0.5; default_speed 0.5 is used
         line 4: LowBattery 26 V is not below battery_full 25 V, so a full battery already reads as low; kept as written
         line 7: scanner_timeout 0.1 s is shorter than one sample period (0.5 s at scanner_rate 2 Hz), so supervision would report faults between healthy samples; kept as written",
    );
    assert_eq!(m.default_speed(), 0.5);
    assert_eq!(m.parameter("default_speed"), Some(0.5));
    assert_eq!(m.low_battery(), 26.0);
}

#[test]
fn a_slow_robot_lowers_the_default_speed_too() {
    let m = check(
        "[PARAMETERS]
max_speed 0.1
[END]",
        "line 2: the default default_speed 0.2 exceeds max_speed 0.1; default_speed 0.1 is used",
    );
    assert_eq!(m.default_speed(), 0.1);
}

#[test]
fn object_parameters_must_be_numbers_or_model_names() {
    let m = check(
        "[OBJECTS]
user yelow 30
flag red 10
cone automatic 1
[COLORS]
yellow 18
[IDENTIFIERS]
automatic 1
[END]",
        "line 2: object `user` has parameter `yelow`, which is neither a number nor a name from [COLORS] or [IDENTIFIERS] (did you mean `yellow`?); it is kept as written
         line 3: object `flag` has parameter `red`, which is neither a number nor a name from [COLORS] or [IDENTIFIERS]; it is kept as written",
    );
    assert_eq!(m.objects.len(), 3);
}

#[test]
fn a_default_that_would_clash_is_not_used() {
    let m = check(
        "[SENSORSANDACTUATORS]
sonar 1 0 5000 8
scanner 1 0 30000
[END]",
        "line 3: [SENSORSANDACTUATORS] expects 5 fields (name id min max readings), found 4 fields; its default would clash (device `scanner` has id 1, already used by `sonar` on line 2), so the line is ignored",
    );
    assert_eq!(m.devices.len(), 1);
}

#[test]
fn text_without_any_section_gives_the_defaults() {
    let (m, w) = RobotModel::parse("", "empty");
    assert_eq!(w.len(), 1);
    assert_eq!(w[0].line, None);
    assert_eq!(
        w[0].message,
        "the robot model has no content; the built-in defaults are used"
    );
    assert_eq!(m.name, "empty");
    assert_eq!(m.devices, RobotModel::defaults().devices);

    let (m, w) = RobotModel::parse("max_speed 0.5\nrobot_width 2\n", "flat");
    assert_eq!(
        w.iter().map(ToString::to_string).collect::<Vec<_>>(),
        vec![
            "no known section tag such as [PARAMETERS] in 2 lines; the built-in defaults are used"
        ]
    );
    assert_eq!(m.max_speed(), 0.6);

    let (m, w) = RobotModel::parse("[PARAMETRES]\nmax_speed 0.5\n[ned]\n", "typos");
    assert_eq!(
        w.iter().map(ToString::to_string).collect::<Vec<_>>(),
        vec![
            "no known section tag such as [PARAMETERS] in 3 lines; the built-in defaults are used",
            "line 1: unknown section [PARAMETRES] (did you mean [PARAMETERS]?); the sections are \
             [SENSORSANDACTUATORS], [OBJECTS], [COLORS], [IDENTIFIERS], [PARAMETERS], [ROS2] and [END]; \
             its 1 line is ignored",
            "line 3: unknown section [ned] (did you mean [END]?); the sections are \
             [SENSORSANDACTUATORS], [OBJECTS], [COLORS], [IDENTIFIERS], [PARAMETERS], [ROS2] and [END]; \
             it holds no entries",
        ]
    );
    assert_eq!(
        m,
        RobotModel {
            name: "typos".into(),
            ..RobotModel::defaults()
        }
    );
}

#[test]
fn an_explicitly_empty_model_is_respected() {
    let m = check("[END]", "");
    assert!(m.devices.is_empty() && m.parameters.is_empty());
}

#[test]
fn finnish_names_are_names() {
    let m = check(
        "[OBJECTS]
ovi 0.8 1.2
[IDENTIFIERS]
pyörät 5
[END]",
        "",
    );
    assert_eq!(m.identifier("PYÖRÄT"), Some(5.0));
}

#[test]
fn a_ros2_section_keeps_known_settings_and_warns_about_the_rest() {
    let (m, warnings) = RobotModel::parse(
        "[PARAMETERS]\nmax_speed 0.5\n[ROS2]\nnamespace /tb3\nCMD_VEL cmd_vel_nav\n\
         odm odom2\ncmd_vel again\nscan\nsensor_qos reliable\n[END]\n",
        "tb3",
    );
    let settings: Vec<(&str, &str)> = m
        .ros2
        .iter()
        .map(|s| (s.name.as_str(), s.value.as_str()))
        .collect();
    assert_eq!(
        settings,
        [
            ("namespace", "/tb3"),
            ("cmd_vel", "cmd_vel_nav"),
            ("sensor_qos", "reliable")
        ]
    );
    let said: Vec<String> = warnings.iter().map(|w| w.to_string()).collect();
    assert!(
        said[0].contains("line 6: unknown [ROS2] setting `odm` (did you mean `odom`?)"),
        "{said:?}"
    );
    assert!(
        said[1].contains("line 7: duplicate [ROS2] setting `cmd_vel`"),
        "{said:?}"
    );
    assert!(
        said[2].contains("line 8: [ROS2] entry `scan` should have 2 fields"),
        "{said:?}"
    );
    assert_eq!(said.len(), 3, "{said:?}");
    // Written out and read back, the section is the same.
    let (back, none) = RobotModel::parse(&m.to_ini(), "tb3");
    assert!(none.is_empty(), "{none:?}");
    assert_eq!(back.ros2, m.ros2);
    // A model without the section writes none.
    assert!(
        !RobotModel::builtin("moro")
            .unwrap()
            .to_ini()
            .contains("[ROS2]")
    );
}
