//! `adhesim experiment`: analysis of filmed contact experiments, and `adhesim experiment synth`
//! to generate a synthetic one. Numerics live in `adhesim_experiment`; this module reads
//! frames and logs, writes `frames.csv`, `changes/`, `plots/` and `summary.json`.

mod plots;
mod spec;

use adhesim_experiment::fit::{fit_jkr_work_of_adhesion, friction_law_fit, pinned_phase, power_law_fit};
use adhesim_experiment::synthetic::SyntheticSpec;
use adhesim_experiment::{
    change_map, classify_phases, detect_jumps, measure, AreaMeasurement, BackgroundModel, Change, GrayImage,
    IndenterTrack, Phase, SegmentationParams, Segmenter,
};
use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use plots::{Panel, Series};
use plotters::style::RGBColor;
use rayon::prelude::*;
use serde_json::json;
use spec::{BackgroundChoice, Reference, Settings};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `adhesim experiment`.
#[derive(Debug, clap::Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct ExperimentArgs {
    #[command(subcommand)]
    pub command: Option<ExperimentCommand>,
    /// Experiment spec (TOML), see docs/interface-experiment.md.
    pub spec: Option<PathBuf>,
    /// Output folder (default: out/<spec file stem>/).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Subcommands of `adhesim experiment`.
#[derive(Debug, clap::Subcommand)]
pub enum ExperimentCommand {
    /// Generate a synthetic experiment (frames, force log, spec) with known contact.
    Synth(SynthArgs),
}

/// Arguments of `adhesim experiment synth`.
#[derive(Debug, clap::Args)]
pub struct SynthArgs {
    /// Output folder (default: out/synth/).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Number of frames.
    #[arg(long, default_value_t = 100)]
    pub frames: usize,
    /// Frame width in pixels.
    #[arg(long, default_value_t = 1600)]
    pub width: usize,
    /// Frame height in pixels.
    #[arg(long, default_value_t = 1200)]
    pub height: usize,
    /// Contrast-to-noise ratio (inf = no noise).
    #[arg(long, default_value_t = 10.0)]
    pub snr: f64,
    /// Seed of the noise and the contact spots.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Optical blur σ in pixels.
    #[arg(long, default_value_t = 1.5)]
    pub blur: f64,
    /// Strength of the uneven illumination (0 = even).
    #[arg(long, default_value_t = 0.2)]
    pub illumination: f64,
    /// Contact size relative to the default (semi-axes 260/300/280 px at 1600×1200).
    #[arg(long, default_value_t = 1.0)]
    pub scale: f64,
    /// Frames per stick phase.
    #[arg(long, default_value_t = 12)]
    pub stick_frames: usize,
    /// Image format: png or tiff.
    #[arg(long, default_value = "png")]
    pub format: String,
    /// Bits per sample: 8 or 16.
    #[arg(long, default_value_t = 8)]
    pub bits: u8,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Entry point of the `experiment` subcommand.
pub fn main(args: ExperimentArgs) -> Result<()> {
    match (args.command, args.spec) {
        (Some(ExperimentCommand::Synth(synth)), _) => run_synth(&synth),
        (None, Some(spec)) => run_experiment(&spec, args.out.as_deref(), args.quiet),
        (None, None) => {
            bail!("give a spec file (adhesim experiment SPEC.toml) or a subcommand (adhesim experiment synth)")
        }
    }
}

fn progress(len: usize, quiet: bool, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len as u64);
    if quiet || !std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    } else if let Ok(style) = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} {per_sec} eta {eta}") {
        bar.set_style(style.progress_chars("=> "));
        bar.set_message(what.to_string());
    }
    bar
}

// ---------------------------------------------------------------- frames and logs

const FRAME_EXTENSIONS: [&str; 5] = ["png", "tif", "tiff", "jpg", "jpeg"];

/// Image files of a folder in file-name order.
fn list_frames(dir: &Path) -> Result<Vec<PathBuf>> {
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
fn read_frame(path: &Path) -> Result<GrayImage> {
    let img = image::ImageReader::open(path)?.with_guessed_format()?.decode()?;
    let (w, h) = (img.width() as usize, img.height() as usize);
    Ok(match img {
        image::DynamicImage::ImageLuma8(buf) => GrayImage::from_u8(w, h, buf.as_raw())?,
        image::DynamicImage::ImageLuma16(buf) => GrayImage::from_u16(w, h, buf.as_raw())?,
        other => GrayImage::from_u16(w, h, other.to_luma16().as_raw())?,
    })
}

fn name_of(path: &Path) -> String {
    path.file_name()
        .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}

/// A column of a CSV file by header name, as numbers (unparsable cells are `None`).
fn read_columns(path: &Path, names: &[&str], key: &str) -> Result<Vec<Vec<Option<f64>>>> {
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
    let mut columns = vec![Vec::new(); names.len()];
    for record in reader.records() {
        let record = record.with_context(|| format!("{key}: malformed CSV in {}", path.display()))?;
        for (col, &i) in columns.iter_mut().zip(&index) {
            col.push(
                record
                    .get(i)
                    .and_then(|s| s.parse::<f64>().ok())
                    .filter(|v| v.is_finite()),
            );
        }
    }
    Ok(columns)
}

/// Force/stage log sampled at its own times; linearly interpolated at frame times.
struct ForceLog {
    time: Vec<f64>,
    /// normal, tangential, stage_x, stage_z; `None` where the column is not mapped.
    channels: [Option<Vec<Option<f64>>>; 4],
}

impl ForceLog {
    fn load(f: &spec::ForcesSpec) -> Result<Self> {
        let mapped: Vec<(usize, &str)> = [&f.normal, &f.tangential, &f.stage_x, &f.stage_z]
            .iter()
            .enumerate()
            .filter_map(|(i, n)| n.as_deref().map(|n| (i, n)))
            .collect();
        let mut names = vec![f.time.as_str()];
        names.extend(mapped.iter().map(|(_, n)| *n));
        let mut columns = read_columns(&f.path, &names, "forces")?;
        let time_col = columns.remove(0);
        // Keep rows with a time, in time order.
        let mut order: Vec<usize> = (0..time_col.len()).filter(|&i| time_col[i].is_some()).collect();
        order.sort_by(|&a, &b| time_col[a].unwrap_or(0.0).total_cmp(&time_col[b].unwrap_or(0.0)));
        let time = order.iter().filter_map(|&i| time_col[i]).collect();
        let mut channels: [Option<Vec<Option<f64>>>; 4] = Default::default();
        for ((slot, _), col) in mapped.iter().zip(columns) {
            channels[*slot] = Some(order.iter().map(|&i| col[i]).collect());
        }
        Ok(Self { time, channels })
    }

    /// Value of channel `c` at time t; `None` outside the log or next to a missing sample.
    fn at(&self, c: usize, t: f64) -> Option<f64> {
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

// ---------------------------------------------------------------- analysis

/// Everything known about one readable frame.
struct FrameRow {
    frame: usize,
    time: f64,
    m: AreaMeasurement,
    force_normal: Option<f64>,
    force_tangential: Option<f64>,
    stage_x: Option<f64>,
    stage_z: Option<f64>,
    jump: bool,
    phase: Phase,
}

fn ratio(num: Option<f64>, den: f64) -> Option<f64> {
    let v = num? / den;
    (den > 0.0 && v.is_finite()).then_some(v)
}

fn build_segmenter(settings: &Settings, files: &[PathBuf]) -> Result<Segmenter> {
    let background = match &settings.background {
        BackgroundChoice::None => BackgroundModel::None,
        BackgroundChoice::Fit => BackgroundModel::Fitted,
        BackgroundChoice::File(p) => BackgroundModel::Reference(
            read_frame(p).with_context(|| format!("contact.background: cannot read {}", p.display()))?,
        ),
    };
    let params = SegmentationParams {
        polarity: settings.polarity,
        threshold: settings.threshold,
        background,
        correction: settings.correction,
        smooth_radius: settings.smooth_radius,
        open_radius: settings.open_radius,
        close_radius: settings.close_radius,
        roi: settings.roi,
    };
    // Calibration frames: up to 5, evenly spaced, readable ones only.
    let picks: Vec<usize> = if files.len() <= 5 {
        (0..files.len()).collect()
    } else {
        (0..5).map(|i| i * (files.len() - 1) / 4).collect()
    };
    let samples: Vec<GrayImage> = picks.par_iter().filter_map(|&i| read_frame(&files[i]).ok()).collect();
    if let Some(first) = samples.first() {
        if samples
            .iter()
            .any(|s| (s.width(), s.height()) != (first.width(), first.height()))
        {
            bail!("frames differ in size; all frames must have the same size");
        }
    }
    Segmenter::new(params, &samples).context("contact threshold calibration")
}

/// Runs `adhesim experiment SPEC.toml [--out DIR]`.
pub fn run_experiment(spec_path: &Path, out: Option<&Path>, quiet: bool) -> Result<()> {
    let started = Instant::now();
    let settings = spec::load(spec_path)?;
    let out_dir = match out {
        Some(d) => d.to_path_buf(),
        None => Path::new("out").join(spec_path.file_stem().unwrap_or_default()),
    };
    let files = list_frames(&settings.frames_dir)?;
    let times: Vec<f64> = match (&settings.timestamps, settings.rate) {
        (Some(path), _) => {
            let mut reader = csv::ReaderBuilder::new()
                .has_headers(true)
                .trim(csv::Trim::All)
                .from_path(path)
                .with_context(|| format!("frames.timestamps: cannot read {}", path.display()))?;
            let mut t = Vec::new();
            for (row, record) in reader.records().enumerate() {
                let record = record?;
                let v: f64 = record
                    .get(0)
                    .and_then(|s| s.parse().ok())
                    .filter(|v: &f64| v.is_finite())
                    .with_context(|| {
                        format!(
                            "frames.timestamps: row {} of {} is not a number",
                            row + 1,
                            path.display()
                        )
                    })?;
                t.push(v);
            }
            if t.len() < files.len() {
                bail!("frames.timestamps: {} times for {} frames", t.len(), files.len());
            }
            t
        }
        (None, Some(rate)) => (0..files.len()).map(|i| i as f64 / rate).collect(),
        (None, None) => bail!("frames: give frames.rate or frames.timestamps"),
    };
    let log = settings.forces.as_ref().map(ForceLog::load).transpose()?;
    let segmenter = build_segmenter(&settings, &files)?;
    let track = settings
        .indenter
        .map(|(cx, cy, x0, motion)| IndenterTrack::new([cx, cy], x0, motion, settings.pixel_size))
        .transpose()?;

    let bar = progress(files.len(), quiet, "frames");
    let decoded_at = Instant::now();
    let results: Vec<Option<FrameRow>> = files
        .par_iter()
        .enumerate()
        .map(|(i, path)| {
            let row = analyse_frame(
                i,
                path,
                times[i],
                &segmenter,
                log.as_ref(),
                track.as_ref(),
                settings.pixel_size,
            );
            bar.inc(1);
            match row {
                Ok(r) => Some(r),
                Err(e) => {
                    bar.suspend(|| eprintln!("skipping unreadable frame {}: {e:#}", name_of(path)));
                    None
                }
            }
        })
        .collect();
    bar.finish_and_clear();
    let analysis_seconds = decoded_at.elapsed().as_secs_f64();
    let skipped: Vec<String> = files
        .iter()
        .zip(&results)
        .filter(|(_, r)| r.is_none())
        .map(|(p, _)| name_of(p))
        .collect();
    let mut rows: Vec<FrameRow> = results.into_iter().flatten().collect();
    if rows.is_empty() {
        bail!("no readable frames in {}", settings.frames_dir.display());
    }
    // Sequence-level analysis: jumps and stick/slip phases over the readable frames.
    let areas: Vec<f64> = rows.iter().map(|r| r.m.area).collect();
    let jumps = detect_jumps(&areas, settings.phases.jump_threshold)?;
    let xs: Vec<f64> = rows.iter().map(|r| r.stage_x.unwrap_or(f64::NAN)).collect();
    let fxs: Vec<f64> = rows.iter().map(|r| r.force_tangential.unwrap_or(f64::NAN)).collect();
    let has_motion = xs.iter().any(|v| v.is_finite()) && fxs.iter().any(|v| v.is_finite());
    let phases = classify_phases(&areas, has_motion.then_some((&xs[..], &fxs[..])), &settings.phases)?;
    for ((r, j), p) in rows.iter_mut().zip(jumps).zip(phases) {
        r.jump = j;
        r.phase = p;
    }

    std::fs::create_dir_all(out_dir.join("plots")).with_context(|| format!("cannot create {}", out_dir.display()))?;
    std::fs::create_dir_all(out_dir.join("changes"))?;
    write_frames_csv(&out_dir.join("frames.csv"), &rows)?;
    let changes_written = write_change_maps(&settings, &files, &rows, &segmenter, &out_dir.join("changes"))?;
    write_plots(&out_dir.join("plots"), &rows)?;
    let results = fit_results(&settings, &rows)?;
    let summary = json!({
        "inputs": {
            "spec": spec_path.display().to_string(),
            "frames_path": settings.frames_dir.display().to_string(),
            "pixel_size": settings.pixel_size,
            "threshold": finite(f64::from(segmenter.threshold())),
        },
        "frames": { "listed": files.len(), "analysed": rows.len(), "skipped": skipped, "change_maps": changes_written },
        "results": results,
        "performance": {
            "wall_seconds": started.elapsed().as_secs_f64(),
            "analysis_seconds": analysis_seconds,
            "frames_per_second": finite(rows.len() as f64 / analysis_seconds.max(1e-9)),
        },
    });
    std::fs::write(out_dir.join("summary.json"), serde_json::to_string_pretty(&summary)?)?;
    if !quiet {
        eprintln!(
            "analysed {} of {} frames into {}",
            rows.len(),
            files.len(),
            out_dir.display()
        );
    }
    Ok(())
}

fn analyse_frame(
    index: usize,
    path: &Path,
    time: f64,
    segmenter: &Segmenter,
    log: Option<&ForceLog>,
    track: Option<&IndenterTrack>,
    pixel_size: f64,
) -> Result<FrameRow> {
    let image = read_frame(path)?;
    let mask = segmenter.segment(&image)?;
    let channel = |c: usize| log.and_then(|l| l.at(c, time));
    let stage_x = channel(2);
    let split = track.map(|t| (t.centre_at(stage_x.unwrap_or(t.stage_x0)), t.motion));
    let m = measure(&mask, pixel_size, split)?;
    Ok(FrameRow {
        frame: index,
        time,
        m,
        force_normal: channel(0),
        force_tangential: channel(1),
        stage_x,
        stage_z: channel(3),
        jump: false,
        phase: Phase::Undetermined,
    })
}

/// JSON number, or null for anything non-finite (never NaN in outputs).
fn finite(v: f64) -> serde_json::Value {
    if v.is_finite() {
        json!(v)
    } else {
        serde_json::Value::Null
    }
}

fn cell(v: Option<f64>) -> String {
    v.filter(|v| v.is_finite()).map_or_else(String::new, |v| format!("{v}"))
}

fn write_frames_csv(path: &Path, rows: &[FrameRow]) -> Result<()> {
    let mut w = csv::Writer::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    w.write_record([
        "frame",
        "time",
        "area",
        "area_front",
        "area_rear",
        "force_normal",
        "force_tangential",
        "pressure",
        "tangential_stress",
        "stage_x",
        "stage_z",
        "jump",
        "phase",
        "pixels",
        "centroid_x_px",
        "centroid_y_px",
        "width",
        "length",
    ])?;
    for r in rows {
        let c = r.m.centroid_px;
        w.write_record([
            r.frame.to_string(),
            cell(Some(r.time)),
            cell(Some(r.m.area)),
            cell(Some(r.m.area_front)),
            cell(Some(r.m.area_rear)),
            cell(r.force_normal),
            cell(r.force_tangential),
            cell(ratio(r.force_normal, r.m.area)),
            cell(ratio(r.force_tangential, r.m.area)),
            cell(r.stage_x),
            cell(r.stage_z),
            u8::from(r.jump).to_string(),
            r.phase.name().to_string(),
            r.m.pixels.to_string(),
            cell(c.map(|c| c[0])),
            cell(c.map(|c| c[1])),
            cell(Some(r.m.width)),
            cell(Some(r.m.length)),
        ])?;
    }
    w.flush()?;
    Ok(())
}

/// Change-map overlays on the raw frame: new contact red, vanished contact blue.
fn write_change_maps(
    settings: &Settings,
    files: &[PathBuf],
    rows: &[FrameRow],
    segmenter: &Segmenter,
    dir: &Path,
) -> Result<usize> {
    // Pairs (reference row, current row) by position in `rows`.
    let mut picks: Vec<(usize, usize)> = Vec::new();
    let reference_of = |k: usize| -> Option<usize> {
        match settings.reference {
            Reference::First => (k > 0).then_some(0),
            Reference::Previous => k.checked_sub(1),
            Reference::Frame(f) => rows.iter().position(|r| r.frame == f).filter(|&p| p != k),
        }
    };
    for (k, r) in rows.iter().enumerate() {
        let scheduled = settings.changes_every > 0 && r.frame % settings.changes_every == 0;
        if scheduled || (settings.changes_at_jumps && r.jump) {
            if let Some(reference) = reference_of(k) {
                picks.push((reference, k));
            }
        }
    }
    if picks.len() > settings.changes_max {
        // Keep an evenly spread subset.
        let n = picks.len();
        picks = (0..settings.changes_max)
            .map(|i| picks[i * n / settings.changes_max])
            .collect();
    }
    let written: Vec<Result<()>> = picks
        .par_iter()
        .map(|&(a, b)| {
            let (ra, rb) = (&rows[a], &rows[b]);
            let reference_mask = segmenter.segment(&read_frame(&files[ra.frame])?)?;
            let raw = read_frame(&files[rb.frame])?;
            let current_mask = segmenter.segment(&raw)?;
            let map = change_map(&reference_mask, &current_mask)?;
            let (x0, y0, x1, y1) = crop_box(&reference_mask, &current_mask, CHANGE_MAP_MARGIN_PX);
            let width = raw.width();
            let mut rgb = image::RgbImage::new((x1 - x0) as u32, (y1 - y0) as u32);
            for (y, row) in (y0..y1).zip(rgb.rows_mut()) {
                for (x, px) in (x0..x1).zip(row) {
                    let i = y * width + x;
                    let g = (raw.pixels()[i].clamp(0.0, 1.0) * 255.0) as u8;
                    *px = match map.changes()[i] {
                        Change::New => image::Rgb([255, 0, 0]),
                        Change::Vanished => image::Rgb([0, 0, 255]),
                        Change::Unchanged => image::Rgb([g, g, g]),
                    };
                }
            }
            let name = format!("change_{:05}_vs_{:05}.png", rb.frame, ra.frame);
            rgb.save(dir.join(&name))
                .with_context(|| format!("cannot write changes/{name}"))?;
            Ok(())
        })
        .collect();
    let mut count = 0;
    for r in written {
        match r {
            Ok(()) => count += 1,
            Err(e) => eprintln!("change map skipped: {e:#}"),
        }
    }
    Ok(count)
}

/// Change maps show the contact's bounding box (both masks) plus this margin, like the
/// paper's Figs. 16 and 24; the whole frame when there is no contact.
const CHANGE_MAP_MARGIN_PX: usize = 20;

/// Bounding box [x0, x1) × [y0, y1) of the union of two masks, widened by `margin`.
fn crop_box(
    a: &adhesim_experiment::ContactMask,
    b: &adhesim_experiment::ContactMask,
    margin: usize,
) -> (usize, usize, usize, usize) {
    let (w, h) = (a.width(), a.height());
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for y in 0..h {
        for x in 0..w {
            if a.get(x, y) || b.get(x, y) {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x + 1), y1.max(y + 1));
            }
        }
    }
    if x0 == usize::MAX {
        return (0, 0, w, h);
    }
    (
        x0.saturating_sub(margin),
        y0.saturating_sub(margin),
        (x1 + margin).min(w),
        (y1 + margin).min(h),
    )
}

const RED: RGBColor = RGBColor(214, 39, 40);
const BLUE: RGBColor = RGBColor(31, 119, 180);
const BLACK: RGBColor = RGBColor(0, 0, 0);

fn series(rows: &[FrameRow], label: &'static str, color: RGBColor, value: impl Fn(&FrameRow) -> Option<f64>) -> Series {
    Series {
        label,
        color,
        points: rows
            .iter()
            .filter_map(|r| value(r).filter(|v| v.is_finite()).map(|v| (r.time, v)))
            .collect(),
    }
}

fn write_plots(dir: &Path, rows: &[FrameRow]) -> Result<()> {
    let area_panel = || Panel {
        y_label: "area",
        series: vec![
            series(rows, "total", BLACK, |r| Some(r.m.area)),
            series(rows, "front", RED, |r| Some(r.m.area_front)),
            series(rows, "rear", BLUE, |r| Some(r.m.area_rear)),
        ],
    };
    plots::write_panels(dir, "areas", "Contact area", &[area_panel()])?;
    let fx = || Panel {
        y_label: "F_x",
        series: vec![series(rows, "F_x", BLACK, |r| r.force_tangential)],
    };
    let tau = || Panel {
        y_label: "tau = F_x/A",
        series: vec![series(rows, "tau", BLACK, |r| ratio(r.force_tangential, r.m.area))],
    };
    // Paper Fig. 19: F_x, areas (total/front/rear), τ.
    plots::write_panels(
        dir,
        "sliding",
        "Tangential force, contact areas, tangential stress",
        &[fx(), area_panel(), tau()],
    )?;
    // Paper Fig. 22: F_N, F_x, p, τ.
    let fn_panel = Panel {
        y_label: "F_N",
        series: vec![series(rows, "F_N", BLACK, |r| r.force_normal)],
    };
    let p_panel = Panel {
        y_label: "p = F_N/A",
        series: vec![series(rows, "p", BLACK, |r| ratio(r.force_normal, r.m.area))],
    };
    plots::write_panels(
        dir,
        "forces",
        "Normal force, tangential force, pressure, tangential stress",
        &[fn_panel, fx(), p_panel, tau()],
    )?;
    Ok(())
}

fn fit_results(settings: &Settings, rows: &[FrameRow]) -> Result<serde_json::Value> {
    let areas: Vec<f64> = rows.iter().map(|r| r.m.area).collect();
    let max_area = areas.iter().copied().fold(0.0, f64::max);
    let jumps = rows.iter().filter(|r| r.jump).count();
    let stick = rows.iter().filter(|r| r.phase == Phase::Stick).count();
    // Friction law (Eq. 18) on frames with a tangential force and contact, in the window.
    let in_window = |t: f64| settings.fits.friction_window.is_none_or(|[t0, t1]| t >= t0 && t <= t1);
    let (fa, ft): (Vec<f64>, Vec<f64>) = rows
        .iter()
        .filter(|r| in_window(r.time))
        .filter_map(|r| ratio(r.force_tangential, r.m.area).map(|tau| (r.m.area, tau)))
        .unzip();
    let mean_stress = (!ft.is_empty()).then(|| ft.iter().sum::<f64>() / ft.len() as f64);
    let friction = friction_law_fit(&fa, &ft)
        .ok()
        .map(|f| json!({"tau0": finite(f.tau0), "q": finite(f.q), "r2": finite(f.r2), "points": f.points}));
    // Normal curve: JKR fits on approach and pull-off, pinned phase after reversal.
    let depth: Vec<f64> = rows.iter().map(|r| r.stage_z.unwrap_or(f64::NAN)).collect();
    let radius: Vec<f64> = areas.iter().map(|a| (a / std::f64::consts::PI).sqrt()).collect();
    let force: Vec<f64> = rows.iter().map(|r| r.force_normal.unwrap_or(f64::NAN)).collect();
    let pinned = pinned_phase(&depth, &radius, settings.fits.pinned_tolerance.unwrap_or(0.01))?
        .filter(|p| p.last > p.reversal && depth.iter().any(|d| d.is_finite() && *d != depth[p.reversal]));
    let (mut gamma_approach, mut gamma_pulloff) = (None, None);
    if let (Some(e), Some(r), Some(p)) = (settings.fits.contact_modulus, settings.fits.indenter_radius, pinned) {
        // (contact radius, force) pairs of each branch; the spec has checked e, r > 0.
        let branch =
            |range: std::ops::Range<usize>| -> Vec<(f64, f64)> { range.map(|i| (radius[i], force[i])).collect() };
        gamma_approach = fit_jkr_work_of_adhesion(&branch(0..p.reversal + 1), r, e).map(|f| f.work_of_adhesion);
        gamma_pulloff = fit_jkr_work_of_adhesion(&branch(p.last + 1..force.len()), r, e).map(|f| f.work_of_adhesion);
    }
    let power_law = match &settings.fits.power_law {
        Some(pl) => {
            let cols = read_columns(&pl.path, &[pl.time.as_str(), pl.force.as_str()], "fits.power_law")?;
            let t: Vec<f64> = cols[0].iter().map(|v| v.unwrap_or(f64::NAN)).collect();
            let f: Vec<f64> = cols[1].iter().map(|v| v.unwrap_or(f64::NAN)).collect();
            power_law_fit(&t, &f).ok().map(|p| json!({"coefficient": finite(p.coefficient), "exponent": finite(p.exponent), "r2": finite(p.r2), "points": p.points}))
        }
        None => None,
    };
    let max_adhesive = force
        .iter()
        .filter(|f| f.is_finite() && **f < 0.0)
        .fold(None, |m: Option<f64>, f| Some(m.map_or(-f, |m| m.max(-f))));
    Ok(json!({
        "max_area": finite(max_area),
        "jumps": jumps,
        "stick_frames": stick,
        "mean_tangential_stress": mean_stress.map(finite),
        "max_adhesive_force": max_adhesive.map(finite),
        "friction_law": friction,
        "pinned_phase_depth": pinned.map(|p| finite(p.depth_span)),
        "gamma_approach": gamma_approach.map(finite),
        "gamma_pulloff": gamma_pulloff.map(finite),
        "boundary_friction": gamma_approach.zip(gamma_pulloff).map(|(g1, g2)| finite((g2 - g1) / 2.0)),
        "power_law": power_law,
    }))
}

// ---------------------------------------------------------------- synth

/// Runs `adhesim experiment synth`: frames under `frames/`, `log.csv`, `truth.csv` and a ready
/// `experiment.toml` in the output folder.
pub fn run_synth(args: &SynthArgs) -> Result<()> {
    let out_dir = args.out.clone().unwrap_or_else(|| PathBuf::from("out/synth"));
    let defaults = SyntheticSpec::default();
    if !(args.scale.is_finite() && args.scale > 0.0) {
        bail!("--scale must be > 0, got {}", args.scale);
    }
    if !matches!(args.bits, 8 | 16) {
        bail!("--bits must be 8 or 16, got {}", args.bits);
    }
    let ext = match args.format.as_str() {
        "png" => "png",
        "tiff" | "tif" => "tif",
        other => bail!("--format must be png or tiff, got \"{other}\""),
    };
    if args.frames == 0 {
        bail!("--frames must be >= 1, got 0");
    }
    // Geometry scales with the frame so that small test frames keep the same layout.
    let fit = (args.width as f64 / 1600.0).min(args.height as f64 / 1200.0) * args.scale;
    let spec = SyntheticSpec {
        width: args.width,
        height: args.height,
        frames: args.frames,
        seed: args.seed,
        snr: args.snr,
        blur_sigma_px: args.blur,
        illumination: args.illumination,
        start_centre_px: [args.width as f64 * 0.4375, args.height as f64 * 0.5],
        front_radius_px: defaults.front_radius_px * fit,
        rear_radius_px: defaults.rear_radius_px * fit,
        half_width_px: defaults.half_width_px * fit,
        speed_px_per_frame: (defaults.speed_px_per_frame * fit).max(0.25),
        stick_frames: args.stick_frames,
        ..defaults
    };
    spec.validate()?;
    let frames_dir = out_dir.join("frames");
    std::fs::create_dir_all(&frames_dir).with_context(|| format!("cannot create {}", frames_dir.display()))?;
    let bar = progress(args.frames, args.quiet, "synth");
    let logs: Vec<_> = (0..args.frames)
        .into_par_iter()
        .map(|k| -> Result<_> {
            let frame = spec.render(k)?;
            let (w, h) = (spec.width as u32, spec.height as u32);
            let path = frames_dir.join(format!("frame_{k:05}.{ext}"));
            let result = if args.bits == 8 {
                image::GrayImage::from_raw(w, h, frame.image.to_u8()).map(|b| b.save(&path))
            } else {
                image::ImageBuffer::<image::Luma<u16>, _>::from_raw(w, h, frame.image.to_u16()).map(|b| b.save(&path))
            };
            result
                .context("image buffer size")?
                .with_context(|| format!("cannot write {}", path.display()))?;
            bar.inc(1);
            Ok(frame.log)
        })
        .collect::<Result<_>>()?;
    bar.finish_and_clear();
    let mut log = csv::Writer::from_path(out_dir.join("log.csv"))?;
    log.write_record(["t", "Fn", "Fx", "x", "z"])?;
    let mut truth = csv::Writer::from_path(out_dir.join("truth.csv"))?;
    truth.write_record(["frame", "time", "true_area"])?;
    for (k, e) in logs.iter().enumerate() {
        log.write_record([e.time, e.force_normal, e.force_tangential, e.stage_x, e.stage_z].map(|v| v.to_string()))?;
        truth.write_record([k.to_string(), e.time.to_string(), e.true_area.to_string()])?;
    }
    log.flush()?;
    truth.flush()?;
    let toml = format!(
        "# Generated by `adhesim experiment synth` (seed {seed}, SNR {snr}).\n\
         [frames]\npath = \"frames/\"\npixel_size = {px}\nrate = {rate}\n\n\
         [forces]\npath = \"log.csv\"\ntime = \"t\"\nnormal = \"Fn\"\ntangential = \"Fx\"\nstage_x = \"x\"\nstage_z = \"z\"\n\n\
         [contact]\nthreshold = \"otsu\"\ncontact_is = \"bright\"\nbackground = \"fit\"\n\n\
         [indenter]\ncentre_px = [{cx}, {cy}]\nstage_x0 = 0.0\nmotion = \"+x\"\n\n\
         [changes]\nreference = \"previous\"\nevery = 0\nat_jumps = true\nmax = 20\n",
        seed = spec.seed,
        snr = spec.snr,
        px = spec.pixel_size,
        rate = spec.frame_rate,
        cx = spec.start_centre_px[0],
        cy = spec.start_centre_px[1],
    );
    std::fs::write(out_dir.join("experiment.toml"), toml)?;
    if !args.quiet {
        eprintln!(
            "wrote {} frames, log.csv, truth.csv and experiment.toml to {}",
            args.frames,
            out_dir.display()
        );
    }
    Ok(())
}
