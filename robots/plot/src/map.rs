//! The map panel: worlds, scanner hits, reference paths, trajectories and command
//! marks, at one scale on both axes.

use ilmr_sim::World;
use ilmr_sim::geometry::Shape;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::data::At;
use crate::err;
use crate::figure::{Colour, Corner, Figure};

/// Room left round what the robot did, metres.
const MARGIN: f64 = 2.0;
/// The smallest span drawn, metres, so a short run is not magnified to nothing.
const MIN_SPAN: f64 = 4.0;
/// Height over width of the map's plotting area, within these.
const MIN_RATIO: f64 = 0.4;
const MAX_RATIO: f64 = 1.0;
const PAD: u32 = 15;
const X_LABELS: u32 = 40;
const Y_LABELS: u32 = 55;
const TITLE: u32 = 30;

const WALL: RGBColor = RGBColor(90, 90, 90);
const OBSTACLE: RGBColor = RGBColor(150, 150, 150);
const HIT: RGBColor = RGBColor(200, 40, 40);
const START: RGBColor = RGBColor(0, 130, 60);
const END: RGBColor = RGBColor(190, 90, 0);

fn rgb(c: Colour) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// The part of the world shown, metres.
pub struct View {
    x: (f64, f64),
    y: (f64, f64),
}

fn bbox(points: impl Iterator<Item = (f64, f64)>) -> Option<((f64, f64), (f64, f64))> {
    points.fold(None, |b, (x, y)| {
        let ((x0, x1), (y0, y1)) = b.unwrap_or(((x, x), (y, y)));
        Some(((x0.min(x), x1.max(x)), (y0.min(y), y1.max(y))))
    })
}

fn widen(range: (f64, f64), span: f64) -> (f64, f64) {
    let mid = (range.0 + range.1) / 2.0;
    (mid - span / 2.0, mid + span / 2.0)
}

impl View {
    /// Round the trajectories, the marks and the reference paths, within the worlds'
    /// bounds; the whole of the worlds when there is none of them.
    pub fn fit(figure: &Figure) -> View {
        let done = figure
            .tracks
            .iter()
            .flat_map(|t| t.samples.iter().map(|p| (p.x, p.y)))
            .chain(figure.marks.iter().map(|m| (m.x, m.y)))
            .chain(
                figure
                    .references
                    .iter()
                    .flat_map(|r| r.points.iter().copied()),
            );
        let bounds = bbox(figure.scenery.iter().flat_map(|s| {
            let b = &s.world.bounds;
            [(b.min.x, b.min.y), (b.max.x, b.max.y)]
        }));
        let (mut x, mut y) = match (bbox(done), bounds) {
            (Some((x, y)), _) => ((x.0 - MARGIN, x.1 + MARGIN), (y.0 - MARGIN, y.1 + MARGIN)),
            (None, Some(b)) => b,
            (None, None) => ((-1.0, 1.0), (-1.0, 1.0)),
        };
        if let Some((bx, by)) = bounds {
            x = (x.0.max(bx.0), x.1.min(bx.1));
            y = (y.0.max(by.0), y.1.min(by.1));
        }
        x = widen(x, (x.1 - x.0).max(MIN_SPAN));
        y = widen(y, (y.1 - y.0).max(MIN_SPAN));
        // One scale on both axes: widen the short axis to fit the panel's shape.
        let ratio = (y.1 - y.0) / (x.1 - x.0);
        if ratio > MAX_RATIO {
            x = widen(x, (y.1 - y.0) / MAX_RATIO);
        } else if ratio < MIN_RATIO {
            y = widen(y, (x.1 - x.0) * MIN_RATIO);
        }
        View { x, y }
    }

    fn ratio(&self) -> f64 {
        (self.y.1 - self.y.0) / (self.x.1 - self.x.0)
    }

    /// The panel's height in pixels for `width`, so that a metre is as long across as up.
    pub fn panel_height(&self, width: u32) -> u32 {
        let plot_w = width - 2 * PAD - Y_LABELS;
        (f64::from(plot_w) * self.ratio()).round() as u32 + 2 * PAD + X_LABELS + TITLE
    }
}

fn v(p: ilmr_sim::Vec2) -> (f64, f64) {
    (p.x, p.y)
}

pub fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    figure: &Figure,
    view: &View,
) -> Result<(), String> {
    area.draw_text(
        &figure.title,
        &("sans-serif", 18).into_font().color(&BLACK),
        (PAD as i32 + Y_LABELS as i32, PAD as i32),
    )
    .map_err(err)?;
    let plot = area.margin(PAD + TITLE, PAD, PAD, PAD);
    let mut chart = ChartBuilder::on(&plot)
        .x_label_area_size(X_LABELS)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(view.x.0..view.x.1, view.y.0..view.y.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("x (m)")
        .y_desc("y (m)")
        .max_light_lines(2)
        .light_line_style(RGBColor(240, 240, 240))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(err)?;

    for s in &figure.scenery {
        draw_world(&mut chart, &s.world, s.tint.map(rgb))?;
    }
    if !figure.hits.is_empty() {
        chart
            .draw_series(
                figure
                    .hits
                    .iter()
                    .filter(|(x, y)| {
                        (view.x.0..=view.x.1).contains(x) && (view.y.0..=view.y.1).contains(y)
                    })
                    .map(|&p| Circle::new(p, 1, HIT.filled())),
            )
            .map_err(err)?
            .label("scanner hits")
            .legend(|(x, y)| Circle::new((x + 10, y), 2, HIT.filled()));
    }
    let mut legend = Legend::default();
    for r in &figure.references {
        let colour = rgb(r.colour);
        let series = chart
            .draw_series(DashedLineSeries::new(
                r.points.iter().copied(),
                8,
                5,
                colour.stroke_width(1),
            ))
            .map_err(err)?;
        if let Some(label) = legend.first(&r.label) {
            series.label(label).legend(move |(x, y)| {
                PathElement::new([(x, y), (x + 8, y)], colour.stroke_width(1))
            });
        }
    }
    for t in &figure.tracks {
        let colour = rgb(t.colour);
        let series = chart
            .draw_series(LineSeries::new(
                t.samples.iter().map(|p| (p.x, p.y)),
                colour.stroke_width(2),
            ))
            .map_err(err)?;
        if let Some(label) = legend.first(&t.label) {
            series.label(label).legend(move |(x, y)| {
                PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(2))
            });
        }
    }
    if !figure.marks.is_empty() {
        draw_marks(&mut chart, figure)?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .position(match figure.legend {
            Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
            Corner::UpperRight => SeriesLabelPosition::UpperRight,
            Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
            Corner::LowerRight => SeriesLabelPosition::LowerRight,
        })
        .draw()
        .map_err(err)?;
    Ok(())
}

/// The labels already in the legend: paths that share a label (the trials of one
/// sweep) get one entry.
#[derive(Default)]
struct Legend(Vec<String>);

impl Legend {
    fn first(&mut self, label: &Option<String>) -> Option<String> {
        let label = label.as_ref()?;
        if self.0.contains(label) {
            return None;
        }
        self.0.push(label.clone());
        Some(label.clone())
    }
}

type Chart<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Walls, obstacles and boxes filled, targets and the charger outlined; all in `tint`
/// when given.
fn draw_world<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    w: &World,
    tint: Option<RGBColor>,
) -> Result<(), String> {
    let (wall_colour, obstacle) = tint.map_or((WALL, OBSTACLE), |t| (t, t));
    let mut solids: Vec<(Vec<(f64, f64)>, RGBColor)> = Vec::new();
    for wall in &w.walls {
        for &(a, b) in &wall.pieces {
            let obb = ilmr_sim::geometry::Obb::from_segment(a, b, wall.thickness);
            solids.push((obb.corners().iter().map(|c| v(*c)).collect(), wall_colour));
        }
    }
    for o in &w.obstacles {
        let outline = match o {
            Shape::Box(b) => b.corners().iter().map(|c| v(*c)).collect(),
            Shape::Circle(c) => circle(v(c.center), c.radius),
        };
        solids.push((outline, obstacle));
    }
    for b in &w.pickup_boxes {
        solids.push((b.shape.corners().iter().map(|c| v(*c)).collect(), obstacle));
    }
    chart
        .draw_series(solids.into_iter().map(|(p, c)| Polygon::new(p, c.filled())))
        .map_err(err)?;
    let outlines = w
        .targets
        .iter()
        .map(|t| circle(v(t.start), t.radius))
        .chain(w.charger.iter().map(|c| circle(v(c.position), c.radius)));
    for o in outlines {
        let mut closed = o.clone();
        closed.extend(o.first().copied());
        chart
            .draw_series(std::iter::once(PathElement::new(
                closed,
                obstacle.stroke_width(1),
            )))
            .map_err(err)?;
    }
    Ok(())
}

fn circle(c: (f64, f64), r: f64) -> Vec<(f64, f64)> {
    (0..24)
        .map(|i| {
            let a = f64::from(i) * std::f64::consts::TAU / 24.0;
            (c.0 + r * a.cos(), c.1 + r * a.sin())
        })
        .collect()
}

/// Circles where movements started and crosses where they ended, each labelled with
/// its line; starts are labelled above, ends below, so a linked pair (one's end is
/// the next one's start) stays readable.
fn draw_marks<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    figure: &Figure,
) -> Result<(), String> {
    let font = ("sans-serif", 13).into_font();
    let starts = figure.marks.iter().filter(|m| m.at == At::Start);
    let ends = figure
        .marks
        .iter()
        .filter(|m| m.at == At::End && m.how.as_deref() != Some("refused"));
    chart
        .draw_series(starts.map(|m| {
            EmptyElement::at((m.x, m.y))
                + Circle::new((0, 0), 5, START.stroke_width(2))
                + Text::new(format!("{}", m.line), (-4, -20), font.clone().color(&START))
        }))
        .map_err(err)?
        .label("movement started (source line)")
        .legend(|(x, y)| Circle::new((x + 10, y), 5, START.stroke_width(2)));
    chart
        .draw_series(ends.map(|m| {
            EmptyElement::at((m.x, m.y))
                + Cross::new((0, 0), 5, END.stroke_width(2))
                + Text::new(format!("{}", m.line), (-4, 8), font.clone().color(&END))
        }))
        .map_err(err)?
        .label("movement ended (source line)")
        .legend(|(x, y)| Cross::new((x + 10, y), 5, END.stroke_width(2)));
    Ok(())
}
