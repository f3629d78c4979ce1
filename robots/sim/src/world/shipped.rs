//! The worlds shipped in `robots/worlds`, compiled into the crate.

use super::{World, WorldError};

/// Name and text of every shipped world.
pub const SHIPPED: [(&str, &str); 3] = [
    ("empty", include_str!("../../../worlds/empty.toml")),
    ("office", include_str!("../../../worlds/office.toml")),
    ("yard", include_str!("../../../worlds/yard.toml")),
];

/// A shipped world by name (`empty`, `office`, `yard`); `None` for any other name.
pub fn shipped(name: &str) -> Option<Result<World, WorldError>> {
    SHIPPED
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(name))
        .map(|(n, text)| World::from_toml(text, &format!("<{n}>")))
}
