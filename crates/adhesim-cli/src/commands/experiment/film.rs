//! `adhesim experiment film RUN`: a simulated run filmed as the paper's camera films its
//! experiments (the contact dark through the rubber, blur, uneven light, noise), with the
//! run's forces as the force log, its own areas as the truth and a ready spec, so that
//! `adhesim experiment` analyses it like a filmed experiment (docs/experiments.md §6, A
//! simulated run, filmed).

use super::progress;
use adhesim_experiment::film::{FilmFrame, GridContact};
use adhesim_experiment::{measure, Camera, Motion};
use adhesim_figures::figure::files::save_image;
use anyhow::{bail, Context, Result};
use ndarray::{Array1, Array3};
use ndarray_npy::ReadNpyExt;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// Arguments of `adhesim experiment film`.
#[derive(Debug, clap::Args)]
pub struct FilmArgs {
    /// The runs' output folders (each with its `curve.csv` and `fields.npz`; a run with
    /// `output.snapshot_every = 1` has a frame per step), filmed one after the other on the
    /// same grid (slides at several depths give Eq. 18's fit contacts of several sizes).
    #[arg(required = true)]
    pub runs: Vec<PathBuf>,
    /// Film only the steps whose axis has travelled at least this far (length units; 0:
    /// every step after the approach), to leave out a slide's first stick phase.
    #[arg(long, default_value_t = 0.0)]
    pub from_x: f64,
    /// Output folder (default: out/film/).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Frame width in pixels.
    #[arg(long, default_value_t = 1600)]
    pub width: usize,
    /// Frame height in pixels.
    #[arg(long, default_value_t = 1200)]
    pub height: usize,
    /// Pixels per element side (the pixel size is the smaller element side over this).
    #[arg(long, default_value_t = 8)]
    pub pixels_per_element: usize,
    /// Contrast-to-noise ratio (inf = no noise).
    #[arg(long, default_value_t = 10.0)]
    pub snr: f64,
    /// Optical blur σ in pixels.
    #[arg(long, default_value_t = 1.5)]
    pub blur: f64,
    /// Strength of the uneven illumination (0 = even).
    #[arg(long, default_value_t = 0.2)]
    pub illumination: f64,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Frames per second (the log's time is the frame index over it).
    #[arg(long, default_value_t = 1.0)]
    pub rate: f64,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// A step's row of `curve.csv`.
#[derive(Debug, Clone, Copy)]
struct CurveRow {
    step: usize,
    approach: bool,
    depth: f64,
    /// The indenter's axis (`x`).
    axis: f64,
    force_normal: f64,
    force_tangential: f64,
    /// Total, front and rear area (`area`, `area_front`, `area_rear`).
    areas: [f64; 3],
}

/// A filmed step: its run (counted from 0), its curve.csv row and its contact.
struct Shot {
    run: usize,
    row: CurveRow,
    contact: Vec<bool>,
}

/// Runs `adhesim experiment film`: frames under `frames/`, `log.csv`, `truth.csv` and
/// `experiment.toml` in the output folder.
pub fn run_film(args: &FilmArgs) -> Result<()> {
    let out_dir = args.out.clone().unwrap_or_else(|| PathBuf::from("out/film"));
    if args.pixels_per_element == 0 {
        bail!("--pixels-per-element must be >= 1, got 0");
    }
    // Each frame in flight holds about 10 bytes a pixel; synth's limit keeps it in memory.
    if args.width == 0 || args.height == 0 || args.width.saturating_mul(args.height) > 1 << 28 {
        bail!(
            "--width × --height must be 1 to 2^28 pixels, got {}×{}",
            args.width,
            args.height
        );
    }
    if !(args.rate.is_finite() && args.rate > 0.0) {
        bail!("--rate must be > 0, got {}", args.rate);
    }
    if !args.from_x.is_finite() {
        bail!("--from-x must be finite, got {}", args.from_x);
    }
    let (grid, shots) = read_runs(&args.runs, args.from_x)?;
    let camera = Camera {
        seed: args.seed,
        snr: args.snr,
        blur_sigma_px: args.blur,
        illumination: args.illumination,
        background_level: 0.7,
        contact_level: 0.2,
    };
    check_camera(&camera)?;
    let pixel_size = grid.dx.min(grid.dy) / args.pixels_per_element as f64;
    let middle = (shots[0].row.axis + shots[shots.len() - 1].row.axis) / 2.0;
    let frame = FilmFrame::centred(args.width, args.height, pixel_size, [middle, 0.0], &grid.contact(&[]));
    frame.validate()?;
    let frames_dir = out_dir.join("frames");
    if frames_dir.read_dir().is_ok_and(|mut entries| entries.next().is_some()) {
        bail!(
            "{} already holds files: choose another --out (nothing is overwritten)",
            frames_dir.display()
        );
    }
    std::fs::create_dir_all(&frames_dir).with_context(|| format!("cannot create {}", frames_dir.display()))?;
    let bar = progress(shots.len(), args.quiet, "film");
    let truths: Vec<[f64; 3]> = shots
        .par_iter()
        .enumerate()
        .map(|(k, shot)| -> Result<[f64; 3]> {
            let mask = frame.mask(&grid.contact(&shot.contact))?;
            let image = camera.expose(&mask, k)?;
            let (w, h) = (frame.width as u32, frame.height as u32);
            let buffer = image::GrayImage::from_raw(w, h, image.to_u8()).context("image buffer size")?;
            save_image(&buffer, &frames_dir.join(format!("frame_{k:05}.png")))?;
            let centre = frame.pixel_of([shot.row.axis, 0.0]);
            let seen = measure(&mask, pixel_size, Some((centre, Motion::PosX)))?;
            bar.inc(1);
            Ok([seen.area, seen.area_front, seen.area_rear])
        })
        .collect::<Result<_>>()?;
    bar.finish_and_clear();
    write_logs(&out_dir, args.rate, &shots, &truths)?;
    let [column, row] = frame.pixel_of([shots[0].row.axis, 0.0]);
    let toml = format!(
        "# Generated by `adhesim experiment film` from {run} (seed {seed}, SNR {snr}).\n\
         [frames]\npath = \"frames/\"\npixel_size = {pixel_size}\nrate = {rate}\n\n\
         [forces]\npath = \"log.csv\"\ntime = \"t\"\nnormal = \"Fn\"\ntangential = \"Fx\"\nstage_x = \"x\"\nstage_z = \"z\"\n\n\
         [contact]\nthreshold = \"otsu\"\ncontact_is = \"dark\"\nbackground = \"fit\"\n\n\
         [indenter]\ncentre_px = [{column}, {row}]\nstage_x0 = {x0}\nmotion = \"+x\"\n\n\
         [changes]\nreference = \"previous\"\nevery = 0\nat_jumps = true\nmax = 20\n\n\
         [analysis]\nforce_drop_threshold = 0.01  # a slip event drops F_x at constant area\n",
        run = args.runs.iter().map(|r| r.display().to_string()).collect::<Vec<_>>().join(", "),
        seed = args.seed,
        snr = args.snr,
        rate = args.rate,
        x0 = shots[0].row.axis,
    );
    std::fs::write(out_dir.join("experiment.toml"), toml)?;
    if !args.quiet {
        eprintln!(
            "adhesim: {} frames of {}×{} pixels of {pixel_size:e} (the run's length unit) in {}; analyse with adhesim experiment {}",
            shots.len(),
            frame.width,
            frame.height,
            out_dir.display(),
            out_dir.join("experiment.toml").display()
        );
    }
    Ok(())
}

/// The run's grid, read from `fields.npz`'s element centres.
struct RunGrid {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
}

impl RunGrid {
    fn contact<'a>(&self, contact: &'a [bool]) -> GridContact<'a> {
        GridContact {
            nx: self.nx,
            ny: self.ny,
            dx: self.dx,
            dy: self.dy,
            contact,
        }
    }
}

/// The camera's levels and optics, checked as `adhesim experiment synth` checks them.
fn check_camera(camera: &Camera) -> Result<()> {
    if camera.snr.is_nan() || camera.snr <= 0.0 {
        bail!("--snr must be > 0 (inf: no noise), got {}", camera.snr);
    }
    if !(0.0..20.0).contains(&camera.blur_sigma_px) {
        bail!("--blur must be in 0..20 pixels, got {}", camera.blur_sigma_px);
    }
    if !(camera.illumination > -1.0 && camera.illumination < 1.0) {
        bail!("--illumination must be in (-1, 1), got {}", camera.illumination);
    }
    Ok(())
}

/// The grid and the filmed steps of `runs`, one after the other, from an axis at `from_x`
/// on; the runs must share their grid.
fn read_runs(runs: &[PathBuf], from_x: f64) -> Result<(RunGrid, Vec<Shot>)> {
    let mut all: Option<(RunGrid, Vec<Shot>)> = None;
    for (index, run) in runs.iter().enumerate() {
        let (grid, mut shots) = read_run(run, index)?;
        shots.retain(|shot| shot.row.axis >= from_x);
        match &mut all {
            None => all = Some((grid, shots)),
            Some((first, filmed)) => {
                if (first.nx, first.ny) != (grid.nx, grid.ny) || first.dx != grid.dx || first.dy != grid.dy {
                    bail!(
                        "{}: its grid {}×{} of {:e}×{:e} is not the first run's, {}×{} of {:e}×{:e}; film runs of one grid together",
                        run.display(), grid.nx, grid.ny, grid.dx, grid.dy, first.nx, first.ny, first.dx, first.dy
                    );
                }
                filmed.append(&mut shots);
            }
        }
    }
    let (grid, shots) = all.expect("clap asks for one run at least");
    if shots.is_empty() {
        bail!("no step of the runs has its axis at --from-x = {from_x} or beyond");
    }
    Ok((grid, shots))
}

/// The grid and the filmed steps of a run (the `index`-th filmed): the snapshot steps of
/// `fields.npz` after the approach, with their `curve.csv` rows.
fn read_run(run: &Path, index: usize) -> Result<(RunGrid, Vec<Shot>)> {
    let path = run.join("fields.npz");
    let file = std::fs::File::open(&path)
        .with_context(|| format!("cannot read {}: RUN must be a run's output folder", path.display()))?;
    let mut archive = zip::ZipArchive::new(file).with_context(|| format!("{} is not a zip archive", path.display()))?;
    let x: Array1<f64> = read_member(&mut archive, &path, "x")?;
    let y: Array1<f64> = read_member(&mut archive, &path, "y")?;
    let steps: Array1<f64> = read_member(&mut archive, &path, "steps")?;
    let contact: Array3<bool> = read_member(&mut archive, &path, "contact")?;
    let spacing = |c: &Array1<f64>| if c.len() > 1 { c[1] - c[0] } else { f64::NAN };
    let grid = RunGrid {
        nx: x.len(),
        ny: y.len(),
        dx: spacing(&x),
        dy: spacing(&y),
    };
    if !(grid.dx > 0.0 && grid.dy > 0.0) || contact.shape() != [steps.len(), grid.ny, grid.nx] {
        bail!(
            "{}: the contact stack {:?} does not fit the grid {}×{}",
            path.display(),
            contact.shape(),
            grid.nx,
            grid.ny
        );
    }
    let curve = read_curve(&run.join("curve.csv"))?;
    let mut shots = Vec::new();
    for (k, &step) in steps.iter().enumerate() {
        let Some(&row) = curve.iter().find(|r| r.step as f64 == step) else {
            bail!("{}: step {step} of fields.npz is not in curve.csv", run.display());
        };
        if !row.approach {
            let layer = contact.index_axis(ndarray::Axis(0), k);
            shots.push(Shot {
                run: index,
                row,
                contact: layer.iter().copied().collect(),
            });
        }
    }
    if shots.is_empty() {
        bail!(
            "{} holds no step after the approach: film a roll, slide, translate or shear run with output.snapshot_every = 1 (or a few)",
            path.display()
        );
    }
    Ok((grid, shots))
}

/// The rows of a run's `curve.csv` (its columns named in errors).
fn read_curve(path: &Path) -> Result<Vec<CurveRow>> {
    let mut reader = csv::Reader::from_path(path).with_context(|| format!("cannot read {}", path.display()))?;
    let headers = reader.headers()?.clone();
    let column = |name: &str| {
        headers.iter().position(|h| h == name).with_context(|| {
            format!(
                "{}: no column \"{name}\" (film a roll, slide, translate or shear with [friction])",
                path.display()
            )
        })
    };
    let names = [
        "step",
        "phase",
        "d",
        "x",
        "force_normal",
        "force_tangential",
        "area",
        "area_front",
        "area_rear",
    ];
    let index: Vec<usize> = names.iter().map(|n| column(n)).collect::<Result<_>>()?;
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.with_context(|| format!("malformed {}", path.display()))?;
        let number = |i: usize| -> Result<f64> {
            let text = record.get(index[i]).unwrap_or("");
            text.parse::<f64>()
                .with_context(|| format!("{}: {} = \"{text}\" is not a number", path.display(), names[i]))
        };
        rows.push(CurveRow {
            step: number(0)? as usize,
            approach: record.get(index[1]) == Some("approach"),
            depth: number(2)?,
            axis: number(3)?,
            force_normal: number(4)?,
            force_tangential: number(5)?,
            areas: [number(6)?, number(7)?, number(8)?],
        });
    }
    Ok(rows)
}

/// `log.csv` (t, Fn, Fx, the axis as the stage's x, the depth as its z) and `truth.csv`
/// (the run's element areas and the areas the camera's frame shows before any optics).
fn write_logs(out_dir: &Path, rate: f64, shots: &[Shot], seen: &[[f64; 3]]) -> Result<()> {
    let mut log = csv::Writer::from_path(out_dir.join("log.csv"))?;
    log.write_record(["t", "Fn", "Fx", "x", "z"])?;
    let mut truth = csv::Writer::from_path(out_dir.join("truth.csv"))?;
    truth.write_record([
        "frame",
        "run",
        "step",
        "time",
        "run_area",
        "run_area_front",
        "run_area_rear",
        "true_area",
        "true_area_front",
        "true_area_rear",
    ])?;
    for (k, (shot, seen)) in shots.iter().zip(seen).enumerate() {
        let row = &shot.row;
        let time = k as f64 / rate;
        log.write_record([time, row.force_normal, row.force_tangential, row.axis, row.depth].map(|v| v.to_string()))?;
        let mut line = vec![
            k.to_string(),
            shot.run.to_string(),
            row.step.to_string(),
            time.to_string(),
        ];
        line.extend(row.areas.iter().chain(seen).map(|v| v.to_string()));
        truth.write_record(line)?;
    }
    log.flush()?;
    truth.flush()?;
    Ok(())
}

/// The array `name` of the npz archive at `path`.
fn read_member<T: ReadNpyExt>(archive: &mut zip::ZipArchive<std::fs::File>, path: &Path, name: &str) -> Result<T> {
    let member = archive
        .by_name(&format!("{name}.npy"))
        .with_context(|| format!("{} has no array \"{name}\" (fields contract 2)", path.display()))?;
    T::read_npy(member).with_context(|| format!("{}: cannot read the array \"{name}\"", path.display()))
}
