//! Names are found whatever their case, keep their spelling, and are listed
//! in lookup order.

use ilmr_model::{ModelName, RobotModel};

fn workpartner() -> RobotModel {
    RobotModel::builtin("workpartner").expect("shipped")
}

#[test]
fn lookups_ignore_case_and_keep_the_files_spelling() {
    let m = workpartner();
    assert_eq!(m.device("SCANNER").map(|d| d.readings), Some(361));
    assert_eq!(m.device("Leg1").map(|d| d.name.as_str()), Some("leg1"));
    assert_eq!(
        m.object("USER").map(|o| o.params.clone()),
        Some(vec!["yellow".into(), "30".into()])
    );
    assert_eq!(m.color("Yellow"), Some(18.0));
    assert_eq!(m.identifier("ODO"), Some(4.0));
    assert_eq!(m.identifier("NAVI"), Some(7.0));
    assert_eq!(m.parameter("MAX_SPEED"), Some(0.6));
    assert_eq!(m.parameter("lowbattery"), Some(23.0));
    let low = m.lookup("lowBATTERY").expect("defined");
    assert_eq!(
        (low.kind(), low.name(), low.value()),
        ("parameter", "LowBattery", Some(23.0))
    );
    assert!(m.lookup("nonexistent").is_none());
    assert!(m.device("yellow").is_none());
}

#[test]
fn lookup_order_is_devices_objects_colors_identifiers_parameters() {
    let m = workpartner();
    let kinds: Vec<&str> = m.names().map(|(_, n)| n.kind()).collect();
    let mut sorted = kinds.clone();
    let rank = |k: &&str| {
        ["device", "object", "color", "identifier", "parameter"]
            .iter()
            .position(|x| x == k)
    };
    sorted.sort_by_key(rank);
    assert_eq!(kinds, sorted);
    assert!(matches!(m.lookup("door"), Some(ModelName::Object(_))));
    assert!(matches!(m.lookup("wheels"), Some(ModelName::Identifier(_))));
    assert_eq!(m.lookup("scanner").map(|n| n.line()), Some(10));
}

#[test]
fn similar_names_suggest_the_nearest_first() {
    let m = workpartner();
    assert_eq!(m.similar_names("scaner", 3), vec!["scanner"]);
    assert_eq!(m.similar_names("LowBatery", 1), vec!["LowBattery"]);
    assert_eq!(m.similar_names("leg5", 2), vec!["leg1", "leg2"]);
    assert!(m.similar_names("zzzzzz", 3).is_empty());
}
