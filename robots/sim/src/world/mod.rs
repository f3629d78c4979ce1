//! Worlds: the static and moving things a robot can meet, loaded from the TOML
//! format documented in `robots/worlds/README.md`.

mod error;
mod format;
pub mod limits;
mod shipped;
mod validate;

pub use error::WorldError;
pub use shipped::{SHIPPED, shipped};

use crate::geometry::{Circle, Obb, Pose, Scene, Shape, Solid, SolidRef, Vec2};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Colours that the camera can tell apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Colour {
    Yellow,
    Red,
    Green,
    Blue,
    Orange,
    White,
}

/// How a moving target walks its waypoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PathMode {
    /// Walk from the start through every waypoint once, then stand.
    #[default]
    Once,
    /// After the last waypoint, walk back to the start and round again.
    Loop,
    /// Walk the waypoints forward, then backward, forever.
    BackAndForth,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Bounds {
    pub min: Vec2,
    pub max: Vec2,
}

impl Bounds {
    pub fn contains(&self, p: Vec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Wall {
    pub id: String,
    pub from: Vec2,
    pub to: Vec2,
    pub thickness: f64,
    /// The solid parts left between the door openings, in order from `from`.
    pub pieces: Vec<(Vec2, Vec2)>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Door {
    pub id: String,
    /// Index into [`World::walls`].
    pub wall: usize,
    pub width: f64,
    /// Middle of the opening on the wall's centre line.
    pub center: Vec2,
    /// The two jambs, in the wall's direction.
    pub jambs: (Vec2, Vec2),
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PickupBox {
    pub id: String,
    pub shape: Obb,
    pub colour: Option<Colour>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Target {
    pub name: String,
    pub colour: Colour,
    pub start: Vec2,
    pub radius: f64,
    /// Walking speed, m/s; 0 keeps the target still.
    pub speed: f64,
    pub waypoints: Vec<Vec2>,
    pub path: PathMode,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Charger {
    pub position: Vec2,
    /// Radians: the direction a docked robot faces.
    pub heading: f64,
    /// A robot whose reference point stands within this radius, stopped, charges.
    pub radius: f64,
    pub colour: Option<Colour>,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Plate {
    pub position: Vec2,
    pub radius: f64,
}

/// A validated world. Every number is finite, every size positive, and every
/// thing lies inside `bounds`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct World {
    pub name: String,
    pub description: String,
    pub bounds: Bounds,
    pub start: Pose,
    pub walls: Vec<Wall>,
    pub doors: Vec<Door>,
    pub obstacles: Vec<Shape>,
    pub pickup_boxes: Vec<PickupBox>,
    pub targets: Vec<Target>,
    pub charger: Option<Charger>,
    pub plates: Vec<Plate>,
    /// Faults to inject, in file order (`[[fault]]`, see `crate::faults`).
    #[serde(default)]
    pub faults: Vec<crate::faults::FaultSpec>,
}

impl World {
    /// Parses and validates world text; `source` names it in errors.
    pub fn from_toml(text: &str, source: &str) -> Result<World, WorldError> {
        validate::parse(text, source)
    }

    pub fn from_path(path: &Path) -> Result<World, WorldError> {
        let source = path.display().to_string();
        let text =
            ilmr_files::read_text(path, ilmr_files::Kind::World).map_err(|e| WorldError {
                source: source.clone(),
                line: 0,
                field: None,
                message: format!("cannot read the world file: {e}"),
            })?;
        World::from_toml(&text, &source)
    }

    /// Every solid: wall pieces, obstacles, pickup boxes and targets (at their
    /// start positions), in that order.
    pub fn scene(&self) -> Scene {
        let mut solids = Vec::new();
        let mut piece = 0;
        for w in &self.walls {
            for &(a, b) in &w.pieces {
                solids.push(Solid::new(
                    Shape::Box(Obb::from_segment(a, b, w.thickness)),
                    SolidRef::Wall(piece),
                ));
                piece += 1;
            }
        }
        for (i, o) in self.obstacles.iter().enumerate() {
            solids.push(Solid::new(*o, SolidRef::Obstacle(i)));
        }
        for (i, b) in self.pickup_boxes.iter().enumerate() {
            solids.push(Solid::new(Shape::Box(b.shape), SolidRef::PickupBox(i)));
        }
        for (i, t) in self.targets.iter().enumerate() {
            solids.push(Solid::new(
                Shape::Circle(Circle::new(t.start, t.radius)),
                SolidRef::Target(i),
            ));
        }
        Scene::new(solids)
    }
}
