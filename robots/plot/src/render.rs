//! The figure's layout: the map on top, then the speed and curvature panels when the
//! figure asks for them.

use plotters::prelude::*;

use crate::figure::Figure;
use crate::series::Quantity;
use crate::{err, map, series};

/// Width of the figure, pixels.
pub const WIDTH: u32 = 1000;
/// Height of each time-series panel, pixels.
const SERIES_HEIGHT: u32 = 220;

pub fn svg(figure: &Figure) -> Result<String, String> {
    let view = map::View::fit(figure);
    let map_height = view.panel_height(WIDTH);
    let series_height = if figure.time_series {
        2 * SERIES_HEIGHT
    } else {
        0
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (WIDTH, map_height + series_height))
            .into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        if figure.time_series {
            let (top, bottom) = root.split_vertically(map_height);
            map::draw(&top, figure, &view)?;
            let (speed, curvature) = bottom.split_vertically(SERIES_HEIGHT);
            series::draw(&speed, figure, Quantity::Speed)?;
            series::draw(&curvature, figure, Quantity::Curvature)?;
        } else {
            map::draw(&root, figure, &view)?;
        }
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// Characters of a reason per line of a [`failure`] figure.
const FAILURE_WRAP: usize = 110;

/// The figure of a run that did not start: what it would have drawn cannot be, so it
/// says why, in place of an empty file or an earlier run's figure.
pub fn failure(reason: &str, exit: u8) -> Result<String, String> {
    let mut lines = vec![format!("The run did not start (exit {exit}):")];
    for part in reason.lines() {
        let mut line = String::new();
        for word in part.split(' ') {
            if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > FAILURE_WRAP {
                lines.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
        lines.push(line);
    }
    let height = 40 + 22 * lines.len() as u32;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        for (i, line) in lines.iter().enumerate() {
            let style = ("sans-serif", if i == 0 { 18 } else { 15 }).into_font();
            root.draw(&Text::new(line.as_str(), (20, 20 + 22 * i as i32), style))
                .map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    Ok(svg)
}
