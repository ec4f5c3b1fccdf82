//! Reading and checking the experiment's input files: the frames, the frame time stamps and
//! the force log (docs/reliability.md, "Experiment inputs", lists every check).

use super::spec::ForcesSpec;
use adhesim_experiment::GrayImage;
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};

const FRAME_EXTENSIONS: [&str; 5] = ["png", "tif", "tiff", "jpg", "jpeg"];

/// Image files of a folder in file-name order.
pub fn list_frames(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("frames.path: cannot read folder {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.is_file()
                && p.extension()
                    .and_then(|e| e.to_str())
                    .is_some_and(|e| FRAME_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
        })
        .collect();
    files.sort_by(|a, b| a.file_name().cmp(&b.file_name()));
    if files.is_empty() {
        bail!("frames.path: no PNG/TIFF/JPEG frames in {}", dir.display());
    }
    Ok(files)
}

/// Decodes a frame as grey levels (colour frames are converted to luma).
pub fn read_frame(path: &Path) -> Result<GrayImage> {
    // read once: the format from the extension, then from the bytes (as `Reader::open`
    // and `with_guessed_format` set it), and a JPEG's bytes go to zune-jpeg whole
    let bytes = std::fs::read(path)?;
    let mut reader = image::io::Reader::new(std::io::Cursor::new(&bytes));
    if let Ok(format) = image::ImageFormat::from_path(path) {
        reader.set_format(format);
    }
    let reader = reader.with_guessed_format()?;
    let img = if reader.format() == Some(image::ImageFormat::Jpeg) {
        decode_jpeg(&bytes)?
    } else {
        reader.decode()?
    };
    let (w, h) = (img.width() as usize, img.height() as usize);
    use image::DynamicImage as Image;
    const BYTE: f32 = 1.0 / u8::MAX as f32;
    const WORD: f32 = 1.0 / u16::MAX as f32;
    Ok(match img {
        Image::ImageLuma8(buf) => GrayImage::from_u8(w, h, buf.as_raw())?,
        Image::ImageLuma16(buf) => GrayImage::from_u16(w, h, buf.as_raw())?,
        Image::ImageRgb8(buf) => GrayImage::from_u16(w, h, &luma_of(buf.as_raw(), 3, |c| c as f32 * BYTE))?,
        Image::ImageRgba8(buf) => GrayImage::from_u16(w, h, &luma_of(buf.as_raw(), 4, |c| c as f32 * BYTE))?,
        Image::ImageRgb16(buf) => GrayImage::from_u16(w, h, &luma_of(buf.as_raw(), 3, |c| c as f32 * WORD))?,
        Image::ImageRgba16(buf) => GrayImage::from_u16(w, h, &luma_of(buf.as_raw(), 4, |c| c as f32 * WORD))?,
        Image::ImageRgb32F(buf) => GrayImage::from_u16(w, h, &luma_of(buf.as_raw(), 3, |c| c))?,
        Image::ImageRgba32F(buf) => GrayImage::from_u16(w, h, &luma_of(buf.as_raw(), 4, |c| c))?,
        // grey with alpha: the alpha dropped, the level widened to 16 bits
        other => GrayImage::from_u16(w, h, other.to_luma16().as_raw())?,
    })
}

/// The luma of colour pixels as image 0.25 (`to_luma16`, the reader adhesim used before)
/// computes it, so that a colour frame gives the grey levels it gave: each channel expanded
/// to f32 in [0, 1], Y = 0 + R·k_R + G·k_G + B·k_B in f32 (one rounding per operation, no
/// fused multiply-add), round(65535·Y) saturated. The coefficients are the f32 values
/// image 0.25 derives for sRGB's primaries and white point (BT.709 luma, 0.2126, 0.7152,
/// 0.0722 to 1e-4; printed from image 0.25.10's `to_luma32f` of the three primaries).
/// Image 0.24's integer rounding to 8 bits first would move colour frames' levels.
fn luma_of<C: Copy>(samples: &[C], channels: usize, expand: impl Fn(C) -> f32) -> Vec<u16> {
    const LUMA: [f32; 3] = [
        f32::from_bits(0x3e59_c05b),
        f32::from_bits(0x3f37_15fc),
        f32::from_bits(0x3d93_cf75),
    ];
    samples
        .chunks_exact(channels)
        .map(|pixel| {
            let mut luma = 0.0f32;
            for (&channel, weight) in pixel[..3].iter().zip(LUMA) {
                luma += expand(channel) * weight;
            }
            (luma * u16::MAX as f32).round() as u16
        })
        .collect()
}

/// A JPEG decoded by zune-jpeg with the options image 0.25 gave it (no strict mode, no size
/// limit, the output in the file's colour space where it is grey or RGB(A), RGB otherwise),
/// so that a lossy frame's grey levels are those that decoder gives (another IDCT rounds
/// differently by a level here and there).
fn decode_jpeg(bytes: &[u8]) -> Result<image::DynamicImage> {
    use zune_core::colorspace::ColorSpace;
    let options = zune_core::options::DecoderOptions::default()
        .set_strict_mode(false)
        .set_max_width(usize::MAX)
        .set_max_height(usize::MAX);
    let mut decoder = zune_jpeg::JpegDecoder::new_with_options(zune_core::bytestream::ZCursor::new(bytes), options);
    decoder.decode_headers().map_err(|e| anyhow::anyhow!("JPEG: {e:?}"))?;
    let colour = match decoder.input_colorspace() {
        Some(space @ (ColorSpace::RGB | ColorSpace::RGBA | ColorSpace::Luma | ColorSpace::LumaA)) => space,
        _ => ColorSpace::RGB,
    };
    decoder.set_options(decoder.options().jpeg_set_out_colorspace(colour));
    let pixels = decoder.decode().map_err(|e| anyhow::anyhow!("JPEG: {e:?}"))?;
    let (w, h) = decoder.dimensions().context("JPEG: no dimensions after decoding")?;
    let (w, h) = (u32::try_from(w)?, u32::try_from(h)?);
    let length = pixels.len();
    let size = || anyhow::anyhow!("JPEG: {length} bytes of pixels for {w} × {h}");
    Ok(match colour {
        ColorSpace::Luma => image::DynamicImage::ImageLuma8(image::GrayImage::from_raw(w, h, pixels).ok_or_else(size)?),
        ColorSpace::LumaA => {
            image::DynamicImage::ImageLumaA8(image::GrayAlphaImage::from_raw(w, h, pixels).ok_or_else(size)?)
        }
        ColorSpace::RGBA => image::DynamicImage::ImageRgba8(image::RgbaImage::from_raw(w, h, pixels).ok_or_else(size)?),
        _ => image::DynamicImage::ImageRgb8(image::RgbImage::from_raw(w, h, pixels).ok_or_else(size)?),
    })
}

pub fn name_of(path: &Path) -> String {
    path.file_name()
        .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}

/// The size every frame must have: that of the first frame (in file-name order) that decodes.
#[derive(Debug, Clone)]
pub struct FrameSize {
    pub width: usize,
    pub height: usize,
    /// File name of that first frame.
    pub first: String,
}

impl FrameSize {
    /// Finds the first decodable frame; `None` when none decodes.
    pub fn of_first(files: &[PathBuf]) -> Option<Self> {
        files.iter().find_map(|p| {
            read_frame(p).ok().map(|img| Self {
                width: img.width(),
                height: img.height(),
                first: name_of(p),
            })
        })
    }

    /// Error naming `what` (a file or key) and both sizes when `image` differs.
    pub fn check(&self, image: &GrayImage, what: &str) -> Result<()> {
        let (w, h) = (image.width(), image.height());
        if (w, h) != (self.width, self.height) {
            bail!(
                "{what} is {w}×{h} pixels but the first frame {} is {}×{}; all frames must have one size",
                self.first,
                self.width,
                self.height
            );
        }
        Ok(())
    }
}

/// Numeric columns of a CSV table, every cell checked: a cell that is not a finite number
/// (text, NaN, ±inf) is an error naming the file, line and column; an empty cell is a missing
/// sample (`None`, counted in `empty_cells`) except in the first column asked for (time),
/// where it is an error.
pub struct Table {
    pub columns: Vec<Vec<Option<f64>>>,
    /// File line of each row (the header is line 1).
    pub lines: Vec<u64>,
    pub empty_cells: usize,
}

/// Reads the columns `names` (by header) of the CSV file `path`; `key` is the spec key.
pub fn read_table(path: &Path, names: &[&str], key: &str) -> Result<Table> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .with_context(|| format!("{key}: cannot read {}", path.display()))?;
    let headers = reader.headers()?.clone();
    let index: Vec<usize> = names
        .iter()
        .map(|n| {
            headers.iter().position(|h| h == *n).with_context(|| {
                format!(
                    "{key}: column \"{n}\" not in {} (columns: {})",
                    path.display(),
                    headers.iter().collect::<Vec<_>>().join(", ")
                )
            })
        })
        .collect::<Result<_>>()?;
    let mut table = Table {
        columns: vec![Vec::new(); names.len()],
        lines: Vec::new(),
        empty_cells: 0,
    };
    for record in reader.records() {
        let record = record.with_context(|| format!("{key}: malformed CSV in {}", path.display()))?;
        let line = record.position().map_or(0, |p| p.line());
        for (k, (col, &i)) in table.columns.iter_mut().zip(&index).enumerate() {
            let text = record.get(i).unwrap_or("");
            let at = || {
                format!(
                    "{key}: {} line {line}, column {} (\"{}\")",
                    path.display(),
                    i + 1,
                    names[k]
                )
            };
            if text.is_empty() {
                if k == 0 {
                    bail!("{}: empty time cell", at());
                }
                table.empty_cells += 1;
                col.push(None);
                continue;
            }
            match text.parse::<f64>() {
                Ok(v) if v.is_finite() => col.push(Some(v)),
                _ => bail!("{}: \"{text}\" is not a finite number", at()),
            }
        }
        table.lines.push(line);
    }
    Ok(table)
}

/// Checks that times never go back (`strict`: that they increase), naming the line.
fn check_time_order(times: &[f64], lines: &[u64], key: &str, path: &Path, strict: bool) -> Result<()> {
    for i in 1..times.len() {
        let (before, t) = (times[i - 1], times[i]);
        if t < before || (strict && t == before) {
            bail!(
                "{key}: {} line {}: time {t} {} time {before} on line {}; times must {}",
                path.display(),
                lines[i],
                if t == before { "repeats the" } else { "comes before the" },
                lines[i - 1],
                if strict { "increase" } else { "not decrease" }
            );
        }
    }
    Ok(())
}

/// Frame times from `frames.timestamps` (first column, one row per listed frame, strictly
/// increasing: each frame is its own exposure) or from `frames.rate`. Returns the times and
/// a warning when the file has more rows than there are frames.
pub fn frame_times(timestamps: Option<&Path>, rate: Option<f64>, frames: usize) -> Result<(Vec<f64>, Option<String>)> {
    let path = match (timestamps, rate) {
        (Some(path), _) => path,
        (None, Some(rate)) => return Ok(((0..frames).map(|i| i as f64 / rate).collect(), None)),
        (None, None) => bail!("frames: give frames.rate or frames.timestamps"),
    };
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .with_context(|| format!("frames.timestamps: cannot read {}", path.display()))?;
    let first = reader.headers()?.get(0).unwrap_or_default().to_string();
    drop(reader);
    let table = read_table(path, &[first.as_str()], "frames.timestamps")?;
    let times: Vec<f64> = table.columns[0].iter().flatten().copied().collect();
    check_time_order(&times, &table.lines, "frames.timestamps", path, true)?;
    if times.len() < frames {
        bail!(
            "frames.timestamps: {} has {} times for {frames} frames",
            path.display(),
            times.len()
        );
    }
    let warning = (times.len() > frames).then(|| {
        format!(
            "frames.timestamps: {} has {} times for {frames} frames; the first {frames} are used",
            path.display(),
            times.len()
        )
    });
    Ok((times, warning))
}

/// Force/stage log sampled at its own times; linearly interpolated at frame times.
pub struct ForceLog {
    path: PathBuf,
    time: Vec<f64>,
    /// normal, tangential, stage_x, stage_z; `None` where the column is not mapped.
    channels: [Option<Vec<Option<f64>>>; 4],
    /// Empty cells (missing samples) of the mapped columns.
    empty_cells: usize,
}

impl ForceLog {
    /// Reads the log; time must not decrease (repeated times are accepted: samples faster
    /// than the clock's resolution).
    pub fn load(f: &ForcesSpec) -> Result<Self> {
        let mapped: Vec<(usize, &str)> = [&f.normal, &f.tangential, &f.stage_x, &f.stage_z]
            .iter()
            .enumerate()
            .filter_map(|(i, n)| n.as_deref().map(|n| (i, n)))
            .collect();
        let mut names = vec![f.time.as_str()];
        names.extend(mapped.iter().map(|(_, n)| *n));
        let mut table = read_table(&f.path, &names, "forces")?;
        let time: Vec<f64> = table.columns.remove(0).into_iter().flatten().collect();
        if time.is_empty() {
            bail!("forces: {} has no samples", f.path.display());
        }
        check_time_order(&time, &table.lines, "forces", &f.path, false)?;
        let mut channels: [Option<Vec<Option<f64>>>; 4] = Default::default();
        for ((slot, _), col) in mapped.iter().zip(table.columns) {
            channels[*slot] = Some(col);
        }
        Ok(Self {
            path: f.path.clone(),
            time,
            channels,
            empty_cells: table.empty_cells,
        })
    }

    /// Frames outside the log's time span get no force: none inside is an error, some
    /// outside a warning with their count.
    pub fn check_overlap(&self, frame_times: &[f64]) -> Result<Option<String>> {
        let (t0, t1) = (self.time[0], self.time[self.time.len() - 1]);
        let outside = frame_times.iter().filter(|&&t| !(t >= t0 && t <= t1)).count();
        let n = frame_times.len();
        let span = |t: &[f64]| format!("t = {} … {}", t[0], t[t.len() - 1]);
        if outside == n {
            bail!(
                "forces: the log {} ({}) does not overlap the frames ({}) in time: no frame would have a force",
                self.path.display(),
                span(&self.time),
                span(frame_times)
            );
        }
        Ok((outside > 0).then(|| {
            format!(
                "forces: {outside} of {n} frames lie outside the time span of {} ({}) and have no force",
                self.path.display(),
                span(&self.time)
            )
        }))
    }

    /// Empty data cells are missing samples: a warning with their count.
    pub fn empty_cells_warning(&self) -> Option<String> {
        (self.empty_cells > 0).then(|| {
            format!(
                "forces: {} has {} empty cells (missing samples); frames next to one have no value in that column",
                self.path.display(),
                self.empty_cells
            )
        })
    }

    /// Value of channel `c` at time t; `None` outside the log or next to a missing sample.
    pub fn at(&self, c: usize, t: f64) -> Option<f64> {
        let values = self.channels[c].as_ref()?;
        let n = self.time.len();
        if n == 0 || !(t >= self.time[0] && t <= self.time[n - 1]) {
            return None;
        }
        let hi = self.time.partition_point(|&x| x < t).min(n - 1);
        if self.time[hi] == t || hi == 0 {
            return values[hi];
        }
        let (t0, t1) = (self.time[hi - 1], self.time[hi]);
        let (v0, v1) = (values[hi - 1]?, values[hi]?);
        let v = if t1 > t0 {
            v0 + (v1 - v0) * (t - t0) / (t1 - t0)
        } else {
            v1
        };
        v.is_finite().then_some(v)
    }
}
