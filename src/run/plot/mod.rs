//! `--plot OUT.svg`: a run drawn the way the dissertation's Figures 46-59 are. On top
//! the map: the world's walls and obstacles, scanner hits as dots, reference paths
//! dashed, the true trajectory solid, and where each movement command started (circle)
//! and ended (cross), labelled with its source line. Below, speed and curvature over
//! time (Figure 54).
//!
//! Drawn with plotters' SVG backend and no font library: text becomes SVG `<text>`
//! elements the viewer renders, so nothing depends on the fonts of the machine that
//! draws.

mod data;
mod map;
mod series;

pub use data::RunRecord;

use std::path::Path;

use plotters::prelude::*;

/// Width of the figure, pixels.
pub const WIDTH: u32 = 1000;
/// Height of each time-series panel, pixels.
const SERIES_HEIGHT: u32 = 220;

fn err(e: impl std::fmt::Debug) -> String {
    format!("cannot draw the plot: {e:?}")
}

/// The figure as SVG text.
pub fn render_svg(record: &RunRecord) -> Result<String, String> {
    let world = record.world()?;
    let view = map::View::fit(record, world.as_ref());
    let map_height = view.panel_height(WIDTH);
    let height = map_height + 2 * SERIES_HEIGHT;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (top, bottom) = root.split_vertically(map_height);
        map::draw(&top, record, world.as_ref(), &view)?;
        let (speed, curvature) = bottom.split_vertically(SERIES_HEIGHT);
        series::draw(&speed, record, series::Quantity::Speed)?;
        series::draw(&curvature, record, series::Quantity::Curvature)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}

pub fn write_svg(record: &RunRecord, path: &Path) -> Result<(), String> {
    let svg = render_svg(record)?;
    std::fs::write(path, svg).map_err(|e| format!("cannot write plot `{}`: {e}", path.display()))
}

/// The figure's title: the task, and the robot, world and seed when the trace says.
fn title(record: &RunRecord) -> String {
    match &record.header {
        Some(h) => format!("{}: {} in {}, seed {}", h.task, h.robot, h.world, h.seed),
        None => "ILMR run".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const POSES: &str = r#"{"t":0,"event":"pose","x":0,"y":0,"h":0,"v":0,"c":0,"source":"true"}
{"t":1,"event":"pose","x":1,"y":0.1,"h":0,"v":0.4,"c":0,"source":"true"}
"#;

    #[test]
    fn reference_paths_are_drawn_from_path_events() {
        let path = r#"{"t":0,"event":"path","line":3,"text":"goahead(3)","points":[[0,0],[3,0]]}"#;
        let without = render_svg(&RunRecord::from_jsonl(POSES).expect("a trace")).expect("drawn");
        let record = RunRecord::from_jsonl(&format!("{POSES}{path}\n")).expect("a trace");
        assert_eq!(record.refs.len(), 1);
        assert_eq!(record.refs[0].line, 3);
        assert_eq!(record.refs[0].points, vec![(0.0, 0.0), (3.0, 0.0)]);
        let with = render_svg(&record).expect("drawn");
        assert!(with.contains("reference path"), "the legend names it");
        assert!(!without.contains("reference path"));
        // Dashes: more line pieces than the run without the path.
        let pieces = |svg: &str| svg.matches("<polyline").count() + svg.matches("<line").count();
        assert!(pieces(&with) > pieces(&without) + 3);
    }

    #[test]
    fn a_path_event_without_points_is_an_error_naming_the_key() {
        let bad = r#"{"t":0,"event":"path","line":3,"points":[[0]]}"#;
        let err = RunRecord::from_jsonl(bad).expect_err("not a path");
        assert!(err.contains("points"), "{err}");
    }
}
