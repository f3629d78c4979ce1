//! Speed and curvature over time (Figure 54), from the tracks' samples, with a tick on
//! the time axis where each movement command started.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::data::{At, Sample};
use crate::err;
use crate::figure::Figure;

const START: RGBColor = RGBColor(0, 130, 60);
/// Below this speed, m/s, the robot is stopping or standing (the VM's arrival speed):
/// its curvature is the wheel's angle, not a path's, and is not drawn.
const MOVING: f64 = 0.05;

#[derive(Debug, Clone, Copy)]
pub enum Quantity {
    Speed,
    Curvature,
}

impl Quantity {
    fn label(self) -> &'static str {
        match self {
            Quantity::Speed => "speed (m/s)",
            Quantity::Curvature => "curvature (1/m)",
        }
    }

    /// The runs of samples drawn as lines: all of them for speed; for curvature only
    /// those while the robot moves.
    fn drawn(self, samples: &[Sample]) -> Vec<&[Sample]> {
        match self {
            Quantity::Speed => vec![samples],
            Quantity::Curvature => samples
                .split(|s| s.v.abs() < MOVING)
                .filter(|run| !run.is_empty())
                .collect(),
        }
    }

    fn of(self, s: &Sample) -> f64 {
        match self {
            Quantity::Speed => s.v,
            Quantity::Curvature => s.c,
        }
    }
}

pub fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    figure: &Figure,
    q: Quantity,
) -> Result<(), String> {
    let samples = || figure.tracks.iter().flat_map(|t| t.samples.iter());
    let t_end = samples().map(|p| p.t).fold(1.0, f64::max);
    let (lo, hi) = figure
        .tracks
        .iter()
        .flat_map(|t| q.drawn(&t.samples))
        .flatten()
        .map(|s| q.of(s))
        .fold((0.0f64, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let pad = ((hi - lo) * 0.1).max(0.05);
    let mut chart = ChartBuilder::on(&area.margin(5, 15, 15, 15))
        .x_label_area_size(35)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..t_end, (lo - pad)..(hi + pad))
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc(q.label())
        .max_light_lines(2)
        .light_line_style(RGBColor(240, 240, 240))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(figure.marks.iter().filter(|m| m.at == At::Start).map(|m| {
            PathElement::new(
                [(m.t, lo - pad), (m.t, hi + pad)],
                START.mix(0.35).stroke_width(1),
            )
        }))
        .map_err(err)?;
    for track in &figure.tracks {
        let c = track.colour;
        for piece in q.drawn(&track.samples) {
            chart
                .draw_series(LineSeries::new(
                    piece.iter().map(|s| (s.t, q.of(s))),
                    RGBColor(c.0, c.1, c.2).stroke_width(2),
                ))
                .map_err(err)?;
        }
    }
    Ok(())
}
