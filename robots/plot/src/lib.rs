//! Runs drawn the way the dissertation's Figures 46-59 are. On top the map: the worlds'
//! walls and obstacles, scanner hits as dots, reference paths dashed, the true
//! trajectories solid, and where each movement command started (circle) and ended
//! (cross), labelled with its source line. Below, when asked, speed and curvature over
//! time (Figure 54).
//!
//! A [`Figure`] is what is drawn; `ilmrc run --plot` and `ilmrc replay` make one from a
//! trace ([`RunRecord`], [`render_svg`]), the experiments (`ilmr-experiments`) from
//! several runs at once.
//!
//! Drawn with plotters' SVG backend and no font library: text becomes SVG `<text>`
//! elements the viewer renders, so nothing depends on the fonts of the machine that
//! draws.

mod data;
mod figure;
mod map;
mod render;
mod series;

pub use data::{At, Header, Mark, RefPath, RunRecord, Sample};
pub use figure::{Colour, Corner, Figure, Reference, Scenery, Track};
pub use render::WIDTH;

use std::path::Path;

/// A run's figure as SVG text.
pub fn render_svg(record: &RunRecord) -> Result<String, String> {
    Figure::of_run(record)?.to_svg()
}

/// A run's figure written to `path`.
pub fn write_svg(record: &RunRecord, path: &Path) -> Result<(), String> {
    Figure::of_run(record)?.write_svg(path)
}

fn err(e: impl std::fmt::Debug) -> String {
    format!("cannot draw the plot: {e:?}")
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
