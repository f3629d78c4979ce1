//! Figure 39 of the dissertation, character for character, must read
//! without a single warning and give exactly its values.

use ilmr_model::{Device, ModelName, RobotModel};

const FIGURE_39: &str = "[SENSORSANDACTUATORS]
gyro 0 -180 180 1
scanner 1 0 30000 361
laser 2 0 30000 1
ptu 3 0 100 2
[OBJECTS]
user yellow 30
side_edge 200 30
[COLORS]
yellow 18
[IDENTIFIERS]
off 0
automatic 1
scanner 2
gps 3
odo 4
rolking 4
wheels 5
parking 6
[PARAMETERS]
max_time_to_search 10
default_speed 0.2
max_speed 0.6
pos_interval 0.5
omax_curvature 0.4
curinc 0.8
robot_length 2.2
robot_width 1.0
followwall_d 1.0
bs_security 1.0
[END]
";

fn figure_39() -> RobotModel {
    let (model, warnings) = RobotModel::parse(FIGURE_39, "ROBO");
    assert!(warnings.is_empty(), "{warnings:#?}");
    model
}

#[test]
fn devices_are_exactly_figure_39s() {
    let m = figure_39();
    let d = |name: &str, id, min, max, readings, line| Device {
        name: name.into(),
        id,
        min,
        max,
        readings,
        line,
    };
    assert_eq!(
        m.devices,
        vec![
            d("gyro", 0, -180.0, 180.0, 1, 2),
            d("scanner", 1, 0.0, 30000.0, 361, 3),
            d("laser", 2, 0.0, 30000.0, 1, 4),
            d("ptu", 3, 0.0, 100.0, 2, 5),
        ]
    );
}

#[test]
fn objects_colors_identifiers_and_parameters_are_exactly_figure_39s() {
    let m = figure_39();
    let objects: Vec<(&str, Vec<&str>, u32)> = m
        .objects
        .iter()
        .map(|o| {
            (
                o.name.as_str(),
                o.params.iter().map(String::as_str).collect(),
                o.line,
            )
        })
        .collect();
    assert_eq!(
        objects,
        vec![
            ("user", vec!["yellow", "30"], 7),
            ("side_edge", vec!["200", "30"], 8)
        ]
    );
    let values = |vs: &[ilmr_model::NamedValue]| -> Vec<(String, f64, u32)> {
        vs.iter()
            .map(|v| (v.name.clone(), v.value, v.line))
            .collect()
    };
    assert_eq!(values(&m.colors), vec![("yellow".into(), 18.0, 10)]);
    let identifiers: Vec<(&str, f64)> = m
        .identifiers
        .iter()
        .map(|v| (v.name.as_str(), v.value))
        .collect();
    assert_eq!(
        identifiers,
        vec![
            ("off", 0.0),
            ("automatic", 1.0),
            ("scanner", 2.0),
            ("gps", 3.0),
            ("odo", 4.0),
            ("rolking", 4.0),
            ("wheels", 5.0),
            ("parking", 6.0),
        ]
    );
    let parameters: Vec<(&str, f64, u32)> = m
        .parameters
        .iter()
        .map(|v| (v.name.as_str(), v.value, v.line))
        .collect();
    assert_eq!(
        parameters,
        vec![
            ("max_time_to_search", 10.0, 21),
            ("default_speed", 0.2, 22),
            ("max_speed", 0.6, 23),
            ("pos_interval", 0.5, 24),
            ("omax_curvature", 0.4, 25),
            ("curinc", 0.8, 26),
            ("robot_length", 2.2, 27),
            ("robot_width", 1.0, 28),
            ("followwall_d", 1.0, 29),
            ("bs_security", 1.0, 30),
        ]
    );
    assert_eq!(m.name, "ROBO");
    assert_eq!(m.source, None);
}

#[test]
fn typed_accessors_read_figure_39_and_default_the_rest() {
    let m = figure_39();
    assert_eq!(m.max_time_to_search(), 10.0);
    assert_eq!(m.default_speed(), 0.2);
    assert_eq!(m.max_speed(), 0.6);
    assert_eq!(m.pos_interval(), 0.5);
    assert_eq!(m.omax_curvature(), 0.4);
    assert_eq!(m.curinc(), 0.8);
    assert_eq!(m.robot_length(), 2.2);
    assert_eq!(m.robot_width(), 1.0);
    assert_eq!(m.followwall_d(), 1.0);
    assert_eq!(m.bs_security(), 1.0);
    // Not in Figure 39: the documented defaults, but not model names.
    assert_eq!(m.max_curvature(), 0.25);
    assert_eq!(m.low_battery(), 23.0);
    assert_eq!(m.parameter("LowBattery"), None);
    assert_eq!(m.parameter_or_default("lowbattery"), Some(23.0));
    assert_eq!(m.max_roll(), None);
}

#[test]
fn scanner_is_a_device_first_and_an_identifier_too() {
    let m = figure_39();
    assert!(matches!(m.lookup("SCANNER"), Some(ModelName::Device(d)) if d.id == 1));
    assert_eq!(m.identifier("Scanner"), Some(2.0));
    assert_eq!(m.device_by_id(1).map(|d| d.name.as_str()), Some("scanner"));
    assert_eq!(m.device_by_id(9), None);
    let scanners: Vec<&str> = m
        .names()
        .filter(|(n, _)| *n == "scanner")
        .map(|(_, kind)| kind.kind())
        .collect();
    assert_eq!(scanners, vec!["device", "identifier"]);
}

#[test]
fn crlf_tabs_and_a_byte_order_mark_read_the_same() {
    let dos = format!(
        "\u{feff}{}",
        FIGURE_39.replace('\n', "\r\n").replace(' ', " \t ")
    );
    let (model, warnings) = RobotModel::parse(&dos, "ROBO");
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert_eq!(model, figure_39());
}
