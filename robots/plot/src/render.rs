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
