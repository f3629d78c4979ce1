//! The shipped models read cleanly and carry the robots' facts from
//! sections 5.1 and 5.2; the defaults match the parameter table.

use ilmr_model::{PARAMETER_SPECS, ParamDefault, RobotModel};

fn clean(name: &str) -> RobotModel {
    let text = std::fs::read_to_string(format!("{}/models/{name}.ini", env!("CARGO_MANIFEST_DIR")))
        .expect("shipped model file");
    let (model, warnings) = RobotModel::parse(&text, name);
    assert!(warnings.is_empty(), "{name}: {warnings:#?}");
    model
}

fn range(m: &RobotModel, device: &str) -> (f64, f64, u32) {
    let d = m
        .device(device)
        .unwrap_or_else(|| panic!("{} lacks {device}", m.name));
    (d.min, d.max, d.readings)
}

#[test]
fn shipped_models_parse_without_warnings_and_match_builtin() {
    for name in RobotModel::builtin_names() {
        let from_file = clean(name);
        let builtin = RobotModel::builtin(&name.to_uppercase()).expect("builtin");
        assert_eq!(builtin, from_file);
        assert_eq!(builtin.name, *name);
    }
    assert_eq!(RobotModel::builtin_names(), &["moro", "workpartner"]);
    assert_eq!(
        RobotModel::builtin("WorkPartner").map(|m| m.name),
        Some("workpartner".into())
    );
    assert!(RobotModel::builtin("default").is_none());
    assert!(RobotModel::builtin("r2d2").is_none());
}

#[test]
fn workpartner_starts_with_figure_39() {
    let m = clean("workpartner");
    let first: Vec<(&str, i64)> = m
        .devices
        .iter()
        .take(4)
        .map(|d| (d.name.as_str(), d.id))
        .collect();
    assert_eq!(
        first,
        vec![("gyro", 0), ("scanner", 1), ("laser", 2), ("ptu", 3)]
    );
    assert_eq!(m.objects[0].params, vec!["yellow", "30"]);
    assert_eq!(m.objects[1].params, vec!["200", "30"]);
    for (name, value) in [
        ("off", 0.0),
        ("automatic", 1.0),
        ("scanner", 2.0),
        ("gps", 3.0),
        ("odo", 4.0),
        ("rolking", 4.0),
        ("wheels", 5.0),
        ("parking", 6.0),
        ("navi", 7.0),
    ] {
        assert_eq!(m.identifier(name), Some(value), "{name}");
    }
    assert_eq!(m.omax_curvature(), 0.4);
    assert_eq!(m.curinc(), 0.8);
    assert_eq!((m.robot_length(), m.robot_width()), (2.2, 1.0));
}

#[test]
fn workpartner_facts() {
    let m = clean("workpartner");
    assert_eq!(m.max_curvature(), 0.25);
    assert_eq!(m.nav_rate(), Some(2.0));
    assert_eq!(m.deadreckoning_rate(), 10.0);
    assert!(m.nav_timeout().is_some());
    assert_eq!(
        (m.max_roll(), m.max_pitch(), m.max_clearance()),
        (Some(30.0), Some(30.0), Some(1.0))
    );
    assert_eq!(range(&m, "ultrasonic").2, 4);
    assert_eq!(range(&m, "scanner"), (0.0, 30000.0, 361));
    // actuator(brake,on) and actuator(leg1,90) must be admissible.
    assert_eq!(range(&m, "brake"), (0.0, 1.0, 1));
    for leg in ["leg1", "leg2", "leg3", "leg4"] {
        let (min, max, _) = range(&m, leg);
        assert!(min <= 90.0 && 90.0 <= max, "{leg}");
    }
    for device in ["gyro", "battery", "odometry", "laser", "ptu", "camera"] {
        assert!(m.device(device).is_some(), "{device}");
    }
    for object in ["door", "charger", "box", "user", "side_edge"] {
        assert!(m.object(object).is_some(), "{object}");
    }
    assert!(m.low_battery() < m.battery_full());
    let (lo, hi, _) = range(&m, "battery");
    assert!(lo <= m.low_battery() && m.battery_full() <= hi);
}

#[test]
fn moro_facts() {
    let m = clean("moro");
    assert_eq!((m.robot_length(), m.robot_width()), (1.2, 0.6));
    assert!((m.max_curvature() - 1.0 / 0.75).abs() < 1e-5);
    assert!(m.max_speed() >= 0.8 && m.default_speed() >= 0.2);
    assert!(m.omax_curvature() <= m.max_curvature());
    assert!((2.0..=4.0).contains(&m.scanner_rate()));
    assert_eq!(range(&m, "scanner"), (0.0, 30000.0, 361));
    for device in [
        "gyro",
        "battery",
        "odometry",
        "plates",
        "frontwheel",
        "horn",
    ] {
        assert!(m.device(device).is_some(), "{device}");
    }
    for absent in ["camera", "ptu", "leg1", "brake", "ultrasonic"] {
        assert!(m.device(absent).is_none(), "{absent}");
    }
    for object in ["door", "charger"] {
        assert!(m.object(object).is_some(), "{object}");
    }
    assert_eq!(
        (m.max_roll(), m.max_pitch(), m.max_clearance()),
        (None, None, None)
    );
    assert_eq!(m.nav_rate(), None);
    assert_eq!(m.deadreckoning_rate(), m.odometry_rate());
    for mode in ["automatic", "scanner", "odo"] {
        assert!(m.identifier(mode).is_some(), "{mode}");
    }
    for mode in ["wheels", "rolking", "parking", "gps"] {
        assert!(m.identifier(mode).is_none(), "{mode}");
    }
    assert!(m.colors.is_empty());
    // Ids shared with Workpartner mean the same device.
    let wp = clean("workpartner");
    for d in &m.devices {
        if let Some(other) = wp.device(&d.name) {
            assert_eq!(d.id, other.id, "{}", d.name);
        }
    }
}

#[test]
fn both_robots_carry_every_parameter_with_a_default() {
    for name in RobotModel::builtin_names() {
        let m = clean(name);
        for spec in PARAMETER_SPECS {
            if let ParamDefault::Value(_) = spec.default {
                assert!(
                    m.parameter(spec.name).is_some(),
                    "{name} lacks {}",
                    spec.name
                );
            }
        }
    }
}

#[test]
fn defaults_are_figure_39_plus_the_table_and_read_cleanly() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/models/default.ini"))
        .expect("default.ini");
    let (parsed, warnings) = RobotModel::parse(&text, "default");
    assert!(warnings.is_empty(), "{warnings:#?}");
    let d = RobotModel::defaults();
    assert_eq!(d, parsed);
    assert_eq!(d.name, "default");
    for spec in PARAMETER_SPECS {
        match spec.default {
            ParamDefault::Value(v) => assert_eq!(d.parameter(spec.name), Some(v), "{}", spec.name),
            _ => assert_eq!(d.parameter(spec.name), None, "{}", spec.name),
        }
    }
    for device in ["gyro", "scanner", "laser", "ptu", "battery", "odometry"] {
        assert!(d.device(device).is_some(), "{device}");
    }
}

#[test]
fn models_round_trip_through_ini_text_and_json() {
    for name in RobotModel::builtin_names()
        .iter()
        .copied()
        .chain(["default"])
    {
        let m = RobotModel::builtin(name).unwrap_or_else(RobotModel::defaults);
        let (again, warnings) = RobotModel::parse(&m.to_ini(), name);
        assert!(warnings.is_empty(), "{warnings:#?}");
        assert_eq!(strip_lines(again), strip_lines(m.clone()));
        let json = serde_json::to_string(&m).expect("serialize");
        let back: RobotModel = serde_json::from_str(&json).expect("deserialize");
        assert_eq!(back, m);
    }
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
