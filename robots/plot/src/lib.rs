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
mod labels;
mod map;
mod render;
mod series;

pub use data::{At, Header, Mark, RefPath, RunRecord, Sample};
pub use figure::{Colour, Corner, Figure, Footprint, Reference, RunSpread, Scenery, Track};
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

/// Writes, in place of a run's figure, one that says why the run did not start.
pub fn write_failure(reason: &str, exit: u8, path: &Path) -> Result<(), String> {
    let svg = render::failure(reason, exit)?;
    std::fs::write(path, svg).map_err(|e| format!("cannot write plot `{}`: {e}", path.display()))
}

fn err(e: impl std::fmt::Debug) -> String {
    format!("cannot draw the plot: {e:?}")
}

#[cfg(test)]
mod tests {
    use super::*;

    const POSES: &str = r#"{"t":0,"event":"trace","version":1}
{"t":0,"event":"pose","x":0,"y":0,"h":0,"v":0,"c":0,"source":"true"}
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

    /// MoRo in the office: two movements whose marks fall on one point (line 6 ends
    /// where line 11 starts, and line 11 ends there too), standing still at the end.
    const OFFICE_RUN: &str = r#"{"t":0,"event":"trace","version":1}
{"t":0,"event":"run","task":"t.ilmr","robot":"moro","world":"office","seed":0,"start":{"x":8,"y":5,"h":0}}
{"t":0,"event":"mark","line":6,"text":"goahead(1)","at":"start","x":8,"y":5,"h":0}
{"t":0,"event":"pose","x":8,"y":5,"h":0,"v":0,"c":0.3,"source":"true"}
{"t":1,"event":"pose","x":8.4,"y":5,"h":0,"v":0.4,"c":0.2,"source":"true"}
{"t":2,"event":"pose","x":8.8,"y":5,"h":0,"v":0.4,"c":0.1,"source":"true"}
{"t":2.5,"event":"mark","line":6,"text":"goahead(1)","at":"end","x":9,"y":5,"h":0,"how":"completed"}
{"t":2.5,"event":"mark","line":11,"text":"goahead(0)","at":"start","x":9,"y":5,"h":0}
{"t":2.5,"event":"mark","line":11,"text":"goahead(0)","at":"end","x":9,"y":5,"h":0,"how":"completed"}
{"t":3,"event":"pose","x":9,"y":5,"h":0,"v":0,"c":0.9,"source":"true"}
{"t":4,"event":"pose","x":9,"y":5,"h":0,"v":0,"c":0.9,"source":"true"}
"#;

    /// The `<text>` elements of an SVG: (x, y, text).
    fn texts(svg: &str) -> Vec<(i32, i32, String)> {
        svg.split("<text")
            .skip(1)
            .filter_map(|t| {
                let attr = |name: &str| {
                    let at = t.find(&format!(" {name}=\""))? + name.len() + 3;
                    t[at..].split('"').next()?.parse::<f64>().ok()
                };
                let body = t.split_once('>')?.1.split("</text>").next()?;
                Some((
                    attr("x")? as i32,
                    attr("y")? as i32,
                    body.trim().to_string(),
                ))
            })
            .collect()
    }

    #[test]
    fn a_run_shows_footprints_world_legend_and_apart_labels() {
        let svg = render_svg(&RunRecord::from_jsonl(OFFICE_RUN).expect("a trace")).expect("drawn");
        for entry in [
            "wall",
            "obstacle, box",
            "door (opening)",
            "robot footprint",
            "time along the trajectory",
        ] {
            assert!(svg.contains(entry), "the legend has {entry}");
        }
        let labels = texts(&svg);
        let find = |text: &str| {
            labels
                .iter()
                .filter(|(_, _, t)| t == text)
                .map(|&(x, y, _)| (x, y))
                .collect::<Vec<_>>()
        };
        // Line 6's end and line 11's end share one label; line 11's start has its own,
        // away from line 6's start label.
        assert_eq!(find("6, 11").len(), 1, "{labels:?}");
        let (start6, start11) = (find("6"), find("11"));
        assert_eq!((start6.len(), start11.len()), (1, 1), "{labels:?}");
        let map_labels: Vec<&(i32, i32, String)> = labels
            .iter()
            .filter(|(.., t)| ["6", "11", "6, 11", "1 s", "2 s", "3-4 s"].contains(&t.as_str()))
            .collect();
        assert_eq!(map_labels.len(), 6, "{labels:?}");
        for (i, a) in map_labels.iter().enumerate() {
            for b in &map_labels[i + 1..] {
                let apart = (a.0 - b.0).abs() >= 12 || (a.1 - b.1).abs() >= 12;
                assert!(apart, "{a:?} and {b:?} overlap");
            }
        }
    }

    #[test]
    fn curvature_is_drawn_only_while_the_robot_moves() {
        let svg = render_svg(&RunRecord::from_jsonl(OFFICE_RUN).expect("a trace")).expect("drawn");
        // The curvature panel's y axis reaches to the largest curvature drawn: 0.2
        // while moving, not the 0.9 of the wheel turned while standing. Its labels
        // follow its title and the time axis's: the y values, rising, then the times.
        let labels: Vec<String> = texts(&svg).into_iter().map(|(.., t)| t).collect();
        let panel = labels
            .iter()
            .position(|l| l == "curvature (1/m)")
            .expect("a curvature panel");
        let values: Vec<f64> = labels[panel + 2..]
            .iter()
            .map_while(|l| l.parse::<f64>().ok())
            .collect();
        let rising = values.windows(2).take_while(|w| w[1] > w[0]).count() + 1;
        let top = values[..rising].iter().copied().fold(f64::MIN, f64::max);
        assert!((0.2..0.5).contains(&top), "{labels:?}");
    }

    #[test]
    fn a_path_event_without_points_is_an_error_naming_the_key() {
        let bad = r#"{"t":0,"event":"trace","version":1}
{"t":0,"event":"path","line":3,"text":"goahead(3)","points":[[0]]}"#;
        let err = RunRecord::from_jsonl(bad).expect_err("not a path");
        assert_eq!((err.code, err.line), (ilmr_trace::Code::NotALine, 2));
        assert!(err.to_string().starts_with("line 2: T0101"), "{err}");
    }
}
