//! The run's observer: writes `curve.csv` rows as the steps come, contact-map snapshots,
//! drives the progress bar and watches for contact at the domain border.

use adhesim::analysis::reference::Jkr;
use adhesim::{Grid, Observer, StepRecord, StepView};
use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::collections::{BTreeMap, BTreeSet};
use std::fs::File;
use std::io::{BufWriter, IsTerminal, Write};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Colours of the contact maps (paper Fig. 16 style).
const STAYING: [u8; 3] = [70, 70, 70];
const ATTACHED: [u8; 3] = [215, 25, 28];
const DETACHED: [u8; 3] = [30, 90, 220];
const FREE: [u8; 3] = [255, 255, 255];

/// Which snapshots to write.
pub struct SnapshotPlan {
    /// Steps that get a PNG and `.npy` fields.
    pub chosen: BTreeSet<usize>,
    /// Every k-th step also (0 = off).
    pub every: usize,
    /// Jump steps with at least this many attached + detached elements get a PNG.
    pub jump_elements: usize,
    /// At most this many jump PNGs.
    pub max_jump_snapshots: usize,
    /// Last approach step (the deepest indentation).
    pub max_depth_step: usize,
}

/// Writes the outputs of each step.
pub struct RunObserver {
    csv: csv::Writer<BufWriter<File>>,
    grid: Grid,
    jkr: Option<Jkr>,
    snapshots: PathBuf,
    plan: SnapshotPlan,
    jump_snapshots: usize,
    progress: ProgressBar,
    /// Every step's record, for the plots and the summary.
    pub records: Vec<StepRecord>,
    largest: (usize, usize, Vec<bool>),
    last_in_contact: Option<(usize, Vec<bool>, Vec<bool>)>,
    /// Warnings for the summary (also printed to stderr).
    pub warnings: Vec<String>,
    border_warned: bool,
    /// The first I/O error; the protocol is stopped when it happens.
    pub error: Option<anyhow::Error>,
    /// Snapshot files written, relative to the output folder.
    pub snapshot_files: Vec<String>,
    /// Steps whose contact sets are kept in `captured` (see [`RunObserver::capture`]).
    capture_steps: BTreeSet<usize>,
    /// (step, contact, previous contact) of the captured steps, in step order.
    pub captured: Vec<(usize, Vec<bool>, Vec<bool>)>,
    /// Solver wall time per phase (time between steps, without this observer's output).
    pub phase_seconds: BTreeMap<&'static str, f64>,
    /// Steps per phase.
    pub phase_steps: BTreeMap<&'static str, usize>,
    /// Wall time spent writing curve.csv rows and snapshots.
    pub output_seconds: f64,
    last_tick: Instant,
}

impl RunObserver {
    /// Creates `curve.csv` (with its header) and `snapshots/` in `out`.
    pub fn new(
        out: &Path,
        grid: Grid,
        jkr: Option<Jkr>,
        plan: SnapshotPlan,
        expected_steps: usize,
        quiet: bool,
    ) -> Result<Self> {
        let snapshots = out.join("snapshots");
        std::fs::create_dir_all(&snapshots).with_context(|| format!("cannot create {}", snapshots.display()))?;
        let path = out.join("curve.csv");
        let file = File::create(&path).with_context(|| format!("cannot create {}", path.display()))?;
        let mut csv = csv::Writer::from_writer(BufWriter::new(file));
        let mut header: Vec<&str> = vec![
            "step",
            "phase",
            "d",
            "x",
            "force_normal",
            "force_tangential",
            "area",
            "radius",
            "n_contact",
            "dissipated_energy",
            "force_tangential_before_change",
            "half_width",
        ];
        if jkr.is_some() {
            header.extend(["d_norm", "force_norm", "radius_norm"]);
        }
        header.extend([
            "attached",
            "detached",
            "jumped",
            "step_dissipated_energy",
            "solves",
            "cg_iterations",
            "fft_pairs",
            "touches_border",
        ]);
        csv.write_record(&header)?;
        csv.flush()?;
        let progress = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::with_draw_target(Some(expected_steps as u64), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} steps {msg}")
                    .expect("valid template"),
            );
            bar
        };
        Ok(Self {
            csv,
            grid,
            jkr,
            snapshots,
            plan,
            jump_snapshots: 0,
            progress,
            records: Vec::new(),
            largest: (0, 0, Vec::new()),
            last_in_contact: None,
            warnings: Vec::new(),
            border_warned: false,
            error: None,
            snapshot_files: Vec::new(),
            capture_steps: BTreeSet::new(),
            captured: Vec::new(),
            phase_seconds: BTreeMap::new(),
            phase_steps: BTreeMap::new(),
            output_seconds: 0.0,
            last_tick: Instant::now(),
        })
    }

    /// Keeps the contact sets of these steps in memory (for composite pictures such as
    /// the consecutive sliding snapshots of the paper's Fig. 9).
    pub fn capture(&mut self, steps: impl IntoIterator<Item = usize>) {
        self.capture_steps.extend(steps);
    }

    fn write_row(&mut self, r: &StepRecord) -> Result<()> {
        let mut row: Vec<String> = vec![
            r.step.to_string(),
            r.phase.map(|p| p.name()).unwrap_or("").to_string(),
            r.depth.to_string(),
            r.offset.to_string(),
            r.force_normal.to_string(),
            r.force_tangential.to_string(),
            r.area.to_string(),
            r.radius.to_string(),
            r.contact_elements.to_string(),
            r.cumulative_dissipated_energy.to_string(),
            r.force_tangential_before_change.to_string(),
            r.half_width.to_string(),
        ];
        if let Some(jkr) = &self.jkr {
            row.push((r.depth / jkr.critical_depth().abs()).to_string());
            row.push((r.force_normal / jkr.critical_force().abs()).to_string());
            row.push((r.radius / jkr.critical_radius()).to_string());
        }
        row.extend([
            r.report.attached.to_string(),
            r.report.detached.to_string(),
            u8::from(r.jumped).to_string(),
            r.report.dissipated_energy.to_string(),
            r.report.solves.to_string(),
            r.report.cg_iterations.to_string(),
            r.report.operator_applications.to_string(),
            u8::from(r.touches_border).to_string(),
        ]);
        self.csv.write_record(&row)?;
        self.csv.flush()?;
        Ok(())
    }

    fn snapshot(&mut self, name: &str, contact: &[bool], previous: &[bool]) -> Result<()> {
        let path = self.snapshots.join(format!("{name}.png"));
        write_contact_map(&path, self.grid.n(), contact, previous)?;
        self.snapshot_files.push(format!("snapshots/{name}.png"));
        Ok(())
    }

    fn handle(&mut self, view: &StepView<'_>) -> Result<()> {
        let r = view.record;
        self.write_row(r)?;
        let step = r.step;
        let n = self.grid.n();
        let changed = r.report.attached + r.report.detached;
        let chosen = self.plan.chosen.contains(&step) || step.checked_rem(self.plan.every) == Some(0);
        if chosen {
            let name = format!("step_{step:06}");
            self.snapshot(&name, &view.state.contact, view.previous_contact)?;
            write_field(
                &self.snapshots.join(format!("{name}_pressure.npy")),
                n,
                &view.state.pressure,
            )?;
            write_field(
                &self.snapshots.join(format!("{name}_displacement.npy")),
                n,
                &view.state.displacement,
            )?;
        }
        if r.jumped && changed >= self.plan.jump_elements && self.jump_snapshots < self.plan.max_jump_snapshots {
            self.jump_snapshots += 1;
            self.snapshot(&format!("jump_{step:06}"), &view.state.contact, view.previous_contact)?;
        }
        if step == self.plan.max_depth_step {
            self.snapshot("max_depth", &view.state.contact, view.previous_contact)?;
        }
        if self.capture_steps.contains(&step) {
            self.captured
                .push((step, view.state.contact.clone(), view.previous_contact.to_vec()));
        }
        if r.contact_elements > self.largest.0 {
            self.largest = (r.contact_elements, step, view.state.contact.clone());
        }
        if r.contact_elements > 0 {
            match &mut self.last_in_contact {
                Some((s, contact, previous)) => {
                    *s = step;
                    contact.copy_from_slice(&view.state.contact);
                    previous.copy_from_slice(view.previous_contact);
                }
                None => {
                    self.last_in_contact = Some((step, view.state.contact.clone(), view.previous_contact.to_vec()));
                }
            }
        }
        if r.touches_border && !self.border_warned {
            self.border_warned = true;
            let message = format!(
                "contact reached the domain border at step {step} (d = {:.6e}): the domain is too small, enlarge grid.size",
                r.depth
            );
            self.progress.suspend(|| eprintln!("warning: {message}"));
            self.warnings.push(message);
        }
        if step as u64 >= self.progress.length().unwrap_or(0) {
            self.progress.inc_length(1);
        }
        self.progress.set_position(step as u64 + 1);
        let phase = r.phase.map(|p| p.name()).unwrap_or("");
        match &self.jkr {
            Some(jkr) => self.progress.set_message(format!(
                "{phase} d/|d_JKR| = {:.2}, F/|F_JKR| = {:.3}",
                r.depth / jkr.critical_depth().abs(),
                r.force_normal / jkr.critical_force().abs()
            )),
            None => self
                .progress
                .set_message(format!("{phase} d = {:.3e}, F = {:.3e}", r.depth, r.force_normal)),
        }
        self.records.push(*r);
        Ok(())
    }

    /// Writes the contact maps of the largest contact and of the last configuration before
    /// contact was lost, and closes the CSV and the progress bar.
    pub fn finish(&mut self) -> Result<()> {
        self.progress.finish_and_clear();
        self.csv.flush()?;
        if self.largest.0 > 0 {
            let contact = std::mem::take(&mut self.largest.2);
            // Shown without change colours: the map of the contact itself.
            self.snapshot("largest_contact", &contact, &contact)?;
        }
        if let Some((_, contact, previous)) = self.last_in_contact.take() {
            self.snapshot("pull_off", &contact, &previous)?;
        }
        Ok(())
    }
}

impl Observer for RunObserver {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        let phase = view.record.phase.map_or("unknown", |p| p.name());
        *self.phase_seconds.entry(phase).or_default() += self.last_tick.elapsed().as_secs_f64();
        *self.phase_steps.entry(phase).or_default() += 1;
        let output_start = Instant::now();
        let result = self.handle(&view);
        self.output_seconds += output_start.elapsed().as_secs_f64();
        self.last_tick = Instant::now();
        match result {
            Ok(()) => ControlFlow::Continue(()),
            Err(error) => {
                self.error = Some(error);
                ControlFlow::Break(())
            }
        }
    }
}

/// Pixel scale so that small grids give pictures of about 512 pixels.
fn pixel_scale(n: usize) -> usize {
    (512 / n).clamp(1, 16)
}

/// A PNG contact map: staying contact dark grey, newly attached red, just detached blue,
/// free white; one square of pixels per element, y upwards.
pub fn write_contact_map(path: &Path, n: usize, contact: &[bool], previous: &[bool]) -> Result<()> {
    let scale = pixel_scale(n);
    let side = (n * scale) as u32;
    let mut image = image::RgbImage::new(side, side);
    for (px, py, pixel) in image.enumerate_pixels_mut() {
        let column = px as usize / scale;
        let row = n - 1 - py as usize / scale;
        let k = row * n + column;
        pixel.0 = match (previous[k], contact[k]) {
            (true, true) => STAYING,
            (false, true) => ATTACHED,
            (true, false) => DETACHED,
            (false, false) => FREE,
        };
    }
    image
        .save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}

fn write_field(path: &Path, n: usize, values: &[f64]) -> Result<()> {
    use ndarray_npy::WriteNpyExt;
    let array = ndarray::Array2::from_shape_vec((n, n), values.to_vec())?;
    let file = File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let mut writer = BufWriter::new(file);
    array
        .write_npy(&mut writer)
        .with_context(|| format!("cannot write {}", path.display()))?;
    writer.flush()?;
    Ok(())
}
