//! `fields.npz` (and, with `adhesim run --fields netcdf`, `fields.nc`): the contact fields
//! of a run's snapshot steps in one file per run, for numpy and xarray users. The contract
//! (names, shapes, dtypes, units, signs) is in `docs/output.md`, "fields.npz".
//!
//! Which steps and which arrays are the scenario crate's ([`SnapshotRecorder`],
//! [`SnapshotFields`]), shared with the Python package's `adhesim.run(out=...)`; this file
//! writes them at the end of the run with `adhesim_topography::write_npz` (DEFLATE),
//! through a `.partial` file renamed when complete.

use crate::{SnapshotFields, SnapshotRecorder, ValidScenario};
use adhesim::StepView;
use adhesim_topography::{write_netcdf, write_npz, NetcdfGrid};
use anyhow::{Context, Result};
use std::path::Path;

/// Collects the fields of the snapshot steps of a run.
pub struct FieldsRecorder {
    recorder: SnapshotRecorder,
    netcdf: bool,
}

impl FieldsRecorder {
    /// A recorder following `recorder`'s plan; `netcdf` also writes `fields.nc`.
    pub fn new(recorder: SnapshotRecorder, netcdf: bool) -> Self {
        Self { recorder, netcdf }
    }

    /// Sees every step: keeps the plan's steps, the last in contact and the largest contact.
    pub fn observe(&mut self, view: &StepView<'_>) {
        self.recorder.observe(view);
    }

    /// Writes `fields.npz` (and `fields.nc`) into `out`; returns the fields written.
    pub fn write(&mut self, scenario: &ValidScenario, out: &Path) -> Result<SnapshotFields> {
        let fields = SnapshotFields::new(scenario, self.recorder.take_snapshots());
        let shapes = fields.shapes();
        write_renamed(&out.join("fields.npz"), |path| {
            Ok(write_npz(path, &fields.npz_arrays(&shapes))?)
        })?;
        if self.netcdf {
            let (nx, ny) = fields.counts();
            let grid = NetcdfGrid {
                nx,
                ny,
                dx: scenario.grid.dx(),
                dy: scenario.grid.dy(),
            };
            let (x_origin, y_origin) = (format!("{:e}", fields.x()[0]), format!("{:e}", fields.y()[0]));
            let attributes = [
                ("title", "adhesim contact fields"),
                (
                    "coordinates",
                    "x, y start at 0; the element centre is x + x_origin, y + y_origin",
                ),
                ("x_origin", x_origin.as_str()),
                ("y_origin", y_origin.as_str()),
            ];
            let arrays = fields.field_arrays(&shapes.field, &shapes.count);
            write_renamed(&out.join("fields.nc"), |path| {
                Ok(write_netcdf(path, &grid, &arrays, &attributes)?)
            })?;
        }
        Ok(fields)
    }
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
