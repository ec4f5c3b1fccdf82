//! `fields.npz` (and, with `adhesim run --fields netcdf`, `fields.nc`): the contact fields
//! of a run's snapshot steps in one file per run, for numpy and xarray users. The contract
//! (names, shapes, dtypes, units, signs) is in `docs/output.md`, "fields.npz".
//!
//! The observer hands over the steps that get a snapshot ([`FieldsRecorder::take`]) and
//! shows every step ([`FieldsRecorder::observe`]) so that the last step in contact
//! (`pull_off`) and the largest contact are kept too; [`FieldsRecorder::write`] writes
//! them all at the end of the run with `adhesim_topography::write_npz` (DEFLATE), through a
//! `.partial` file renamed when complete.

use adhesim::{Grid, StepView, TranslatingContact};
use adhesim_topography::{write_netcdf, write_npz, NamedArray, NetcdfGrid};
use anyhow::{Context, Result};
use std::path::Path;

/// The indenter profile z(x, y) whose gap the fields report.
pub enum FieldProfile {
    /// Indentation: the heights on the grid, fixed.
    Fixed(Vec<f64>),
    /// Roll / slide / translate: the profile at the step's lateral offset X.
    Moving(TranslatingContact),
}

/// One step's fields.
#[derive(Clone)]
struct Snapshot {
    step: usize,
    depth: f64,
    offset: f64,
    pressure: Vec<f64>,
    displacement: Vec<f64>,
    contact: Vec<bool>,
}

impl Snapshot {
    fn of(view: &StepView<'_>) -> Self {
        Self {
            step: view.record.step,
            depth: view.record.depth,
            offset: view.record.offset,
            pressure: view.state.pressure.clone(),
            displacement: view.state.displacement.clone(),
            contact: view.state.contact.clone(),
        }
    }

    fn copy_from(&mut self, view: &StepView<'_>) {
        self.step = view.record.step;
        self.depth = view.record.depth;
        self.offset = view.record.offset;
        self.pressure.copy_from_slice(&view.state.pressure);
        self.displacement.copy_from_slice(&view.state.displacement);
        self.contact.copy_from_slice(&view.state.contact);
    }
}

/// Collects the fields of the snapshot steps of a run.
pub struct FieldsRecorder {
    grid: Grid,
    profile: FieldProfile,
    netcdf: bool,
    taken: Vec<Snapshot>,
    last_in_contact: Option<Snapshot>,
    largest: Option<(usize, Snapshot)>,
}

impl FieldsRecorder {
    /// A recorder for `grid`; `netcdf` also writes `fields.nc`.
    pub fn new(grid: Grid, profile: FieldProfile, netcdf: bool) -> Self {
        Self {
            grid,
            profile,
            netcdf,
            taken: Vec::new(),
            last_in_contact: None,
            largest: None,
        }
    }

    /// Keeps the fields of this step (a snapshot step); a step taken twice is kept once.
    pub fn take(&mut self, view: &StepView<'_>) {
        if self.taken.last().is_none_or(|s| s.step != view.record.step) {
            self.taken.push(Snapshot::of(view));
        }
    }

    /// Sees every step: keeps the last one in contact and the one of the largest contact.
    pub fn observe(&mut self, view: &StepView<'_>) {
        let elements = view.record.contact_elements;
        if elements == 0 {
            return;
        }
        match &mut self.last_in_contact {
            Some(snapshot) => snapshot.copy_from(view),
            None => self.last_in_contact = Some(Snapshot::of(view)),
        }
        match &mut self.largest {
            Some((largest, snapshot)) if elements > *largest => {
                *largest = elements;
                snapshot.copy_from(view);
            }
            Some(_) => {}
            None => self.largest = Some((elements, Snapshot::of(view))),
        }
    }

    /// Writes `fields.npz` (and `fields.nc`) into `out`; returns the file names written.
    pub fn write(&mut self, out: &Path) -> Result<Vec<String>> {
        let mut snapshots = std::mem::take(&mut self.taken);
        snapshots.extend(self.last_in_contact.take());
        snapshots.extend(self.largest.take().map(|(_, s)| s));
        snapshots.sort_by_key(|s| s.step);
        snapshots.dedup_by_key(|s| s.step);
        let n = self.grid.n();
        let centres: Vec<f64> = (0..n).map(|i| self.grid.centre(i).0).collect();
        let (heights, surface) = finite_or_zero(&self.profile_at(0.0));
        let mut gaps = Vec::with_capacity(snapshots.len());
        for s in &snapshots {
            let profile = self.profile_at(s.offset);
            let gap: Vec<f64> = profile
                .iter()
                .zip(&s.displacement)
                .map(|(z, u)| if z.is_finite() { u + z - s.depth } else { 0.0 })
                .collect();
            gaps.push(gap);
        }
        let steps: Vec<f64> = snapshots.iter().map(|s| s.step as f64).collect();
        let depths: Vec<f64> = snapshots.iter().map(|s| s.depth).collect();
        let offsets: Vec<f64> = snapshots.iter().map(|s| s.offset).collect();
        let names: Vec<[String; 4]> = snapshots
            .iter()
            .map(|s| ["pressure", "displacement", "gap", "contact"].map(|f| format!("{f}_{:06}", s.step)))
            .collect();
        let field = [n, n];
        let count = [snapshots.len()];
        let axis = [n];
        let mut arrays = vec![
            NamedArray::f64("heights", &field, &heights).with_unit("length"),
            NamedArray::bool("surface", &field, &surface),
            NamedArray::f64("steps", &count, &steps),
            NamedArray::f64("depths", &count, &depths).with_unit("length"),
            NamedArray::f64("offsets", &count, &offsets).with_unit("length"),
        ];
        for ((s, gap), names) in snapshots.iter().zip(&gaps).zip(&names) {
            arrays.extend([
                NamedArray::f64(&names[0], &field, &s.pressure).with_unit("pressure"),
                NamedArray::f64(&names[1], &field, &s.displacement).with_unit("length"),
                NamedArray::f64(&names[2], &field, gap).with_unit("length"),
                NamedArray::bool(&names[3], &field, &s.contact),
            ]);
        }
        let mut written = Vec::new();
        let mut npz_arrays = vec![
            NamedArray::f64("x", &axis, &centres).with_unit("length"),
            NamedArray::f64("y", &axis, &centres).with_unit("length"),
        ];
        npz_arrays.extend(arrays.iter().copied());
        write_renamed(&out.join("fields.npz"), |path| Ok(write_npz(path, &npz_arrays)?))?;
        written.push("fields.npz".to_string());
        if self.netcdf {
            let spacing = self.grid.element_size();
            let grid = NetcdfGrid {
                nx: n,
                ny: n,
                dx: spacing,
                dy: spacing,
            };
            let origin = format!("{:e}", centres[0]);
            let attributes = [
                ("title", "adhesim contact fields"),
                (
                    "coordinates",
                    "x, y start at 0; the element centre is x + x_origin, y + y_origin",
                ),
                ("x_origin", origin.as_str()),
                ("y_origin", origin.as_str()),
            ];
            write_renamed(&out.join("fields.nc"), |path| {
                Ok(write_netcdf(path, &grid, &arrays, &attributes)?)
            })?;
            written.push("fields.nc".to_string());
        }
        Ok(written)
    }

    /// The profile z on the grid with the axis at X = `offset`.
    fn profile_at(&self, offset: f64) -> Vec<f64> {
        match &self.profile {
            FieldProfile::Fixed(heights) => heights.clone(),
            FieldProfile::Moving(contact) => {
                let mut heights = vec![0.0; self.grid.len()];
                contact.fill_heights(&self.grid, offset, &mut heights);
                heights
            }
        }
    }
}

/// Heights with 0 where the indenter has no surface (+∞ outside a punch or a measured
/// map), and the mask of where it has one.
fn finite_or_zero(heights: &[f64]) -> (Vec<f64>, Vec<bool>) {
    let surface: Vec<bool> = heights.iter().map(|z| z.is_finite()).collect();
    let values = heights.iter().map(|&z| if z.is_finite() { z } else { 0.0 }).collect();
    (values, surface)
}

/// Writes through `PATH.partial`, renamed to `PATH` once complete.
fn write_renamed(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let mut partial = path.as_os_str().to_owned();
    partial.push(".partial");
    let partial = std::path::PathBuf::from(partial);
    write(&partial).with_context(|| format!("cannot write {}", path.display()))?;
    std::fs::rename(&partial, path)
        .with_context(|| format!("cannot rename {} to {}", partial.display(), path.display()))
}
