//! Worlds: the static and moving things a robot can meet, loaded from the TOML
//! format documented in `robots/worlds/README.md`.

mod error;
mod format;
pub mod limits;
mod shipped;
mod validate;

pub use error::WorldError;
pub use shipped::{SHIPPED, shipped};

use crate::geometry::{Circle, Obb, Point2, Pose, Scene, Shape, Solid, SolidRef, xy};
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
    #[serde(with = "xy")]
    pub min: Point2<f64>,
    #[serde(with = "xy")]
    pub max: Point2<f64>,
}

impl Bounds {
    pub fn contains(&self, p: Point2<f64>) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Wall {
    pub id: String,
    #[serde(with = "xy")]
    pub from: Point2<f64>,
    #[serde(with = "xy")]
    pub to: Point2<f64>,
    pub thickness: f64,
    /// The solid parts left between the door openings, in order from `from`.
    #[serde(with = "xy::pairs")]
    pub pieces: Vec<(Point2<f64>, Point2<f64>)>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Door {
    pub id: String,
    /// Index into [`World::walls`].
    pub wall: usize,
    pub width: f64,
    /// Middle of the opening on the wall's centre line.
    #[serde(with = "xy")]
    pub center: Point2<f64>,
    /// The two jambs, in the wall's direction.
    #[serde(with = "xy::pair")]
    pub jambs: (Point2<f64>, Point2<f64>),
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
    #[serde(with = "xy")]
    pub start: Point2<f64>,
    pub radius: f64,
    /// Walking speed, m/s; 0 keeps the target still.
    pub speed: f64,
    #[serde(with = "xy::seq")]
    pub waypoints: Vec<Point2<f64>>,
    pub path: PathMode,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Charger {
    #[serde(with = "xy")]
    pub position: Point2<f64>,
    /// Radians: the direction a docked robot faces.
    pub heading: f64,
    /// A robot whose reference point stands within this radius, stopped, charges.
    pub radius: f64,
    pub colour: Option<Colour>,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Plate {
    #[serde(with = "xy")]
    pub position: Point2<f64>,
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
