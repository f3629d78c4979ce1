//! The map panel: worlds, scanner hits, reference paths, trajectories and command
//! marks, at one scale on both axes.

use ilmr_sim::World;
use ilmr_sim::geometry::Shape;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::data::{At, Sample};
use crate::err;
use crate::figure::{Colour, Corner, Figure, Footprint};
use crate::labels::{self, Placer};

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
const DOOR: RGBColor = RGBColor(175, 125, 60);
const FOOTPRINT: RGBColor = RGBColor(110, 130, 165);
const TICK: RGBColor = RGBColor(90, 90, 90);
/// Round intervals of time ticks, seconds; the first that gives at most
/// [`MAX_TICKS`] ticks is used.
const TICK_STEPS: [f64; 10] = [1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 60.0, 120.0, 300.0, 600.0];
const MAX_TICKS: f64 = 10.0;
/// Marks closer than this, pixels, share a label.
const SAME_PLACE: i32 = 4;

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
                    .spreads
                    .iter()
                    .flat_map(|s| s.runs.iter().flatten().copied()),
            )
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

fn v(p: ilmr_sim::Point2<f64>) -> (f64, f64) {
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
    world_legend(&mut chart, figure)?;
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
    for spread in &figure.spreads {
        draw_spread(&mut chart, spread)?;
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
    let ticks = if figure.time_ticks {
        figure
            .tracks
            .first()
            .map(|t| time_ticks(&t.samples))
            .unwrap_or_default()
    } else {
        Vec::new()
    };
    if let Some(body) = figure.body {
        draw_footprints(&mut chart, figure, body, &ticks)?;
    }
    // The references go over the trajectories, thin and dashed, so that the path the
    // robot was to follow shows where it drove on it.
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
    let mut placer = Placer::default();
    let marks = visible_marks(figure);
    for m in &marks {
        placer.block(chart.backend_coord(&(m.x, m.y)), 6);
    }
    for (_, s) in &ticks {
        placer.block(chart.backend_coord(&(s.x, s.y)), 3);
    }
    if !marks.is_empty() {
        draw_marks(&mut chart, &marks, &mut placer)?;
    }
    if !ticks.is_empty() {
        draw_ticks(&mut chart, &ticks, &mut placer)?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .position(match figure.legend {
            Corner::Quietest => quietest(figure, view),
            Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
            Corner::UpperRight => SeriesLabelPosition::UpperRight,
            Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
            Corner::LowerRight => SeriesLabelPosition::LowerRight,
        })
        .draw()
        .map_err(err)?;
    Ok(())
}

/// The runs of a spread: pale enough that where many overlap reads darker.
const RUN_OPACITY: f64 = 0.35;

/// A spread's runs, thin and pale, and their mean over them, thick.
fn draw_spread<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    spread: &crate::figure::RunSpread,
) -> Result<(), String> {
    let colour = rgb(spread.colour);
    let pale = colour.mix(RUN_OPACITY);
    for (i, run) in spread.runs.iter().enumerate() {
        let series = chart
            .draw_series(LineSeries::new(run.iter().copied(), pale.stroke_width(1)))
            .map_err(err)?;
        if i == 0 {
            let label = format!("{} ({} runs)", spread.label, spread.runs.len());
            series.label(label).legend(move |(x, y)| {
                PathElement::new([(x, y), (x + 20, y)], pale.stroke_width(1))
            });
        }
    }
    chart
        .draw_series(LineSeries::new(
            spread.mean.iter().copied(),
            colour.stroke_width(3),
        ))
        .map_err(err)?
        .label(format!("mean of {}", spread.label))
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(3)));
    Ok(())
}

/// Share of the map's width and height the legend's corner is taken to cover.
const LEGEND_SHARE: (f64, f64) = (0.35, 0.4);

/// The corner whose legend would cover the fewest trajectory samples and marks.
fn quietest(figure: &Figure, view: &View) -> SeriesLabelPosition {
    let points: Vec<(f64, f64)> = figure
        .tracks
        .iter()
        .flat_map(|t| t.samples.iter().map(|s| (s.x, s.y)))
        .chain(figure.marks.iter().map(|m| (m.x, m.y)))
        .collect();
    let (w, h) = (view.x.1 - view.x.0, view.y.1 - view.y.0);
    let in_corner = |right: bool, upper: bool| {
        let xs = if right {
            (view.x.1 - LEGEND_SHARE.0 * w, view.x.1)
        } else {
            (view.x.0, view.x.0 + LEGEND_SHARE.0 * w)
        };
        let ys = if upper {
            (view.y.1 - LEGEND_SHARE.1 * h, view.y.1)
        } else {
            (view.y.0, view.y.0 + LEGEND_SHARE.1 * h)
        };
        points
            .iter()
            .filter(|(x, y)| (xs.0..=xs.1).contains(x) && (ys.0..=ys.1).contains(y))
            .count()
    };
    [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
        (SeriesLabelPosition::LowerLeft, false, false),
    ]
    .into_iter()
    .min_by_key(|(_, right, upper)| in_corner(*right, *upper))
    .map_or(SeriesLabelPosition::UpperRight, |(p, ..)| p)
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
    let door = tint.unwrap_or(DOOR);
    chart
        .draw_series(
            w.doors
                .iter()
                .map(|d| PathElement::new([v(d.jambs.0), v(d.jambs.1)], door.stroke_width(3))),
        )
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

/// The marks drawn: every start, and every end but refusals (a refused movement
/// never moved).
fn visible_marks(figure: &Figure) -> Vec<&crate::data::Mark> {
    figure
        .marks
        .iter()
        .filter(|m| m.at == At::Start || m.how != Some(ilmr_trace::How::Refused))
        .collect()
}

/// Circles where movements started and crosses where they ended. Each is labelled
/// with its source line, starts first, in a free place round it (`labels`); marks of
/// one kind at one place share a label (`4, 12`).
fn draw_marks<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    marks: &[&crate::data::Mark],
    placer: &mut Placer,
) -> Result<(), String> {
    let font = ("sans-serif", labels::FONT).into_font();
    for (at, colour) in [(At::Start, START), (At::End, END)] {
        let kind: Vec<&crate::data::Mark> = marks.iter().copied().filter(|m| m.at == at).collect();
        let pixels: Vec<(i32, i32)> = kind
            .iter()
            .map(|m| chart.backend_coord(&(m.x, m.y)))
            .collect();
        let mut texts = Vec::new();
        for group in labels::group(&pixels, SAME_PLACE) {
            let mut lines: Vec<u32> = group.iter().map(|&i| kind[i].line).collect();
            lines.dedup();
            let text = lines
                .iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(", ");
            let size = (labels::width(&text), labels::FONT as i32);
            let first = group[0];
            let offset = placer
                .place(pixels[first], size)
                .unwrap_or((-size.0 / 2, if at == At::Start { -20 } else { 8 }));
            texts.push(((kind[first].x, kind[first].y), text, offset));
        }
        let series = chart
            .draw_series(kind.iter().map(|m| {
                EmptyElement::at((m.x, m.y))
                    + match at {
                        At::Start => Circle::new((0, 0), 5, colour.stroke_width(2)).into_dyn(),
                        At::End => Cross::new((0, 0), 5, colour.stroke_width(2)).into_dyn(),
                    }
            }))
            .map_err(err)?;
        match at {
            At::Start => series
                .label("movement started (source line)")
                .legend(|(x, y)| Circle::new((x + 10, y), 5, START.stroke_width(2))),
            At::End => series
                .label("movement ended (source line)")
                .legend(|(x, y)| Cross::new((x + 10, y), 5, END.stroke_width(2))),
        };
        chart
            .draw_series(texts.into_iter().map(|(p, text, offset)| {
                EmptyElement::at(p) + Text::new(text, offset, font.clone().color(&colour))
            }))
            .map_err(err)?;
    }
    Ok(())
}

/// The first track's samples at round times, with their times: at most
/// [`MAX_TICKS`] of them, none at 0 (the start is marked already).
fn time_ticks(samples: &[Sample]) -> Vec<(f64, Sample)> {
    let end = samples.last().map_or(0.0, |s| s.t);
    let Some(step) = TICK_STEPS.iter().copied().find(|s| end / s <= MAX_TICKS) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut next = step;
    for s in samples {
        if s.t + 1e-9 >= next {
            out.push((next, *s));
            next += step;
        }
    }
    out
}

/// A dot on the track at each tick, labelled `20 s` where there is room; ticks at
/// one place (the robot stood) share a label, `60-540 s`.
fn draw_ticks<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    ticks: &[(f64, Sample)],
    placer: &mut Placer,
) -> Result<(), String> {
    let font = ("sans-serif", labels::FONT - 2).into_font();
    let pixels: Vec<(i32, i32)> = ticks
        .iter()
        .map(|(_, s)| chart.backend_coord(&(s.x, s.y)))
        .collect();
    let mut texts = Vec::new();
    for group in labels::group(&pixels, SAME_PLACE) {
        let (first, last) = (group[0], group[group.len() - 1]);
        let text = if first == last {
            format!("{} s", ticks[first].0)
        } else {
            format!("{}-{} s", ticks[first].0, ticks[last].0)
        };
        let size = (labels::width(&text), labels::FONT as i32 - 2);
        if let Some(offset) = placer.place(pixels[first], size) {
            let s = ticks[first].1;
            texts.push(((s.x, s.y), text, offset));
        }
    }
    chart
        .draw_series(
            ticks
                .iter()
                .map(|(_, s)| Circle::new((s.x, s.y), 2, TICK.filled())),
        )
        .map_err(err)?
        .label("time along the trajectory")
        .legend(|(x, y)| Circle::new((x + 10, y), 2, TICK.filled()));
    chart
        .draw_series(texts.into_iter().map(|(p, text, offset)| {
            EmptyElement::at(p) + Text::new(text, offset, font.clone().color(&TICK))
        }))
        .map_err(err)?;
    Ok(())
}

/// The robot's outline where each movement started, and at the time ticks where it
/// stands clear of the outlines drawn already; its front edge drawn heavier, so the
/// heading shows.
fn draw_footprints<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    figure: &Figure,
    body: Footprint,
    ticks: &[(f64, Sample)],
) -> Result<(), String> {
    let starts = figure
        .marks
        .iter()
        .filter(|m| m.at == At::Start)
        .map(|m| ((m.x, m.y, m.h), true));
    let at_ticks = ticks.iter().map(|(_, s)| ((s.x, s.y, s.h), false));
    let mut drawn: Vec<(f64, f64, f64)> = Vec::new();
    let (mut outlines, mut fronts) = (Vec::new(), Vec::new());
    for ((x, y, h), start) in starts.chain(at_ticks) {
        let same =
            |&(px, py, ph): &(f64, f64, f64)| (px - x).hypot(py - y) < 0.1 && (ph - h).abs() < 0.2;
        let crowded = |&(px, py, _): &(f64, f64, f64)| (px - x).hypot(py - y) < body.length;
        if drawn.iter().any(same) || (!start && drawn.iter().any(crowded)) {
            continue;
        }
        drawn.push((x, y, h));
        let c = body.corners(x, y, h);
        outlines.push(vec![c[2], c[3], c[0], c[1]]);
        fronts.push(vec![c[1], c[2]]);
    }
    chart
        .draw_series(
            outlines
                .into_iter()
                .map(|o| PathElement::new(o, FOOTPRINT.stroke_width(1))),
        )
        .map_err(err)?
        .label("robot footprint (front edge heavy)")
        .legend(|(x, y)| Rectangle::new([(x, y - 4), (x + 20, y + 4)], FOOTPRINT.stroke_width(1)));
    chart
        .draw_series(
            fronts
                .into_iter()
                .map(|f| PathElement::new(f, FOOTPRINT.stroke_width(3))),
        )
        .map_err(err)?;
    Ok(())
}

/// Legend entries for what the worlds hold (untinted: tinted worlds tell figures'
/// worlds apart, and their legend is the tracks').
fn world_legend<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    figure: &Figure,
) -> Result<(), String> {
    let plain = || {
        figure
            .scenery
            .iter()
            .filter(|s| s.tint.is_none())
            .map(|s| &s.world)
    };
    let walls = plain().any(|w| !w.walls.is_empty());
    let solids = plain().any(|w| !w.obstacles.is_empty() || !w.pickup_boxes.is_empty());
    let doors = plain().any(|w| !w.doors.is_empty());
    if walls {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())
            .map_err(err)?
            .label("wall")
            .legend(|(x, y)| Rectangle::new([(x, y - 3), (x + 20, y + 3)], WALL.filled()));
    }
    if solids {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())
            .map_err(err)?
            .label("obstacle, box")
            .legend(|(x, y)| Rectangle::new([(x, y - 4), (x + 20, y + 4)], OBSTACLE.filled()));
    }
    if doors {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())
            .map_err(err)?
            .label("door (opening)")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], DOOR.stroke_width(3)));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::RunSpread;

    #[test]
    fn the_view_holds_every_run_of_a_spread() {
        let mut f = Figure::new("seeds");
        f.spreads.push(RunSpread {
            label: "seeds".into(),
            colour: Colour::palette(0),
            runs: vec![vec![(0.0, 0.0), (1.0, 0.0)], vec![(0.0, 9.0), (1.0, 9.0)]],
            mean: vec![(0.0, 4.5), (1.0, 4.5)],
        });
        let v = View::fit(&f);
        assert!(v.y.0 <= -MARGIN && v.y.1 >= 9.0 + MARGIN, "{:?}", v.y);
    }
}
