mod common;

use ilmr_sim::World;
use ilmr_sim::world::{SHIPPED, shipped};

#[test]
fn all_shipped_worlds_load_and_have_their_parts() {
    for (name, _) in SHIPPED {
        let w = common::shipped(name);
        assert_eq!(w.name, name);
    }
    let office = common::shipped("office");
    assert!(office.doors.len() >= 8, "corridor doors on both sides");
    assert!(office.doors.iter().any(|d| d.id == "lab_door"));
    assert!(office.plates.len() >= 5);
    assert!(office.charger.is_some());
    assert_eq!(office.targets[0].name, "user");
    let yard = common::shipped("yard");
    assert!(yard.obstacles.len() >= 8, "trees and poles");
    assert!(yard.charger.is_some());
    assert!(
        yard.targets
            .iter()
            .any(|t| t.name == "user" && t.speed > 0.0)
    );
    assert!(shipped("nowhere").is_none());
}

#[test]
fn shipped_worlds_also_load_from_their_files() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../worlds");
    for (name, _) in SHIPPED {
        let from_file = World::from_path(&dir.join(format!("{name}.toml")));
        assert_eq!(from_file.ok(), Some(common::shipped(name)));
    }
    let missing = World::from_path(&dir.join("missing.toml"));
    assert!(missing.is_err_and(|e| e.line == 0 && e.message.contains("cannot read")));
}

#[test]
fn doors_cut_openings_out_of_their_wall() {
    let w = common::world(
        r#"
name = "t"
bounds = { min = [0.0, 0.0], max = [10.0, 10.0] }
start = { x = 1.0, y = 1.0 }

[[wall]]
id = "w"
from = [0.0, 5.0]
to = [10.0, 5.0]

[[door]]
wall = "w"
at = 7.0
width = 1.0

[[door]]
wall = "w"
at = 2.0
width = 1.0
"#,
    );
    let pieces: Vec<(f64, f64)> = w.walls[0].pieces.iter().map(|(a, b)| (a.x, b.x)).collect();
    assert_eq!(pieces, vec![(0.0, 1.5), (2.5, 6.5), (7.5, 10.0)]);
    assert_eq!(w.doors[0].center.x, 7.0);
    assert_eq!(w.doors[1].id, "door2");
}

/// Loads `text` and returns the error's rendering.
fn error_of(text: &str) -> String {
    match World::from_toml(text, "bad.toml") {
        Ok(_) => panic!("world should not load:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const HEAD: &str = r#"name = "bad"
bounds = { min = [0.0, 0.0], max = [10.0, 10.0] }
start = { x = 1.0, y = 1.0 }
"#;

#[test]
fn bad_worlds_report_line_and_field() {
    let cases: [(&str, &str); 10] = [
        (
            "[[wall]]\nfrom = [0.0, 0.0]\nto = [1.0, 0.0]\ncolour = 3\n",
            "bad.toml:8: unknown field `colour`",
        ),
        (
            "[[wall]]\nfrom = [0.0, 0.0]\nto = \"east\"\n",
            "bad.toml:7:",
        ),
        (
            "[[wall]]\nid = \"a\"\nfrom = [0.0, 0.0]\nto = [4.0, 0.0]\n\n[[door]]\nwall = \"b\"\nat = 1.0\nwidth = 1.0\n",
            "bad.toml:11: door #1 wall: no wall has the id `b`",
        ),
        (
            "[[wall]]\nid = \"a\"\nfrom = [0.0, 0.0]\nto = [4.0, 0.0]\n\n[[door]]\nwall = \"a\"\nat = 3.8\nwidth = 1.0\n",
            "bad.toml:12: door #1 at: the opening 3.300..4.300 m does not fit",
        ),
        (
            "[[obstacle]]\nshape = \"circle\"\ncenter = [2.0, 2.0]\nradius = -0.5\n",
            "bad.toml:8: obstacle #1 radius: -0.5 out of range (expected > 0 and <= 100 m)",
        ),
        (
            "[[obstacle]]\nshape = \"triangle\"\ncenter = [2.0, 2.0]\n",
            "bad.toml:6: obstacle #1 shape: unknown shape `triangle`",
        ),
        (
            "[[plate]]\nposition = [2.0, 2.0]\n\n[[plate]]\nposition = [12.0, 2.0]\n",
            "bad.toml:9: plate #2 position: (12, 2) lies outside the bounds",
        ),
        (
            "[[target]]\nname = \"user\"\ncolour = \"purple\"\nposition = [1.0, 1.0]\n",
            "bad.toml:7: unknown variant `purple`",
        ),
        (
            "[[target]]\nname = \"user\"\ncolour = \"yellow\"\nposition = [1.0, 1.0]\nspeed = 0.5\n",
            "bad.toml:5: target #1 waypoints: a target with a speed needs waypoints",
        ),
        (
            "[[pickup_box]]\nid = \"b\"\ncenter = [1.0, 1.0]\nsize = [0.4, 0.4]\n\n[[pickup_box]]\nid = \"b\"\ncenter = [2.0, 1.0]\nsize = [0.4, 0.4]\n",
            "bad.toml:11: pickup_box #2 id: `b` is used twice",
        ),
    ];
    for (body, expected) in cases {
        let got = error_of(&format!("{HEAD}\n{body}"));
        assert!(
            got.starts_with(expected),
            "expected `{expected}`, got `{got}`"
        );
    }
}

#[test]
fn bad_header_fields_report_their_line() {
    let got = error_of(
        "name = \"bad\"\nbounds = { min = [0.0, 0.0], max = [-1.0, 10.0] }\nstart = { x = 1.0, y = 1.0 }\n",
    );
    assert!(
        got.starts_with("bad.toml:2: bounds max: must be above"),
        "{got}"
    );
    let got = error_of("name = \"bad\"\nbounds = { min = [0.0, 0.0], max = [10.0, 10.0] }\n");
    assert!(got.contains("missing field `start`"), "{got}");
    let got = error_of(
        "name = \"bad\"\nbounds = { min = [0.0, 0.0], max = [10.0, 10.0] }\nstart = { x = 11.0, y = 1.0 }\n",
    );
    assert!(got.starts_with("bad.toml:3: start x:"), "{got}");
}
