//! Keys under the raster maps (contact maps, contact strips, height maps): a map is one
//! square of pixels per element and says nothing of its scale or colours by itself, so a
//! strip under it carries a scale bar in the run's length unit and either the colour of
//! each category or a colour bar with the value range and its unit.

use crate::figure::{plot_error, register_font};
use anyhow::Result;
use plotters::prelude::*;
use plotters::style::FontStyle;

/// Height of the key strip in pixels.
const KEY_HEIGHT: u32 = 46;
const FONT: (&str, f64) = ("sans-serif", 13.0);

/// What the key shows besides the scale bar.
pub enum Legend<'a> {
    /// Coloured squares with their names (contact maps).
    Categories(&'a [([u8; 3], &'a str)]),
    /// A colour bar from `low` to `high` (label with its unit) through `colour(t)`, t ∈ [−1, 1].
    ColourBar {
        low: f64,
        high: f64,
        label: &'a str,
        colour: &'a dyn Fn(f64) -> [u8; 3],
    },
}

/// A 1-2-5 length near a quarter of `width` (the map's side in length units), for the
/// scale bar.
fn scale_bar_length(width: f64) -> f64 {
    let target = 0.25 * width;
    let decade = 10f64.powi(target.log10().floor() as i32);
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&l| l <= target)
        .unwrap_or(decade)
}

/// Short text of a number: plain when it reads well, else with an exponent.
fn number(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || (1e-3..1e4).contains(&magnitude) {
        let text = format!("{value:.4}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{value:.2e}")
    }
}

/// `map` with a key strip under it: a scale bar of `pixels_per_length` and the legend.
pub fn with_key(map: &image::RgbImage, pixels_per_length: f64, legend: Legend<'_>) -> Result<image::RgbImage> {
    register_font()?;
    let width = map.width().max(420);
    let height = map.height() + KEY_HEIGHT;
    let mut buffer = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (width, height)).into_drawing_area();
        let font = FontDesc::new(FontFamily::SansSerif, FONT.1, FontStyle::Normal);
        let text = |s: &str, x: i32, y: i32| Text::new(s.to_string(), (x, y), font.clone());
        let top = map.height() as i32 + 8;
        // scale bar: the 1-2-5 length nearest below a quarter of the map (of one frame
        // of a strip of frames side by side: the shorter side)
        let side = map.width().min(map.height()) as f64;
        let length = scale_bar_length(side / pixels_per_length);
        let bar = (length * pixels_per_length).round() as i32;
        root.draw(&Rectangle::new([(6, top + 4), (6 + bar, top + 9)], BLACK.filled()))
            .map_err(plot_error)?;
        root.draw(&text(&number(length), 6, top + 14)).map_err(plot_error)?;
        let mut x = 6 + bar.max(40) + 18;
        match legend {
            Legend::Categories(entries) => {
                for (rgb, name) in entries {
                    let colour = RGBColor(rgb[0], rgb[1], rgb[2]);
                    root.draw(&Rectangle::new([(x, top + 2), (x + 12, top + 14)], colour.filled()))
                        .map_err(plot_error)?;
                    root.draw(&Rectangle::new([(x, top + 2), (x + 12, top + 14)], BLACK.mix(0.5)))
                        .map_err(plot_error)?;
                    root.draw(&text(name, x + 16, top + 2)).map_err(plot_error)?;
                    x += 16 + 8 * name.chars().count() as i32 + 12;
                }
            }
            Legend::ColourBar {
                low,
                high,
                label,
                colour,
            } => {
                let bar_width = 160;
                for i in 0..bar_width {
                    let t = 2.0 * i as f64 / (bar_width - 1) as f64 - 1.0;
                    let rgb = colour(t);
                    root.draw(&Rectangle::new(
                        [(x + i, top + 2), (x + i + 1, top + 12)],
                        RGBColor(rgb[0], rgb[1], rgb[2]).filled(),
                    ))
                    .map_err(plot_error)?;
                }
                root.draw(&text(&number(low), x, top + 16)).map_err(plot_error)?;
                let high_text = number(high);
                let high_x = x + bar_width - 7 * high_text.chars().count() as i32;
                root.draw(&text(&high_text, high_x, top + 16)).map_err(plot_error)?;
                root.draw(&text(label, x + bar_width + 12, top + 2))
                    .map_err(plot_error)?;
            }
        }
        root.present().map_err(plot_error)?;
    }
    let mut keyed = image::RgbImage::from_raw(width, height, buffer).expect("buffer of width × height × 3");
    image::imageops::replace(&mut keyed, map, 0, 0);
    Ok(keyed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_bars_are_1_2_5_lengths_up_to_a_quarter_of_the_map() {
        for (width, bar) in [(0.8, 0.2), (0.16, 0.02), (1.0, 0.2), (3e-5, 5e-6), (7.0, 1.0)] {
            let length = scale_bar_length(width);
            assert!((length / bar - 1.0).abs() < 1e-12, "{width}: {length} vs {bar}");
        }
    }

    #[test]
    fn a_keyed_map_keeps_its_pixels_and_grows_a_strip() {
        let map = image::RgbImage::from_pixel(512, 512, image::Rgb([70, 70, 70]));
        let keyed = with_key(&map, 640.0, Legend::Categories(&[([70, 70, 70], "in contact")])).unwrap();
        assert_eq!((keyed.width(), keyed.height()), (512, 512 + KEY_HEIGHT));
        assert_eq!(keyed.get_pixel(100, 100).0, [70, 70, 70]);
        // the scale bar (0.2 length units = 128 pixels) is drawn in black under the map
        assert_eq!(keyed.get_pixel(60, 512 + 14).0, [0, 0, 0]);
    }
}
