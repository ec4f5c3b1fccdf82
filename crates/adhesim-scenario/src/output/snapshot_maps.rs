//! The snapshots of a run folder: at the chosen steps the contact map, the stick/slip map
//! of a shear and the pressure and displacement fields (`snapshots/*.npy`); the maps of
//! the first jumps and of the deepest step; at the end, the maps of the largest contact
//! and of the last configuration before contact was lost.

use super::observer::RunPictures;
use super::observer_state::{Bits, ObserverState};
use super::parts::StepWriter;
use crate::SnapshotPlan;
use adhesim::{Grid, StepView};
use anyhow::{Context, Result};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The snapshot maps and fields of a run (a [`StepWriter`]).
pub struct SnapshotMaps<'a> {
    grid: Grid,
    snapshots: PathBuf,
    plan: SnapshotPlan,
    pictures: Option<&'a dyn RunPictures>,
    jump_snapshots: usize,
    largest: (usize, usize, Vec<bool>),
    last_in_contact: Option<(usize, Vec<bool>, Vec<bool>)>,
    /// Snapshot files written, relative to the output folder.
    pub snapshot_files: Vec<String>,
}

impl<'a> SnapshotMaps<'a> {
    /// Creates `snapshots/` in `out`; the maps are drawn by `pictures` (none without).
    pub fn new(out: &Path, grid: Grid, plan: SnapshotPlan, pictures: Option<&'a dyn RunPictures>) -> Result<Self> {
        let snapshots = out.join("snapshots");
        std::fs::create_dir_all(&snapshots).with_context(|| format!("cannot create {}", snapshots.display()))?;
        Ok(Self {
            grid,
            snapshots,
            plan,
            pictures,
            jump_snapshots: 0,
            largest: (0, 0, Vec::new()),
            last_in_contact: None,
            snapshot_files: Vec::new(),
        })
    }

    /// The run folder.
    pub fn folder(&self) -> Option<&Path> {
        self.snapshots.parent()
    }

    /// The maps of the largest contact and of the last configuration in contact (a run
    /// that succeeded).
    pub fn finish(&mut self) -> Result<()> {
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

    pub(super) fn save(&self, state: &mut ObserverState) {
        let bits = |b: &Vec<bool>| Bits(b.clone());
        state.jump_snapshots = self.jump_snapshots;
        state.largest = (self.largest.0, self.largest.1, bits(&self.largest.2));
        state.last_in_contact = self.last_in_contact.as_ref().map(|(s, c, p)| (*s, bits(c), bits(p)));
        state.snapshot_files = self.snapshot_files.clone();
    }

    pub(super) fn restore(&mut self, state: &mut ObserverState) {
        self.jump_snapshots = state.jump_snapshots;
        let largest = std::mem::replace(&mut state.largest, (0, 0, Bits(Vec::new())));
        self.largest = (largest.0, largest.1, largest.2 .0);
        self.last_in_contact = state.last_in_contact.take().map(|(s, c, p)| (s, c.0, p.0));
        self.snapshot_files = std::mem::take(&mut state.snapshot_files);
    }

    fn snapshot(&mut self, name: &str, contact: &[bool], previous: &[bool]) -> Result<()> {
        let Some(pictures) = self.pictures else {
            return Ok(());
        };
        let path = self.snapshots.join(format!("{name}.png"));
        pictures.contact_map(&path, &self.grid, contact, previous)?;
        self.snapshot_files.push(format!("snapshots/{name}.png"));
        Ok(())
    }

    /// The maps and fields of a chosen step.
    fn chosen_step(&mut self, view: &StepView<'_>) -> Result<()> {
        let name = SnapshotPlan::step_name(view.record.step);
        let n = (self.grid.ny(), self.grid.nx());
        self.snapshot(&name, &view.state.contact, view.previous_contact)?;
        if let (Some(pictures), Some(shear)) = (self.pictures, view.shear) {
            pictures.slip_map(
                &self.snapshots.join(format!("{name}_slip.png")),
                &self.grid,
                &shear.status,
            )?;
            self.snapshot_files.push(format!("snapshots/{name}_slip.png"));
        }
        write_field(
            &self.snapshots.join(format!("{name}_pressure.npy")),
            n,
            &view.state.pressure,
        )?;
        write_field(
            &self.snapshots.join(format!("{name}_displacement.npy")),
            n,
            &view.state.displacement,
        )
    }

    /// Keeps the largest contact and the last configuration in contact.
    fn track(&mut self, view: &StepView<'_>) {
        let (r, step) = (view.record, view.record.step);
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
    }
}

impl StepWriter for SnapshotMaps<'_> {
    fn write_step(&mut self, view: &StepView<'_>) -> Result<()> {
        let (r, step) = (view.record, view.record.step);
        let changed = r.report.attached + r.report.detached;
        if self.plan.is_chosen(step) {
            self.chosen_step(view)?;
        }
        if r.jumped && changed >= self.plan.jump_elements && self.jump_snapshots < self.plan.max_jump_snapshots {
            self.jump_snapshots += 1;
            self.snapshot(&format!("jump_{step:06}"), &view.state.contact, view.previous_contact)?;
        }
        if step == self.plan.max_depth_step {
            self.snapshot("max_depth", &view.state.contact, view.previous_contact)?;
        }
        self.track(view);
        Ok(())
    }
}

/// A field as an .npy array of `shape` = (rows, columns) = (Ny, Nx).
pub(super) fn write_field(path: &Path, shape: (usize, usize), values: &[f64]) -> Result<()> {
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
