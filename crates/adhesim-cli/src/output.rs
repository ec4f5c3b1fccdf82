//! The run's observer: writes `curve.csv` rows as the steps come, contact-map snapshots,
//! drives the progress bar and watches for contact at the domain border.

use adhesim::analysis::reference::Jkr;
use adhesim::{Grid, Observer, StepRecord, StepView};
use adhesim_scenario::output::curve_csv::CurveCsv;
use adhesim_scenario::output::timings::PhaseTimings;
use adhesim_scenario::{SnapshotPlan, ValidScenario};
use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::collections::BTreeSet;
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

/// The progress bar (hidden when quiet or when stderr is not a terminal) with the
/// current depth and force, normalised by the JKR scales where they exist.
struct Progress {
    bar: ProgressBar,
    jkr: Option<Jkr>,
}

impl Progress {
    fn new(expected_steps: usize, quiet: bool, jkr: Option<Jkr>) -> Self {
        let bar = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::with_draw_target(Some(expected_steps as u64), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} steps {msg}")
                    .expect("valid template"),
            );
            bar
        };
        Self { bar, jkr }
    }

    fn step(&self, r: &StepRecord) {
        if r.step as u64 >= self.bar.length().unwrap_or(0) {
            self.bar.inc_length(1);
        }
        self.bar.set_position(r.step as u64 + 1);
        let phase = r.phase.map(|p| p.name()).unwrap_or("");
        match &self.jkr {
            Some(jkr) => self.bar.set_message(format!(
                "{phase} d/|d_JKR| = {:.2}, F/|F_JKR| = {:.3}",
                r.depth / jkr.critical_depth().abs(),
                r.force_normal / jkr.critical_force().abs()
            )),
            None => self
                .bar
                .set_message(format!("{phase} d = {:.3e}, F = {:.3e}", r.depth, r.force_normal)),
        }
    }
}

/// Writes the outputs of each step.
pub struct RunObserver {
    csv: CurveCsv,
    grid: Grid,
    snapshots: PathBuf,
    plan: SnapshotPlan,
    jump_snapshots: usize,
    progress: Progress,
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
    /// Solver and output wall time per phase.
    pub timings: PhaseTimings,
    /// `fields.npz` of the snapshot steps (crate::fields), when set.
    pub fields: Option<adhesim_scenario::output::fields::FieldsRecorder>,
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
        let csv = CurveCsv::create(&out.join("curve.csv"), jkr)?;
        let progress = Progress::new(expected_steps, quiet, jkr);
        Ok(Self {
            csv,
            grid,
            snapshots,
            plan,
            jump_snapshots: 0,
            progress,
            largest: (0, 0, Vec::new()),
            last_in_contact: None,
            warnings: Vec::new(),
            border_warned: false,
            error: None,
            snapshot_files: Vec::new(),
            capture_steps: BTreeSet::new(),
            captured: Vec::new(),
            timings: PhaseTimings::new(),
            fields: None,
        })
    }

    /// Keeps the contact sets of these steps in memory (for composite pictures such as
    /// the consecutive sliding snapshots of the paper's Fig. 9).
    pub fn capture(&mut self, steps: impl IntoIterator<Item = usize>) {
        self.capture_steps.extend(steps);
    }

    fn snapshot(&mut self, name: &str, contact: &[bool], previous: &[bool]) -> Result<()> {
        let path = self.snapshots.join(format!("{name}.png"));
        write_contact_map(&path, &self.grid, contact, previous)?;
        self.snapshot_files.push(format!("snapshots/{name}.png"));
        Ok(())
    }

    fn handle(&mut self, view: &StepView<'_>) -> Result<()> {
        let r = view.record;
        self.csv.write(r)?;
        let step = r.step;
        let n = (self.grid.ny(), self.grid.nx());
        let changed = r.report.attached + r.report.detached;
        if self.plan.is_chosen(step) {
            let name = SnapshotPlan::step_name(step);
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
        if let Some(fields) = &mut self.fields {
            fields.observe(view);
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
            let message = adhesim_scenario::border_warning(step, r.depth);
            self.progress.bar.suspend(|| eprintln!("warning: {message}"));
            self.warnings.push(message);
        }
        self.progress.step(r);
        Ok(())
    }

    /// Writes the contact maps of the largest contact and of the last configuration before
    /// contact was lost, and closes the CSV and the progress bar.
    /// Then `fields.npz` of the snapshot steps of `scenario` (the one run).
    /// After an I/O error (in `error`) the partial `curve.csv` is left as it is.
    pub fn finish(&mut self, scenario: &ValidScenario) -> Result<()> {
        self.progress.bar.finish_and_clear();
        if self.error.is_some() {
            return Ok(());
        }
        self.csv.commit()?;
        if self.largest.0 > 0 {
            let contact = std::mem::take(&mut self.largest.2);
            // Shown without change colours: the map of the contact itself.
            self.snapshot("largest_contact", &contact, &contact)?;
        }
        if let Some((_, contact, previous)) = self.last_in_contact.take() {
            self.snapshot("pull_off", &contact, &previous)?;
        }
        if let (Some(fields), Some(out)) = (&mut self.fields, self.snapshots.parent()) {
            fields.write(scenario, out)?;
        }
        Ok(())
    }
}

impl Observer for RunObserver {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.timings
            .solver_step(view.record.phase.map_or("unknown", |p| p.name()));
        let output_start = Instant::now();
        let result = self.handle(&view);
        self.timings.output_done(output_start);
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
/// free white; one block of pixels per element, y upwards. The blocks are square on
/// square elements and keep the elements' aspect ratio Δy/Δx (to the pixel) otherwise.
pub fn write_contact_map(path: &Path, grid: &Grid, contact: &[bool], previous: &[bool]) -> Result<()> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let scale = pixel_scale(nx.max(ny));
    let scale_y = ((scale as f64 * grid.dy() / grid.dx()).round() as usize).max(1);
    let mut image = image::RgbImage::new((nx * scale) as u32, (ny * scale_y) as u32);
    for (px, py, pixel) in image.enumerate_pixels_mut() {
        let column = px as usize / scale;
        let row = ny - 1 - py as usize / scale_y;
        let k = row * nx + column;
        pixel.0 = match (previous[k], contact[k]) {
            (true, true) => STAYING,
            (false, true) => ATTACHED,
            (true, false) => DETACHED,
            (false, false) => FREE,
        };
    }
    let legend = [(STAYING, "in contact"), (ATTACHED, "attached"), (DETACHED, "detached")];
    let pixels_per_length = scale as f64 / grid.dx();
    let keyed = crate::map_key::with_key(&image, pixels_per_length, crate::map_key::Legend::Categories(&legend))?;
    crate::figure::files::save_image(&keyed, path)
}

/// A field as an .npy array of `shape` = (rows, columns) = (Ny, Nx).
fn write_field(path: &Path, shape: (usize, usize), values: &[f64]) -> Result<()> {
    use ndarray_npy::WriteNpyExt;
    let array = ndarray::Array2::from_shape_vec(shape, values.to_vec())?;
    let file = File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let mut writer = BufWriter::new(file);
    array
        .write_npy(&mut writer)
        .with_context(|| format!("cannot write {}", path.display()))?;
    writer.flush()?;
    Ok(())
}
