//! Walls from scanner points, the goals of `followwall` (section 4.5.3) and
//! the space check of `turn(left|right)`.

mod fit;
mod goal;
mod space;

pub use fit::{WallError, WallLine, WallParams, fit_wall};
pub use goal::{FOLLOWWALL_AHEAD, FOLLOWWALL_REPLAN, followwall_goal, middle_goal};
pub use space::{Outline, TurnRoom, leg_short_of_wall, path_is_free, turn_space_free};
