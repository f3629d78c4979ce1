//! The world file as written: serde structures mirroring the TOML text one to
//! one. `validate` turns them into a [`super::World`]; nothing else reads them.

use super::Colour;
use serde::Deserialize;
use toml::Spanned;

pub type Point = [f64; 2];

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldFile {
    pub name: String,
    #[serde(default)]
    pub description: String,
    pub bounds: Spanned<BoundsDef>,
    pub start: Spanned<StartDef>,
    #[serde(default)]
    pub wall: Vec<Spanned<WallDef>>,
    #[serde(default)]
    pub door: Vec<Spanned<DoorDef>>,
    #[serde(default)]
    pub obstacle: Vec<Spanned<ObstacleDef>>,
    #[serde(default)]
    pub pickup_box: Vec<Spanned<PickupBoxDef>>,
    #[serde(default)]
    pub target: Vec<Spanned<TargetDef>>,
    pub charger: Option<Spanned<ChargerDef>>,
    #[serde(default)]
    pub plate: Vec<Spanned<PlateDef>>,
    #[serde(default)]
    pub fault: Vec<Spanned<crate::faults::world::FaultDef>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundsDef {
    pub min: Point,
    pub max: Point,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StartDef {
    pub x: f64,
    pub y: f64,
    /// Degrees, counter-clockwise from +x.
    #[serde(default)]
    pub heading: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallDef {
    pub id: Option<String>,
    pub from: Point,
    pub to: Point,
    pub thickness: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoorDef {
    pub id: Option<String>,
    pub wall: String,
    /// Distance from the wall's `from` end to the middle of the opening.
    pub at: f64,
    pub width: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObstacleDef {
    pub shape: String,
    pub center: Point,
    pub radius: Option<f64>,
    pub size: Option<Point>,
    pub heading: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PickupBoxDef {
    pub id: String,
    pub center: Point,
    pub size: Point,
    #[serde(default)]
    pub heading: f64,
    pub colour: Option<Colour>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TargetDef {
    pub name: String,
    pub colour: Colour,
    pub position: Point,
    pub radius: Option<f64>,
    #[serde(default)]
    pub speed: f64,
    #[serde(default)]
    pub waypoints: Vec<Point>,
    #[serde(default)]
    pub path: super::PathMode,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChargerDef {
    pub position: Point,
    #[serde(default)]
    pub heading: f64,
    pub radius: Option<f64>,
    pub colour: Option<Colour>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlateDef {
    pub position: Point,
    pub radius: Option<f64>,
}
