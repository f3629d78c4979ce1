//! What a figure shows, whatever it was made from: one run's trace (`Figure::of_run`,
//! for `ilmrc run --plot` and `ilmrc replay`) or several runs of an experiment drawn
//! together (the dissertation's Figures 46-59). Both are drawn by the same code.

use std::path::Path;

use ilmr_sim::World;

use crate::data::{Mark, RunRecord, Sample};

/// An RGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Colour(pub u8, pub u8, pub u8);

impl Colour {
    /// A run's true trajectory when it is the only one.
    pub const TRUE_PATH: Colour = Colour(20, 60, 170);
    /// Reference and ideal paths.
    pub const REFERENCE: Colour = Colour(40, 40, 40);

    /// The `i`th colour of Okabe and Ito's palette, which stays distinguishable for
    /// colour-blind readers; it repeats after seven.
    pub fn palette(i: usize) -> Colour {
        const OKABE_ITO: [Colour; 7] = [
            Colour(0, 114, 178),
            Colour(213, 94, 0),
            Colour(0, 158, 115),
            Colour(204, 121, 167),
            Colour(230, 159, 0),
            Colour(86, 180, 233),
            Colour(0, 0, 0),
        ];
        OKABE_ITO[i % OKABE_ITO.len()]
    }
}

/// A world drawn under the paths; `tint` colours its walls and obstacles (to tell the
/// worlds of one figure apart) instead of grey.
#[derive(Debug, Clone)]
pub struct Scenery {
    pub world: World,
    pub tint: Option<Colour>,
}

/// A driven path. Tracks with the same label share one legend entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    pub label: Option<String>,
    pub colour: Colour,
    pub samples: Vec<Sample>,
}

/// Many runs of one experiment (one per seed): each drawn thin and pale, their mean
/// drawn over them, so that the picture shows how far the runs spread.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSpread {
    /// The legend's name of the runs; the mean's is "mean of" it.
    pub label: String,
    pub colour: Colour,
    pub runs: Vec<Vec<(f64, f64)>>,
    pub mean: Vec<(f64, f64)>,
}

/// A path drawn dashed: a reference, an ideal route or a recording.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    pub label: Option<String>,
    pub colour: Colour,
    pub points: Vec<(f64, f64)>,
}

/// The robot's outline round its reference point (the point the pose is of), for
/// footprints on the map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    pub length: f64,
    pub width: f64,
    /// From the rear edge forward to the reference point.
    pub rear_overhang: f64,
}

impl Footprint {
    /// The shipped robot a trace names (`moro`, `workpartner`); `None` for a model
    /// given by its file, whose body the trace does not hold.
    pub fn of_robot(name: &str) -> Option<Footprint> {
        let kind = match name {
            "moro" => ilmr_sim::RobotKind::Moro,
            "workpartner" => ilmr_sim::RobotKind::Workpartner,
            _ => return None,
        };
        let b = ilmr_sim::RobotConfig::for_kind(kind).body;
        Some(Footprint {
            length: b.length,
            width: b.width,
            rear_overhang: b.rear_overhang,
        })
    }

    /// The outline's corners at pose (x, y, h), world frame: rear right, front right,
    /// front left, rear left.
    pub fn corners(&self, x: f64, y: f64, h: f64) -> [(f64, f64); 4] {
        let (s, c) = h.sin_cos();
        let at = |fwd: f64, left: f64| (x + fwd * c - left * s, y + fwd * s + left * c);
        let (rear, front, half) = (
            -self.rear_overhang,
            self.length - self.rear_overhang,
            self.width / 2.0,
        );
        [
            at(rear, -half),
            at(front, -half),
            at(front, half),
            at(rear, half),
        ]
    }
}

/// Where the map's legend sits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corner {
    /// The corner of the map with the fewest trajectory samples and marks in it.
    Quietest,
    UpperLeft,
    UpperRight,
    LowerLeft,
    LowerRight,
}

#[derive(Debug, Clone)]
pub struct Figure {
    pub title: String,
    pub scenery: Vec<Scenery>,
    /// Scanner hits in the world frame.
    pub hits: Vec<(f64, f64)>,
    pub references: Vec<Reference>,
    pub tracks: Vec<Track>,
    /// Runs drawn thin with their mean, under the tracks.
    pub spreads: Vec<RunSpread>,
    /// Where movement commands started and ended.
    pub marks: Vec<Mark>,
    /// Speed and curvature of every track over time, below the map (Figure 54).
    pub time_series: bool,
    /// The robot's footprint and heading, drawn where each movement started and at
    /// the time ticks; none when `None`.
    pub body: Option<Footprint>,
    /// Ticks along the first track at round times, labelled in seconds.
    pub time_ticks: bool,
    pub legend: Corner,
}

impl Figure {
    /// A map with nothing on it yet and no time series.
    pub fn new(title: impl Into<String>) -> Figure {
        Figure {
            title: title.into(),
            scenery: Vec::new(),
            hits: Vec::new(),
            references: Vec::new(),
            tracks: Vec::new(),
            spreads: Vec::new(),
            marks: Vec::new(),
            time_series: false,
            body: None,
            time_ticks: false,
            legend: Corner::UpperRight,
        }
    }

    /// One run as `ilmrc run --plot` draws it: its world, hits, the VM's reference
    /// paths, the true trajectory, the marks, and speed and curvature below.
    pub fn of_run(record: &RunRecord) -> Result<Figure, String> {
        let mut figure = Figure::new(title(record));
        figure
            .scenery
            .extend(record.world()?.map(|world| Scenery { world, tint: None }));
        figure.hits = record.hits.clone();
        figure.references = record
            .refs
            .iter()
            .map(|r| Reference {
                label: Some("reference path".into()),
                colour: Colour::REFERENCE,
                points: r.points.clone(),
            })
            .collect();
        figure.tracks.push(Track {
            label: Some("true trajectory".into()),
            colour: Colour::TRUE_PATH,
            samples: record.poses.clone(),
        });
        figure.marks = record.marks.clone();
        figure.time_series = true;
        figure.time_ticks = true;
        figure.legend = Corner::Quietest;
        figure.body = record
            .header
            .as_ref()
            .and_then(|h| Footprint::of_robot(&h.robot));
        Ok(figure)
    }

    /// The figure as SVG text.
    pub fn to_svg(&self) -> Result<String, String> {
        crate::render::svg(self)
    }

    pub fn write_svg(&self, path: &Path) -> Result<(), String> {
        let svg = self.to_svg()?;
        std::fs::write(path, svg)
            .map_err(|e| format!("cannot write plot `{}`: {e}", path.display()))
    }
}

/// A run's title: the task, and the robot, world and seed when the trace says.
fn title(record: &RunRecord) -> String {
    match &record.header {
        Some(h) => format!("{}: {} in {}, seed {}", h.task, h.robot, h.world, h.seed),
        None => "ILMR run".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn samples(points: &[(f64, f64)]) -> Vec<Sample> {
        points
            .iter()
            .enumerate()
            .map(|(i, &(x, y))| Sample {
                t: i as f64,
                x,
                y,
                h: 0.0,
                v: 0.3,
                c: 0.0,
            })
            .collect()
    }

    fn track(label: &str, colour: Colour, points: &[(f64, f64)]) -> Track {
        Track {
            label: Some(label.into()),
            colour,
            samples: samples(points),
        }
    }

    fn height(svg: &str) -> u32 {
        let at = svg.find("height=\"").expect("an SVG height") + 8;
        svg[at..]
            .split('"')
            .next()
            .and_then(|h| h.parse().ok())
            .expect("a number")
    }

    #[test]
    fn tracks_that_share_a_label_share_one_legend_entry() {
        let mut f = Figure::new("trials");
        for i in 0..3 {
            let y = f64::from(i);
            f.tracks
                .push(track("sweep A", Colour::palette(0), &[(0.0, y), (2.0, y)]));
        }
        f.tracks.push(track(
            "sweep B",
            Colour::palette(1),
            &[(0.0, 5.0), (2.0, 5.0)],
        ));
        let svg = f.to_svg().expect("drawn");
        assert_eq!(svg.matches("sweep A").count(), 1, "one entry for A");
        assert_eq!(svg.matches("sweep B").count(), 1);
        // Each track drawn in its colour.
        assert!(svg.contains("stroke=\"#0072B2\""), "A's colour");
        assert!(svg.contains("stroke=\"#D55E00\""), "B's colour");
    }

    #[test]
    fn a_spread_draws_each_run_pale_and_its_mean_over_them() {
        let mut f = Figure::new("seeds");
        let runs: Vec<Vec<(f64, f64)>> = (0..4)
            .map(|i| vec![(0.0, f64::from(i)), (2.0, f64::from(i))])
            .collect();
        f.spreads.push(RunSpread {
            label: "seeds".into(),
            colour: Colour::palette(0),
            runs,
            mean: vec![(0.0, 1.5), (2.0, 1.5)],
        });
        let svg = f.to_svg().expect("drawn");
        // One legend entry for the runs and one for the mean.
        assert_eq!(svg.matches("seeds (4 runs)").count(), 1);
        assert_eq!(svg.matches("mean of seeds").count(), 1);
        // Four pale runs (and the legend's sample), one thick mean (and its sample).
        let pale = "opacity=\"0.35\" stroke=\"#0072B2\" stroke-width=\"1\"";
        assert_eq!(svg.matches(pale).count(), 5);
        let thick = "opacity=\"1\" stroke=\"#0072B2\" stroke-width=\"3\"";
        assert_eq!(svg.matches(thick).count(), 2);
    }

    #[test]
    fn the_time_series_panels_are_drawn_only_when_asked() {
        let mut f = Figure::new("one run");
        f.tracks
            .push(track("run", Colour::TRUE_PATH, &[(0.0, 0.0), (3.0, 1.0)]));
        let map_only = f.to_svg().expect("drawn");
        f.time_series = true;
        let with_series = f.to_svg().expect("drawn");
        assert!(!map_only.contains("time (s)"));
        assert!(with_series.contains("time (s)") && with_series.contains("curvature (1/m)"));
        assert_eq!(height(&with_series), height(&map_only) + 2 * 220);
    }

    #[test]
    fn a_tinted_world_is_drawn_in_its_tint() {
        let world = World::from_toml(
            "name = \"w\"\nbounds = { min = [-5.0, -5.0], max = [5.0, 5.0] }\n\
             start = { x = 0.0, y = 0.0, heading = 0.0 }\n[[wall]]\nfrom = [-4.0, 2.0]\nto = [4.0, 2.0]\n",
            "<test>",
        )
        .expect("a world");
        let mut f = Figure::new("walls");
        f.tracks
            .push(track("run", Colour::TRUE_PATH, &[(0.0, 0.0), (3.0, 0.0)]));
        f.scenery.push(Scenery {
            world: world.clone(),
            tint: None,
        });
        let grey = f.to_svg().expect("drawn");
        f.scenery[0].tint = Some(Colour(1, 2, 3));
        let tinted = f.to_svg().expect("drawn");
        let tint = |svg: &str| svg.contains("\"#010203\"");
        assert!(tint(&tinted) && !tint(&grey));
    }
}
