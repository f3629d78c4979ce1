//! The ranges of a world file's numbers and the most entries of each kind
//! (issue 12). Sizes keep to what a building or a yard holds; counts keep a
//! run of the largest world within 1 GB (the simulator's scene and index,
//! the VM's site plan of surface points every 5 cm on both faces of every
//! outline) and each tick's cost bounded: walls and obstacles sit in the
//! scene's spatial index, and the few moving or movable things (targets,
//! pickup boxes) are tested one by one. `robots/worlds/README.md` carries the
//! table made from these constants (`limits_markdown`), kept in step by a test.

/// Largest magnitude of any coordinate, m.
pub const MAX_COORDINATE: f64 = 1e6;
/// Longest side of `bounds`, m: a 10 km site.
pub const MAX_WORLD_SIDE: f64 = 10_000.0;
/// Headings, degrees: one turn either way.
pub const MAX_HEADING_DEG: f64 = 360.0;
/// Thickest wall, m.
pub const MAX_WALL_THICKNESS: f64 = 10.0;
/// Largest obstacle: a circle's radius, a box's side, m.
pub const MAX_OBSTACLE_SIZE: f64 = 100.0;
/// Largest pickup box side, m.
pub const MAX_PICKUP_BOX_SIZE: f64 = 5.0;
/// Largest target radius, m.
pub const MAX_TARGET_RADIUS: f64 = 5.0;
/// Fastest walking target, m/s (a running person is 5-10).
pub const MAX_TARGET_SPEED: f64 = 10.0;
/// Largest charger radius, m.
pub const MAX_CHARGER_RADIUS: f64 = 10.0;
/// Largest floor plate radius, m.
pub const MAX_PLATE_RADIUS: f64 = 1.0;

/// Most walls.
pub const MAX_WALLS: usize = 100_000;
/// Most doors.
pub const MAX_DOORS: usize = 10_000;
/// Most fixed obstacles.
pub const MAX_OBSTACLES: usize = 10_000;
/// Sum of the wall lengths and obstacle outlines, m: the VM's site plan
/// holds about 1.3 KB per metre of it.
pub const MAX_OUTLINE_LENGTH: f64 = 100_000.0;
/// Most pickup boxes.
pub const MAX_PICKUP_BOXES: usize = 100;
/// Most targets.
pub const MAX_TARGETS: usize = 100;
/// Most waypoints of one target.
pub const MAX_WAYPOINTS: usize = 1_000;
/// Most floor plates.
pub const MAX_PLATES: usize = 10_000;
/// Most `[[fault]]` entries.
pub const MAX_FAULTS: usize = 100;

/// The table of `robots/worlds/README.md`: every range and count above.
pub fn limits_markdown() -> String {
    let rows: [(&str, String); 20] = [
        (
            "every coordinate",
            format!("-{0} to {0} m", num(MAX_COORDINATE)),
        ),
        (
            "`bounds` sides",
            format!("> 0 and <= {} m", num(MAX_WORLD_SIDE)),
        ),
        (
            "every `heading`",
            format!("-{0} to {0} deg", num(MAX_HEADING_DEG)),
        ),
        (
            "wall `thickness`",
            format!("> 0 and <= {} m", num(MAX_WALL_THICKNESS)),
        ),
        (
            "door `width`",
            "> 0, and the opening fits on its wall".to_string(),
        ),
        (
            "obstacle `radius`, `size`",
            format!("> 0 and <= {} m", num(MAX_OBSTACLE_SIZE)),
        ),
        (
            "pickup_box `size`",
            format!("> 0 and <= {} m", num(MAX_PICKUP_BOX_SIZE)),
        ),
        (
            "target `radius`",
            format!("> 0 and <= {} m", num(MAX_TARGET_RADIUS)),
        ),
        (
            "target `speed`",
            format!("0 to {} m/s", num(MAX_TARGET_SPEED)),
        ),
        (
            "charger `radius`",
            format!("> 0 and <= {} m", num(MAX_CHARGER_RADIUS)),
        ),
        (
            "plate `radius`",
            format!("> 0 and <= {} m", num(MAX_PLATE_RADIUS)),
        ),
        ("`[[wall]]` entries", num(MAX_WALLS as f64)),
        ("`[[door]]` entries", num(MAX_DOORS as f64)),
        ("`[[obstacle]]` entries", num(MAX_OBSTACLES as f64)),
        (
            "wall lengths plus obstacle outlines",
            format!("{} m in all", num(MAX_OUTLINE_LENGTH)),
        ),
        ("`[[pickup_box]]` entries", num(MAX_PICKUP_BOXES as f64)),
        ("`[[target]]` entries", num(MAX_TARGETS as f64)),
        ("`waypoints` of one target", num(MAX_WAYPOINTS as f64)),
        ("`[[plate]]` entries", num(MAX_PLATES as f64)),
        ("`[[fault]]` entries", num(MAX_FAULTS as f64)),
    ];
    let mut out = String::from("| what | admits |\n| --- | --- |\n");
    for (what, admits) in rows {
        out.push_str(&format!("| {what} | {admits} |\n"));
    }
    out
}

/// A limit as the docs write it: `100,000`, `1e6`.
fn num(v: f64) -> String {
    if v >= 1e6 {
        return format!("{v:e}");
    }
    let digits = (v as u64).to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// A value in a message: as written when short, in exponent form when `{}`
/// would print hundreds of digits.
pub(crate) fn shown(v: f64) -> String {
    let a = v.abs();
    if a.is_finite() && a != 0.0 && !(1e-6..1e9).contains(&a) {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}
