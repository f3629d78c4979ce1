//! The state machine of Figure 35: NORMAL, AVOIDING (OBS_CONTROL = 1: the
//! detour overrides the position control), RETURNING (OBS_CONTROL = 0: the
//! position controller brings the robot back to its route) and back to
//! NORMAL after a security wait; plus BLOCKED, where the robot stands.

use super::area::{AreaParams, CheckArea, check_length, on_the_way, route_turn};
use super::grid::PointGrid;
use super::side::{Detour, SideParams, corridor_is_free, detour_path, find_free_side};
use crate::path::{Direction, Path};
use crate::pose::Pose;
use nalgebra::Point2;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// `obsavoid(on|off|stop)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum AvoidMode {
    On,
    Off,
    Stop,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum AvoidState {
    Normal,
    Avoiding,
    Returning,
    /// Halted: an obstacle in `stop` mode, or no way round it in `on` mode.
    Blocked,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AvoidParams {
    pub area: AreaParams,
    pub side: SideParams,
    /// Seconds the way must stay clear before RETURNING (or BLOCKED) gives
    /// way to NORMAL (ROBO.INI `bs_security`).
    pub security_wait: f64,
    /// Spacing of detour path samples, m.
    pub spacing: f64,
}

/// What the robot senses this cycle.
#[derive(Clone, Copy, Debug)]
pub struct Observation<'a> {
    pub pose: Pose,
    pub direction: Direction,
    /// Current steering curvature, 1/m.
    pub curvature: f64,
    /// The speed the movement command drives at (its setting, not the
    /// momentary speed): v of equation (11). Were it the momentary speed,
    /// braking for an obstacle would shrink the area until the obstacle
    /// left it, and the robot would start again.
    pub speed: f64,
    /// The route the movement command follows, and the controller's index.
    pub reference: &'a Path,
    pub k: usize,
    /// The environmental map in world coordinates.
    pub points: &'a [Point2<f64>],
    pub dt: f64,
}

/// What the movement command must do this cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Decision<'a> {
    pub state: AvoidState,
    /// OBS_CONTROL: follow `detour` instead of the reference path.
    pub obs_control: bool,
    /// Stand still.
    pub halt: bool,
    pub detour: Option<&'a Path>,
}

/// Map points closer than this to each other belong to one obstacle.
const SAME_OBSTACLE: f64 = 0.25;

/// The obstacle the `seeds` belong to: every map point reachable from them
/// in steps shorter than `SAME_OBSTACLE`, in map order. The area only sees
/// the near face of an obstacle; its far side decides when it is passed.
fn cluster(points: &[Point2<f64>], seeds: &[usize]) -> Vec<Point2<f64>> {
    // Points bucketed in cells as wide as the linking distance, so each
    // step looks at the 3 x 3 cells around a point, not the whole map: a
    // robot standing blocked in a walled room searches every tick.
    let cell = |p: &Point2<f64>| {
        (
            (p.x / SAME_OBSTACLE).floor() as i64,
            (p.y / SAME_OBSTACLE).floor() as i64,
        )
    };
    let mut grid: BTreeMap<(i64, i64), Vec<usize>> = BTreeMap::new();
    for (i, p) in points.iter().enumerate() {
        if p.x.is_finite() && p.y.is_finite() {
            grid.entry(cell(p)).or_default().push(i);
        }
    }
    let mut member = vec![false; points.len()];
    let mut stack: Vec<usize> = seeds
        .iter()
        .copied()
        .filter(|&i| i < points.len())
        .collect();
    for &i in &stack {
        member[i] = true;
    }
    while let Some(i) = stack.pop() {
        let (cx, cy) = cell(&points[i]);
        for dx in -1..=1 {
            for dy in -1..=1 {
                let Some(near) = grid.get(&(cx + dx, cy + dy)) else {
                    continue;
                };
                for &j in near {
                    if !member[j] && (points[j] - points[i]).norm() < SAME_OBSTACLE {
                        member[j] = true;
                        stack.push(j);
                    }
                }
            }
        }
    }
    points
        .iter()
        .zip(member)
        .filter_map(|(p, m)| m.then_some(*p))
        .collect()
}

#[derive(Clone, Debug, PartialEq)]
pub struct Avoider {
    pub mode: AvoidMode,
    state: AvoidState,
    params: AvoidParams,
    /// The obstacle being avoided, in world coordinates.
    obstacle: Vec<Point2<f64>>,
    detour: Option<(Detour, Path)>,
    clear_for: f64,
}

impl Avoider {
    pub fn new(mode: AvoidMode, params: AvoidParams) -> Self {
        Avoider {
            mode,
            state: AvoidState::Normal,
            params,
            obstacle: vec![],
            detour: None,
            clear_for: 0.0,
        }
    }

    pub fn state(&self) -> AvoidState {
        self.state
    }

    /// Changes the mode (`obsavoid(..)` while moving); leaving `on` drops any
    /// detour at once.
    pub fn set_mode(&mut self, mode: AvoidMode) {
        self.mode = mode;
        if mode == AvoidMode::Off || (mode == AvoidMode::Stop && self.state != AvoidState::Blocked)
        {
            self.reset();
        }
    }

    /// Forgets the obstacle: a new movement command starts in NORMAL.
    pub fn reset(&mut self) {
        self.state = AvoidState::Normal;
        self.obstacle.clear();
        self.detour = None;
        self.clear_for = 0.0;
    }

    /// One cycle of the state machine.
    pub fn step(&mut self, obs: &Observation<'_>) -> Decision<'_> {
        self.step_among(obs, None)
    }

    /// As `step`, with `grid` an index of `obs.points`: the checked area
    /// visits only the points near it. The same decisions as `step`.
    pub fn step_indexed(&mut self, obs: &Observation<'_>, grid: &PointGrid) -> Decision<'_> {
        self.step_among(obs, Some(grid))
    }

    fn step_among(&mut self, obs: &Observation<'_>, grid: Option<&PointGrid>) -> Decision<'_> {
        if self.mode == AvoidMode::Off {
            // Avoidance off looks at nothing: the area is not worked out.
            self.reset();
            return Decision {
                state: AvoidState::Normal,
                obs_control: false,
                halt: false,
                detour: None,
            };
        }
        let travel = match obs.direction {
            Direction::Forward => obs.pose,
            Direction::Backward => obs.pose.flipped(),
        };
        let reach =
            self.params.area.front_offset + check_length(self.params.area.max_curvature, obs.speed);
        let max_turn = route_turn(
            obs.reference,
            obs.k,
            &travel,
            obs.direction.sign() * obs.curvature,
            reach,
        );
        let area = CheckArea::turning_at_most(
            &obs.pose,
            obs.direction,
            obs.curvature,
            obs.speed,
            &self.params.area,
            max_turn,
        );
        let mut hits = match grid {
            Some(g) => area.hits_near(obs.points, g),
            None => area.hits(obs.points),
        };
        if self.state != AvoidState::Avoiding {
            let (route, half) = (obs.reference, 0.5 * area.width);
            hits.retain(|h| on_the_way(route, obs.k, &obs.pose, &obs.points[h.index], reach, half));
        }
        let next = match (self.mode, self.state) {
            (AvoidMode::Off, _) => {
                self.reset();
                AvoidState::Normal
            }
            (AvoidMode::Stop, AvoidState::Blocked) | (AvoidMode::On, AvoidState::Blocked) => {
                if hits.is_empty() {
                    self.clear_for += obs.dt;
                    if self.clear_for + 1e-9 >= self.params.security_wait {
                        self.reset();
                        AvoidState::Normal
                    } else {
                        AvoidState::Blocked
                    }
                } else if self.mode == AvoidMode::On {
                    self.clear_for = 0.0;
                    self.start_detour(obs, &hits)
                } else {
                    self.clear_for = 0.0;
                    AvoidState::Blocked
                }
            }
            (AvoidMode::Stop, _) => {
                if hits.is_empty() {
                    AvoidState::Normal
                } else {
                    self.clear_for = 0.0;
                    AvoidState::Blocked
                }
            }
            (AvoidMode::On, AvoidState::Normal) => {
                if hits.is_empty() {
                    AvoidState::Normal
                } else {
                    self.start_detour(obs, &hits)
                }
            }
            (AvoidMode::On, AvoidState::Avoiding) => self.avoiding(obs, &hits),
            (AvoidMode::On, AvoidState::Returning) => {
                if hits.is_empty() {
                    self.clear_for += obs.dt;
                    if self.clear_for + 1e-9 >= self.params.security_wait {
                        self.reset();
                        AvoidState::Normal
                    } else {
                        AvoidState::Returning
                    }
                } else {
                    self.clear_for = 0.0;
                    self.start_detour(obs, &hits)
                }
            }
        };
        self.state = next;
        Decision {
            state: next,
            obs_control: next == AvoidState::Avoiding,
            halt: next == AvoidState::Blocked,
            detour: match next {
                AvoidState::Avoiding => self.detour.as_ref().map(|(_, p)| p),
                _ => None,
            },
        }
    }

    /// Figure 34 B-D: the obstacle is the group of hits; find a side and a
    /// path round it, or stand.
    fn start_detour(&mut self, obs: &Observation<'_>, hits: &[super::Hit]) -> AvoidState {
        let seeds: Vec<usize> = hits.iter().map(|h| h.index).collect();
        let obstacle = cluster(obs.points, &seeds);
        let travel = match obs.direction {
            Direction::Forward => obs.pose,
            Direction::Backward => obs.pose.flipped(),
        };
        let found =
            find_free_side(&travel, &obstacle, obs.points, &self.params.side).and_then(|d| {
                detour_path(
                    &obs.pose,
                    obs.direction,
                    &d,
                    self.params.area.max_curvature,
                    self.params.spacing,
                )
                .ok()
                .map(|p| (d, p))
            });
        match found {
            Some(detour) => {
                self.obstacle = obstacle;
                self.detour = Some(detour);
                self.clear_for = 0.0;
                AvoidState::Avoiding
            }
            None => {
                self.clear_for = 0.0;
                AvoidState::Blocked
            }
        }
    }

    /// Figure 34 E-H: go on round the obstacle until the way back is free
    /// and the rear has passed it (or it has gone away).
    fn avoiding(&mut self, obs: &Observation<'_>, hits: &[super::Hit]) -> AvoidState {
        // While going round, the checked area sweeps over the obstacle being
        // avoided; only a point on the detour lane itself calls for a new
        // plan.
        let half = 0.5 * super::check_width(self.params.side.robot_width);
        let lane_blocked: Vec<usize> = match &self.detour {
            Some((_, path)) => {
                let travel = match obs.direction {
                    Direction::Forward => obs.pose,
                    Direction::Backward => obs.pose.flipped(),
                };
                obs.points
                    .iter()
                    .enumerate()
                    .filter(|(_, p)| travel.to_local(p).x > 0.0 && path.distance_to(p) < half)
                    .map(|(i, _)| i)
                    .collect()
            }
            None => vec![],
        };
        if !lane_blocked.is_empty() {
            let seeds: Vec<super::Hit> = if hits.is_empty() {
                lane_blocked
                    .iter()
                    .map(|&index| super::Hit {
                        index,
                        s: 0.0,
                        n: 0.0,
                    })
                    .collect()
            } else {
                hits.to_vec()
            };
            return self.start_detour(obs, &seeds);
        }
        let travel = match obs.direction {
            Direction::Forward => obs.pose,
            Direction::Backward => obs.pose.flipped(),
        };
        let rear = self.params.side.robot_length - self.params.side.front_offset;
        let rear_passed = self.obstacle.iter().all(|o| travel.to_local(o).x < -rear);
        let still_there = self
            .obstacle
            .iter()
            .any(|o| obs.points.iter().any(|p| (p - o).norm() <= SAME_OBSTACLE));
        let back_to = {
            let r = obs.reference;
            let ahead = self.params.area.front_offset + self.params.side.robot_length;
            let target_s = r.points()[r.clamp_index(obs.k)].s + ahead;
            r.points()
                .iter()
                .find(|p| p.s >= target_s)
                .unwrap_or_else(|| r.last())
                .position()
        };
        // The robot's own pose is not an obstacle: only map points count.
        let way_back_free = corridor_is_free(&obs.pose.position(), &back_to, obs.points, half);
        let finished = self
            .detour
            .as_ref()
            .is_some_and(|(_, p)| p.passed_end(&obs.pose.position()));
        if way_back_free && (rear_passed || !still_there) {
            self.detour = None;
            self.clear_for = 0.0;
            AvoidState::Returning
        } else if finished {
            self.clear_for = 0.0;
            AvoidState::Blocked
        } else {
            AvoidState::Avoiding
        }
    }
}

#[cfg(test)]
mod tests {
    use super::cluster;
    use nalgebra::Point2;

    #[test]
    fn a_cluster_follows_chains_of_near_points_only() {
        // A 3 m wall sampled every 5 cm, a box 1 m off it, and a wall
        // piece in the next cell but beyond the linking distance.
        let mut pts: Vec<Point2<f64>> = (0..=60)
            .map(|i| Point2::new(f64::from(i) * 0.05, 0.0))
            .collect();
        pts.push(Point2::new(1.0, 1.0));
        pts.push(Point2::new(3.3, 0.0));
        let wall = cluster(&pts, &[30]);
        assert_eq!(wall.len(), 61);
        assert_eq!(wall[0], pts[0], "in map order");
        assert_eq!(cluster(&pts, &[61]), vec![Point2::new(1.0, 1.0)]);
        assert!(cluster(&pts, &[99]).is_empty(), "a stale seed is ignored");
    }
}
