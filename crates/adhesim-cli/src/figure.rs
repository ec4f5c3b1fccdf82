//! What every figure of the command line shares: the bundled font (registered once), the
//! palette, and writing a drawing as `NAME.svg` and `NAME.png` in one call.

use anyhow::{anyhow, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::Path;
use std::sync::OnceLock;

const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Colours of the series, in order.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
    RGBColor(127, 127, 127),
];

/// The colour of the `k`-th series where series 0 is a neutral grey (the reference case
/// of the master-curve figures) and the others follow [`PALETTE`].
pub fn grey_first(k: usize) -> RGBColor {
    PALETTE[(k + PALETTE.len() - 1) % PALETTE.len()]
}

/// Registers the bundled font as "sans-serif" (there are no system fonts to rely on).
pub fn register_font() -> Result<()> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the bundled font could not be loaded"))
    }
}

/// A figure that can draw itself on any plotters backend.
pub trait Drawing {
    /// Draws the whole figure on `area`.
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static;
}

/// Writes `dir/NAME.svg` and `dir/NAME.png` of `size` pixels (`dir` exists); returns the
/// two file names.
pub fn save_svg_png(dir: &Path, name: &str, size: (u32, u32), drawing: &impl Drawing) -> Result<[String; 2]> {
    register_font()?;
    let svg = format!("{name}.svg");
    drawing.draw(&SVGBackend::new(&dir.join(&svg), size).into_drawing_area())?;
    let png = format!("{name}.png");
    drawing.draw(&BitMapBackend::new(&dir.join(&png), size).into_drawing_area())?;
    Ok([svg, png])
}
