//! The vocabulary the layers below the VM share, so that the HAL, the motion
//! algorithms and the simulator speak of one pose, fold angles one way and draw
//! noise from one generator: a value handed from one layer to another needs no
//! conversion, and a seed means the same thing everywhere.
//!
//! Points and vectors are nalgebra's ([`Point2`], [`Vector2`]), in the motion
//! code, the VM and the simulator alike; [`PlaneVector`] adds what the plane
//! needs that nalgebra lacks, and [`xy`] writes them as `{ x, y }` tables.

pub mod angle;
pub mod plane;
pub mod pose;
pub mod rng;
pub mod side;

pub use angle::{angle_diff, wrap_angle};
pub use nalgebra::{Point2, Vector2};
pub use plane::{PlaneVector, xy};
pub use pose::Pose;
pub use rng::{Rng, SplitMix64};
pub use side::Side;
