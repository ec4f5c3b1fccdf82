//! The tangential fields of a shear's snapshot steps in `fields.npz` / `fields.nc`
//! (docs/output.md, "fields.npz"): shear traction, accumulated slip and the
//! open/stick/slip state, stacked along the step axis like the normal fields.

use crate::snapshots::FieldSnapshot;
use adhesim_topography::NamedArray;

/// The tangential fields stacked along the step axis, (K, Ny, Nx), row-major. An approach
/// step (no shift yet) has no traction and no slip, and its contact elements stick.
#[derive(Debug, Clone, Default)]
pub struct ShearStacked {
    pub traction_x: Vec<f64>,
    pub traction_y: Vec<f64>,
    pub slip_x: Vec<f64>,
    pub slip_y: Vec<f64>,
    /// 0 open, 1 stick, 2 slip.
    pub state: Vec<i64>,
}

impl ShearStacked {
    /// The fields of `snapshots`.
    pub fn of(snapshots: &[FieldSnapshot]) -> Self {
        let mut stacked = Self::default();
        for snapshot in snapshots {
            match &snapshot.shear {
                Some(fields) => {
                    stacked.traction_x.extend_from_slice(&fields.traction[0]);
                    stacked.traction_y.extend_from_slice(&fields.traction[1]);
                    stacked.slip_x.extend_from_slice(&fields.slip[0]);
                    stacked.slip_y.extend_from_slice(&fields.slip[1]);
                    stacked.state.extend(fields.status.iter().map(|s| i64::from(s.code())));
                }
                None => {
                    let n = snapshot.contact.len();
                    for buffer in [
                        &mut stacked.traction_x,
                        &mut stacked.traction_y,
                        &mut stacked.slip_x,
                        &mut stacked.slip_y,
                    ] {
                        buffer.extend(std::iter::repeat_n(0.0, n));
                    }
                    stacked.state.extend(snapshot.contact.iter().map(|&c| i64::from(c)));
                }
            }
        }
        stacked
    }

    /// The named arrays, each of shape `by_step` (K, Ny, Nx), with their units.
    pub fn arrays<'a>(&'a self, by_step: &'a [usize; 3]) -> Vec<NamedArray<'a>> {
        vec![
            NamedArray::f64("shear_traction_x", by_step, &self.traction_x).with_unit("pressure"),
            NamedArray::f64("shear_traction_y", by_step, &self.traction_y).with_unit("pressure"),
            NamedArray::f64("slip_x", by_step, &self.slip_x).with_unit("length"),
            NamedArray::f64("slip_y", by_step, &self.slip_y).with_unit("length"),
            NamedArray::i64("slip_state", by_step, &self.state),
        ]
    }
}
