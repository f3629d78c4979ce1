//! Every number of a world file has a range and every list a limit (issue
//! 12): NaN, infinity and huge values in each numeric field, too many
//! entries, the target at 1e12 m/s on a loop, a world of 100,000 walls. Each
//! ends with an error naming file, line, entry and field, or runs within
//! bounds; none panics or hangs.

mod common;

use ilmr_sim::world::limits::*;
use ilmr_sim::{RobotConfig, World};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

const HEAD: &str = r#"name = "bad"
bounds = { min = [0.0, 0.0], max = [10.0, 10.0] }
start = { x = 1.0, y = 1.0 }
"#;

fn error_of(text: &str) -> String {
    match World::from_toml(text, "bad.toml") {
        Ok(_) => panic!("world should not load:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Each numeric field of each entry, as `(entry text with X for the value,
/// the error's start)`.
const FIELDS: &[(&str, &str)] = &[
    (
        "name = \"b\"\nbounds = { min = [X, 0.0], max = [10.0, 10.0] }\nstart = { x = 1.0, y = 1.0 }\n",
        "bad.toml:2: bounds min:",
    ),
    (
        "name = \"b\"\nbounds = { min = [0.0, 0.0], max = [10.0, X] }\nstart = { x = 1.0, y = 1.0 }\n",
        "bad.toml:2: bounds max:",
    ),
    (
        "name = \"b\"\nbounds = { min = [0.0, 0.0], max = [10.0, 10.0] }\nstart = { x = X, y = 1.0 }\n",
        "bad.toml:3: start x:",
    ),
    (
        "name = \"b\"\nbounds = { min = [0.0, 0.0], max = [10.0, 10.0] }\nstart = { x = 1.0, y = 1.0, heading = X }\n",
        "bad.toml:3: start heading:",
    ),
    (
        "[[wall]]\nfrom = [X, 0.0]\nto = [1.0, 0.0]\n",
        "bad.toml:6: wall #1 from:",
    ),
    (
        "[[wall]]\nfrom = [0.0, 0.0]\nto = [1.0, X]\n",
        "bad.toml:7: wall #1 to:",
    ),
    (
        "[[wall]]\nfrom = [0.0, 0.0]\nto = [1.0, 0.0]\nthickness = X\n",
        "bad.toml:8: wall #1 thickness:",
    ),
    (
        "[[wall]]\nid = \"a\"\nfrom = [0.0, 0.0]\nto = [4.0, 0.0]\n[[door]]\nwall = \"a\"\nat = X\nwidth = 1.0\n",
        "bad.toml:11: door #1 at:",
    ),
    (
        "[[wall]]\nid = \"a\"\nfrom = [0.0, 0.0]\nto = [4.0, 0.0]\n[[door]]\nwall = \"a\"\nat = 2.0\nwidth = X\n",
        "bad.toml:12: door #1 width:",
    ),
    (
        "[[obstacle]]\nshape = \"circle\"\ncenter = [X, 2.0]\nradius = 0.5\n",
        "bad.toml:7: obstacle #1 center:",
    ),
    (
        "[[obstacle]]\nshape = \"circle\"\ncenter = [2.0, 2.0]\nradius = X\n",
        "bad.toml:8: obstacle #1 radius:",
    ),
    (
        "[[obstacle]]\nshape = \"box\"\ncenter = [2.0, 2.0]\nsize = [X, 1.0]\n",
        "bad.toml:8: obstacle #1 size:",
    ),
    (
        "[[obstacle]]\nshape = \"box\"\ncenter = [2.0, 2.0]\nsize = [1.0, 1.0]\nheading = X\n",
        "bad.toml:9: obstacle #1 heading:",
    ),
    (
        "[[pickup_box]]\nid = \"b\"\ncenter = [2.0, X]\nsize = [0.4, 0.4]\n",
        "bad.toml:7: pickup_box #1 center:",
    ),
    (
        "[[pickup_box]]\nid = \"b\"\ncenter = [2.0, 2.0]\nsize = [0.4, X]\n",
        "bad.toml:8: pickup_box #1 size:",
    ),
    (
        "[[pickup_box]]\nid = \"b\"\ncenter = [2.0, 2.0]\nsize = [0.4, 0.4]\nheading = X\n",
        "bad.toml:9: pickup_box #1 heading:",
    ),
    (
        "[[target]]\nname = \"u\"\ncolour = \"yellow\"\nposition = [X, 1.0]\n",
        "bad.toml:8: target #1 position:",
    ),
    (
        "[[target]]\nname = \"u\"\ncolour = \"yellow\"\nposition = [1.0, 1.0]\nradius = X\n",
        "bad.toml:9: target #1 radius:",
    ),
    (
        "[[target]]\nname = \"u\"\ncolour = \"yellow\"\nposition = [1.0, 1.0]\nspeed = X\nwaypoints = [[2.0, 2.0]]\n",
        "bad.toml:9: target #1 speed:",
    ),
    (
        "[[target]]\nname = \"u\"\ncolour = \"yellow\"\nposition = [1.0, 1.0]\nwaypoints = [[2.0, X]]\n",
        "bad.toml:9: target #1 waypoints:",
    ),
    (
        "[charger]\nposition = [X, 1.0]\n",
        "bad.toml:6: charger position:",
    ),
    (
        "[charger]\nposition = [1.0, 1.0]\nheading = X\n",
        "bad.toml:7: charger heading:",
    ),
    (
        "[charger]\nposition = [1.0, 1.0]\nradius = X\n",
        "bad.toml:7: charger radius:",
    ),
    (
        "[[plate]]\nposition = [1.0, X]\n",
        "bad.toml:6: plate #1 position:",
    ),
    (
        "[[plate]]\nposition = [1.0, 1.0]\nradius = X\n",
        "bad.toml:7: plate #1 radius:",
    ),
];

#[test]
fn nan_infinity_and_huge_values_are_refused_in_every_field() {
    for value in ["nan", "-nan", "inf", "-inf", "1e308", "-1e308", "1e12"] {
        for (entry, expected) in FIELDS {
            let text = if entry.starts_with("name") {
                entry.replace('X', value)
            } else {
                format!("{HEAD}\n{}", entry.replace('X', value))
            };
            let got = error_of(&text);
            assert!(
                got.starts_with(expected),
                "{value}: expected `{expected}`, got `{got}`\n{text}"
            );
        }
    }
}

#[test]
fn out_of_range_values_say_what_is_expected() {
    let cases = [
        (
            "[[target]]\nname = \"u\"\ncolour = \"yellow\"\nposition = [1.0, 1.0]\nspeed = 1e12\nwaypoints = [[2.0, 2.0]]\npath = \"loop\"\n",
            "bad.toml:9: target #1 speed: 1e12 out of range (expected 0 to 10 m/s)",
        ),
        (
            "[[wall]]\nfrom = [0.0, 0.0]\nto = [1.0, 0.0]\nthickness = 20\n",
            "bad.toml:8: wall #1 thickness: 20 out of range (expected > 0 and <= 10 m)",
        ),
        (
            "[[obstacle]]\nshape = \"circle\"\ncenter = [2.0, 2.0]\nradius = nan\n",
            "bad.toml:8: obstacle #1 radius: NaN is not a number (expected > 0 and <= 100 m)",
        ),
        (
            "[[obstacle]]\nshape = \"circle\"\ncenter = [2.0, 2.0]\nradius = -0.5\n",
            "bad.toml:8: obstacle #1 radius: -0.5 out of range (expected > 0 and <= 100 m)",
        ),
    ];
    for (body, expected) in cases {
        assert_eq!(error_of(&format!("{HEAD}\n{body}")), expected);
    }
    let got = error_of(
        "name = \"b\"\nbounds = { min = [0.0, 0.0], max = [20000.0, 10.0] }\nstart = { x = 1.0, y = 1.0 }\n",
    );
    assert_eq!(
        got,
        "bad.toml:2: bounds max: a side of 20000 m out of range (expected at most 10000 m)"
    );
}

/// A world of `n` entries made by `entry(i)`, on a 10 km site.
fn many(n: usize, entry: impl Fn(usize) -> String) -> String {
    let mut text = String::from(
        "name = \"many\"\nbounds = { min = [0.0, 0.0], max = [10000.0, 10000.0] }\nstart = { x = 5.0, y = 5.0 }\n",
    );
    for i in 0..n {
        text.push_str(&entry(i));
    }
    text
}

fn short_wall(i: usize) -> String {
    let (x, y) = (
        20.0 + (i % 3000) as f64 * 3.0,
        20.0 + (i / 3000) as f64 * 3.0,
    );
    format!("[[wall]]\nfrom = [{x}, {y}]\nto = [{}, {y}]\n", x + 0.8)
}

#[test]
fn too_many_entries_are_refused_at_the_first_one_past_the_limit() {
    let text = many(MAX_WALLS + 1, short_wall);
    let got = error_of(&text);
    let line = 4 + 3 * MAX_WALLS;
    assert_eq!(
        got,
        format!(
            "bad.toml:{line}: wall #{}: {} [[wall]] entries out of range (expected at most {MAX_WALLS})",
            MAX_WALLS + 1,
            MAX_WALLS + 1
        )
    );
    type Entry = fn(usize) -> String;
    let checks: [(&str, usize, Entry); 5] = [
        ("obstacle", MAX_OBSTACLES, |i| {
            format!(
                "[[obstacle]]\nshape = \"circle\"\ncenter = [{}.0, 50.0]\nradius = 0.1\n",
                10 + i % 9000
            )
        }),
        ("pickup_box", MAX_PICKUP_BOXES, |i| {
            format!(
                "[[pickup_box]]\nid = \"b{i}\"\ncenter = [{}.0, 50.0]\nsize = [0.4, 0.4]\n",
                10 + i
            )
        }),
        ("target", MAX_TARGETS, |i| {
            format!(
                "[[target]]\nname = \"t{i}\"\ncolour = \"red\"\nposition = [{}.0, 50.0]\n",
                10 + i
            )
        }),
        ("plate", MAX_PLATES, |i| {
            format!("[[plate]]\nposition = [{}.0, 60.0]\n", 10 + i % 9000)
        }),
        ("fault", MAX_FAULTS, |_| {
            "[[fault]]\nkind = \"scanner_dropout\"\n".to_string()
        }),
    ];
    for (what, max, entry) in checks {
        let got = error_of(&many(max + 1, entry));
        assert!(
            got.contains(&format!(
                "{what} #{}: {} [[{what}]] entries out of range (expected at most {max})",
                max + 1,
                max + 1
            )),
            "{got}"
        );
    }
    let mut waypoints = String::new();
    for i in 0..=MAX_WAYPOINTS {
        let _ = write!(waypoints, "[{}.0, 7.0],", 10 + i);
    }
    let got = error_of(&many(0, |_| String::new()).replace(
        "start = { x = 5.0, y = 5.0 }\n",
        &format!("start = {{ x = 5.0, y = 5.0 }}\n[[target]]\nname = \"u\"\ncolour = \"red\"\nposition = [5.0, 5.0]\nspeed = 1.0\nwaypoints = [{waypoints}]\n"),
    ));
    assert!(
        got.contains("target #1 waypoints: 1001 waypoints out of range (expected at most 1000)"),
        "{got}"
    );
}

#[test]
fn too_much_outline_is_refused() {
    // 11 walls of 9,999 m: the 11th passes 100 km.
    let got = error_of(&many(11, |i| {
        format!(
            "[[wall]]\nfrom = [0.5, {}.0]\nto = [9999.5, {}.0]\n",
            10 + i,
            10 + i
        )
    }));
    assert!(
        got.contains("wall #11 to: the walls and obstacles so far measure 109989 m, out of range"),
        "{got}"
    );
}

#[test]
fn a_world_of_the_most_walls_loads_and_runs_in_bounded_time() {
    let started = Instant::now();
    let text = many(MAX_WALLS, short_wall);
    let world = match World::from_toml(&text, "many.toml") {
        Ok(w) => w,
        Err(e) => panic!("{e}"),
    };
    assert_eq!(world.walls.len(), MAX_WALLS);
    let mut sim = common::sim(RobotConfig::moro(), world, 3);
    let _ = sim.set_setpoints(0.3, 0.0);
    // Two simulated seconds: eight scans among the walls.
    common::run(&mut sim, 200);
    assert!(sim.snapshot().scan.is_some());
    // A guard against a hang, not a benchmark (debug build, shared machine).
    assert!(
        started.elapsed() < Duration::from_secs(120),
        "{:?}",
        started.elapsed()
    );
}

#[test]
fn the_readme_limits_table_is_fresh() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../worlds/README.md");
    let doc = std::fs::read_to_string(path).expect("robots/worlds/README.md");
    let start =
        "<!-- limits-table:start (generated by ilmr_sim::world::limits::limits_markdown) -->\n";
    let end = "<!-- limits-table:end -->";
    let (Some(s), Some(e)) = (doc.find(start), doc.find(end)) else {
        panic!("robots/worlds/README.md lacks the limits-table markers");
    };
    let generated = limits_markdown();
    if doc[s + start.len()..e] != generated {
        if std::env::var_os("ILMR_UPDATE_DOCS").is_some() {
            let updated = format!("{}{generated}{}", &doc[..s + start.len()], &doc[e..]);
            std::fs::write(path, updated).expect("rewrite README");
        } else {
            panic!(
                "the limits table in robots/worlds/README.md is stale; rerun with ILMR_UPDATE_DOCS=1"
            );
        }
    }
}
