//! Image and figure files written whole or not at all (`docs/reliability.md`, "Outputs and
//! folders"). `image::ImageBuffer::save` and plotters' file backends write through a
//! `BufWriter` that is dropped without a checked flush: on a full disk a PNG was left empty
//! or cut at 4096 bytes while the command reported success. Here the file is encoded in
//! memory, written to a temporary file beside it with every write checked, and renamed.

use anyhow::{anyhow, Context, Result};
use std::path::Path;

/// Writes `bytes` to `path` through `.NAME.PID.tmp` in the same folder: every write is
/// checked (a full disk is an error naming the file, and the temporary file is removed),
/// then the file is renamed into place, so a file of the final name is always whole. No
/// fsync: figures are many and are redone by rerunning; what a full disk gives is the
/// write's own error.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    adhesim_scenario::output::write_through_temp(path, bytes, false)
}

/// Writes the RGB `pixels` of a figure drawn by plotters' bitmap backend as a PNG with the
/// encoder that backend's own file writer uses, so that the bytes stay those
/// of the figures written before; every write checked ([`write_file`]).
pub fn save_figure_png(pixels: Vec<u8>, size: (u32, u32), path: &Path) -> Result<()> {
    let image = image::RgbImage::from_raw(size.0, size.1, pixels)
        .ok_or_else(|| anyhow!("{}: image buffer size", path.display()))?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageOutputFormat::Png)
        .with_context(|| format!("cannot encode {}", path.display()))?;
    write_file(path, bytes.get_ref())
}

/// Encodes `image` in the format of `path`'s extension (png, tif, jpg) and writes it with
/// [`write_file`]: the same bytes as `ImageBuffer::save`, every write checked.
pub fn save_image<P>(image: &image::ImageBuffer<P, Vec<P::Subpixel>>, path: &Path) -> Result<()>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
{
    let format = image::ImageFormat::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, format)
        .with_context(|| format!("cannot encode {}", path.display()))?;
    write_file(path, bytes.get_ref())
}

#[cfg(test)]
mod tests {
    use crate::figure::{Drawing, Figure, Mark, Panel, Series, PALETTE};
    use plotters::prelude::*;

    /// The checked writes give the bytes plotters' and image's own file writers gave, so the
    /// figures of valid runs are unchanged.
    #[test]
    fn checked_writes_give_the_bytes_of_the_file_backends() {
        let dir = tempfile::tempdir().unwrap();
        let panel = Panel::new("t", "x", "y").with([Series::new(
            "a",
            PALETTE[0],
            Mark::LinePoints,
            vec![(0.0, 1.0), (1.0, 3.0), (2.0, 2.0)],
        )]);
        let figure = Figure::stacked(vec![panel]);
        figure.save(dir.path(), "new", (300, 200)).unwrap();
        crate::figure::register_font().unwrap();
        figure
            .draw(&SVGBackend::new(&dir.path().join("old.svg"), (300, 200)).into_drawing_area())
            .unwrap();
        figure
            .draw(&BitMapBackend::new(&dir.path().join("old.png"), (300, 200)).into_drawing_area())
            .unwrap();
        for extension in ["svg", "png"] {
            let read = |stem: &str| std::fs::read(dir.path().join(format!("{stem}.{extension}"))).unwrap();
            assert_eq!(read("new"), read("old"), "{extension}");
        }
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 4, "no temporary file is left: {names:?}");
    }
}
