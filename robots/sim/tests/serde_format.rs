//! The serde form of the simulator's worlds and robot configuration: every
//! point and vector is the table `{ x, y }`, whatever type holds it in memory.

mod common;

use ilmr_sim::{RobotConfig, World};

const WORLD: &str = r#"
name = "formats"
bounds = { min = [-1.0, -2.0], max = [6.0, 4.0] }
start = { x = 0.5, y = 0.25, heading = 90.0 }

[[wall]]
id = "w"
from = [0.0, 3.0]
to = [5.0, 3.0]
thickness = 0.1

[[door]]
wall = "w"
at = 2.0
width = 1.0

[[obstacle]]
shape = "circle"
center = [3.0, 0.5]
radius = 0.25

[[obstacle]]
shape = "box"
center = [4.0, -1.0]
size = [0.5, 0.25]
heading = 90.0

[[pickup_box]]
id = "b"
center = [1.0, 1.0]
size = [0.4, 0.3]

[[target]]
name = "p"
colour = "yellow"
position = [2.0, 2.0]
speed = 0.5
waypoints = [[3.0, 2.0], [3.0, 1.0]]

[charger]
position = [5.0, 0.0]

[[plate]]
position = [1.0, -1.0]
"#;

#[test]
fn a_world_is_written_with_x_y_tables_and_read_back() {
    let w = common::world(WORLD);
    let text = serde_json::to_string(&w).unwrap_or_default();
    assert_eq!(
        text,
        concat!(
            r#"{"name":"formats","description":"","#,
            r#""bounds":{"min":{"x":-1.0,"y":-2.0},"max":{"x":6.0,"y":4.0}},"#,
            r#""start":{"x":0.5,"y":0.25,"h":1.5707963267948966},"#,
            r#""walls":[{"id":"w","from":{"x":0.0,"y":3.0},"to":{"x":5.0,"y":3.0},"thickness":0.1,"#,
            r#""pieces":[[{"x":0.0,"y":3.0},{"x":1.5,"y":3.0}],[{"x":2.5,"y":3.0},{"x":5.0,"y":3.0}]]}],"#,
            r#""doors":[{"id":"door1","wall":0,"width":1.0,"center":{"x":2.0,"y":3.0},"#,
            r#""jambs":[{"x":1.5,"y":3.0},{"x":2.5,"y":3.0}]}],"#,
            r#""obstacles":[{"Circle":{"center":{"x":3.0,"y":0.5},"radius":0.25}},"#,
            r#"{"Box":{"center":{"x":4.0,"y":-1.0},"axis":{"x":6.123233995736766e-17,"y":1.0},"#,
            r#""half":{"x":0.25,"y":0.125}}}],"#,
            r#""pickup_boxes":[{"id":"b","shape":{"center":{"x":1.0,"y":1.0},"axis":{"x":1.0,"y":0.0},"#,
            r#""half":{"x":0.2,"y":0.15}},"colour":null}],"#,
            r#""targets":[{"name":"p","colour":"yellow","start":{"x":2.0,"y":2.0},"radius":0.25,"#,
            r#""speed":0.5,"waypoints":[{"x":3.0,"y":2.0},{"x":3.0,"y":1.0}],"path":"once"}],"#,
            r#""charger":{"position":{"x":5.0,"y":0.0},"heading":0.0,"radius":0.5,"colour":null},"#,
            r#""plates":[{"position":{"x":1.0,"y":-1.0},"radius":0.05}],"faults":[]}"#,
        )
    );
    let back: Option<World> = serde_json::from_str(&text).ok();
    assert_eq!(back, Some(w));
}

#[test]
fn the_scanner_mount_and_camera_head_are_x_y_tables() {
    let cfg = RobotConfig::workpartner();
    let scanner = serde_json::to_string(&cfg.scanner).unwrap_or_default();
    assert!(
        scanner.contains(r#""mount":{"x":1.0,"y":0.0}"#),
        "{scanner}"
    );
    let camera = serde_json::to_string(&cfg.camera).unwrap_or_default();
    assert!(camera.contains(r#""head":{"x":0.3,"y":0.0}"#), "{camera}");
    let text = serde_json::to_string(&cfg).unwrap_or_default();
    let back: Option<RobotConfig> = serde_json::from_str(&text).ok();
    assert_eq!(back, Some(cfg));
}

#[test]
fn a_scan_writes_its_mount_as_an_x_y_table() {
    let mut s = common::sim(RobotConfig::moro(), common::open_floor(), 1);
    common::run(&mut s, 20);
    let Some(scan) = s.snapshot().scan else {
        panic!("no scan after 0.2 s");
    };
    let text = serde_json::to_string(&*scan).unwrap_or_default();
    assert!(text.contains(r#""mount":{"x":0.85,"y":0.0}"#), "{text}");
}
