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
use adhesim_topography::{write_netcdf_variables, write_npz, NamedArray, NcVariable};
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

    /// The recorder (its state goes into a checkpoint).
    pub(crate) fn recorder(&self) -> &SnapshotRecorder {
        &self.recorder
    }

    /// Continues with the recorder of a checkpoint.
    pub(crate) fn restore(&mut self, recorder: SnapshotRecorder) {
        self.recorder = recorder;
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
            write_renamed(&out.join("fields.nc"), |path| Ok(write_fields_nc(path, &fields)?))?;
        }
        Ok(fields)
    }
}

/// The version of the `fields.npz` / `fields.nc` layout (docs/output.md, "fields.npz"):
/// 2 added the `step` dimension, centred coordinates and CF attributes.
pub const FIELDS_CONTRACT: &str = "2";

/// Writes `fields.nc` (docs/output.md): dimensions `step` (K), `y` (Ny), `x` (Nx); the
/// coordinates `step` (int), `x`, `y` (element centres) and the auxiliary coordinates
/// `depth(step)`, `offset(step)`; `heights`, `surface` on (y, x); `pressure`,
/// `displacement`, `gap`, `contact` on (step, y, x); CF-1.8 attributes.
fn write_fields_nc(path: &Path, fields: &SnapshotFields) -> Result<(), adhesim_topography::TopographyError> {
    let (nx, ny) = fields.counts();
    let k = fields.snapshots().len();
    let (x_shape, y_shape, k_shape, field, stack) = ([nx], [ny], [k], [ny, nx], [k, ny, nx]);
    let (depths, offsets) = fields.depths_offsets();
    let stacked = fields.stacked();
    let text = |pairs: &[(&'static str, &str)]| -> Vec<(&'static str, String)> {
        pairs.iter().map(|(k, v)| (*k, v.to_string())).collect()
    };
    let field_attrs = |long_name: &str| text(&[("long_name", long_name), ("coordinates", "depth offset")]);
    let mut variables = vec![
        var(
            NamedArray::i64("step", &k_shape, fields.steps()),
            &["step"],
            text(&[("long_name", "step number (curve.csv's step)"), ("axis", "T")]),
        ),
        var(
            NamedArray::f64("y", &y_shape, fields.y()).with_unit("length"),
            &["y"],
            text(&[
                ("long_name", "element centre y relative to the indenter axis"),
                ("axis", "Y"),
            ]),
        ),
        var(
            NamedArray::f64("x", &x_shape, fields.x()).with_unit("length"),
            &["x"],
            text(&[
                ("long_name", "element centre x relative to the indenter axis"),
                ("axis", "X"),
            ]),
        ),
        var(
            NamedArray::f64("depth", &k_shape, depths).with_unit("length"),
            &["step"],
            text(&[("long_name", "indentation depth d (> 0 into the body)")]),
        ),
        var(
            NamedArray::f64("offset", &k_shape, offsets).with_unit("length"),
            &["step"],
            text(&[("long_name", "lateral position X of the indenter axis")]),
        ),
        var(
            NamedArray::f64("heights", &field, fields.heights()).with_unit("length"),
            &["y", "x"],
            text(&[("long_name", "indenter profile z at X = 0 (0 where surface is 0)")]),
        ),
        var(
            NamedArray::bool("surface", &field, fields.surface()),
            &["y", "x"],
            text(&[("long_name", "1 where the indenter has a surface, 0 where z is infinite")]),
        ),
        var(
            NamedArray::f64("pressure", &stack, &stacked.pressure).with_unit("pressure"),
            &["step", "y", "x"],
            field_attrs("pressure (> 0 compressive, < 0 adhesive tension)"),
        ),
        var(
            NamedArray::f64("displacement", &stack, &stacked.displacement).with_unit("length"),
            &["step", "y", "x"],
            field_attrs("normal surface displacement u (> 0 into the body)"),
        ),
        var(
            NamedArray::f64("gap", &stack, &stacked.gap).with_unit("length"),
            &["step", "y", "x"],
            field_attrs("gap g = u + z - d (0 in contact)"),
        ),
        var(
            NamedArray::bool("contact", &stack, &stacked.contact),
            &["step", "y", "x"],
            field_attrs("contact set (1 in contact, 0 outside)"),
        ),
    ];
    if let Some(shear) = fields.shear() {
        let meanings = [
            "shear traction q_x on the body",
            "shear traction q_y on the body",
            "accumulated slip s_x (the sum of slip increments)",
            "accumulated slip s_y",
            "0 open, 1 stick, 2 slip",
        ];
        for (array, meaning) in shear.arrays(&stack).into_iter().zip(meanings) {
            variables.push(var(array, &["step", "y", "x"], field_attrs(meaning)));
        }
    }
    let revision = adhesim::RESULTS_REVISION.to_string();
    let globals = [
        ("Conventions", "CF-1.8"),
        ("title", "adhesim contact fields"),
        ("source", "adhesim"),
        ("results_revision", revision.as_str()),
        ("fields_contract", FIELDS_CONTRACT),
        (
            "comment",
            "units are the scenario's: length and pressure (= modulus) as given in scenario.toml",
        ),
    ];
    write_netcdf_variables(path, &[("step", k), ("y", ny), ("x", nx)], &variables, &globals)
}

fn var<'a>(array: NamedArray<'a>, dims: &[&'a str], attributes: Vec<(&'a str, String)>) -> NcVariable<'a> {
    NcVariable {
        array,
        dims: dims.to_vec(),
        attributes,
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
