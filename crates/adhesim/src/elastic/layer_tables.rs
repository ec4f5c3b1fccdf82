//! The layer's kernel tables, kept for the life of the process.
//!
//! A table (`super::layer::PointCorrection`) is a Hankel transform in ρ = r/t: it depends on
//! the layer's Poisson ratio and base and on which kernel it is, not on the grid, the
//! thickness or the modulus. It costs about 6·10⁷ Bessel values, most of a small run on a
//! layer, so a sweep, a study or a Python session that builds many operators on layers of
//! one ν computes each table once. The tables kept are the ones computed, so a run's bits
//! do not depend on what ran before it.
//!
//! The tables of an incompressible layer (ν = 1/2, the rubber of the paper's experiments)
//! ship with the library ([`SHIPPED`], little-endian f64 files beside this one): a run on
//! such a layer reads them instead of computing them, which is most of a small run's time
//! there and the same bits. A test in the default suite recomputes every 8th row of each
//! and asks for the same bits; `ADHESIM_WRITE_LAYER_TABLES=1 cargo test --release -p adhesim
//! --lib shipped_tables` writes them anew after a change to a table's definition.

use super::LayerBase;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

/// ρ = r/t beyond which the layer's point kernel is below e^{−0.739·60} ≈ 2e-20 of its
/// scale: its nearest pole is at kt = 0.739i (bonded, ν = 1/2; further out for the others).
pub(super) const TABLE_RANGE: f64 = 60.0;
/// Table step in ρ: cubic interpolation error ≈ 0.02·h⁴·max|d''''| ≈ 1e-8 of d.
pub(super) const TABLE_STEP: f64 = 1.0 / 128.0;
/// Rows of a table: ρ = jh for 0 ≤ j < `TABLE_ROWS`, up to [`TABLE_RANGE`].
pub(super) const TABLE_ROWS: usize = 7681;
const _: () = assert!(TABLE_ROWS as f64 == TABLE_RANGE / TABLE_STEP + 1.0);

/// Which table, with every parameter its values depend on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum TableKey {
    /// d(ρ) of the normal kernel (J₀), by Poisson ratio (its bits) and base.
    Normal { poisson_ratio_bits: u64, base: LayerBase },
    /// d₀(ρ) of the tangential kernel (J₀) of a bonded layer.
    ShearIsotropic { poisson_ratio_bits: u64 },
    /// d₂(ρ) of the tangential kernel (J₂) of a bonded layer.
    ShearDeviatoric { poisson_ratio_bits: u64 },
    /// e(ρ) of the normal–tangential coupling (J₁(x)/x) of a bonded layer.
    Coupling { poisson_ratio_bits: u64 },
}

/// Tables kept at most (about 61 kB each); past it the store starts again empty.
const KEPT: usize = 64;

/// The table of `key`: the one kept, or `compute`'s, then kept.
pub(super) fn table(key: TableKey, compute: impl FnOnce() -> Vec<f64>) -> Arc<[f64]> {
    static TABLES: OnceLock<Mutex<HashMap<TableKey, Arc<[f64]>>>> = OnceLock::new();
    let tables = TABLES.get_or_init(Default::default);
    // A panic elsewhere while the lock was held leaves a map of finished tables: still good.
    if let Some(kept) = tables.lock().unwrap_or_else(PoisonError::into_inner).get(&key) {
        return Arc::clone(kept);
    }
    // Computed outside the lock: two runs asking at once compute the same values.
    let values: Arc<[f64]> = shipped(key).unwrap_or_else(compute).into();
    let mut kept = tables.lock().unwrap_or_else(PoisonError::into_inner);
    if kept.len() >= KEPT {
        kept.clear();
    }
    Arc::clone(kept.entry(key).or_insert(values))
}

/// ν = 1/2 (its bits).
const HALF: u64 = 0.5f64.to_bits();

/// A shipped table: its key, its file's name in `layer_tables/` (without `.f64`) and the
/// file's bytes.
pub(super) type ShippedTable = (TableKey, &'static str, &'static [u8]);

/// The entry of the shipped file `layer_tables/<name>.f64`.
macro_rules! shipped_table {
    ($key:expr, $name:literal) => {
        ($key, $name, include_bytes!(concat!("layer_tables/", $name, ".f64")))
    };
}

/// The tables shipped with the library: their values at ρ = jh for every row j
/// ([`TABLE_ROWS`] of them), as little-endian f64.
pub(super) const SHIPPED: [ShippedTable; 5] = [
    shipped_table!(
        TableKey::Normal {
            poisson_ratio_bits: HALF,
            base: LayerBase::Bonded,
        },
        "normal_bonded_half"
    ),
    shipped_table!(
        TableKey::Normal {
            poisson_ratio_bits: HALF,
            base: LayerBase::Frictionless,
        },
        "normal_frictionless_half"
    ),
    shipped_table!(
        TableKey::ShearIsotropic {
            poisson_ratio_bits: HALF
        },
        "shear_isotropic_half"
    ),
    shipped_table!(
        TableKey::ShearDeviatoric {
            poisson_ratio_bits: HALF
        },
        "shear_deviatoric_half"
    ),
    shipped_table!(
        TableKey::Coupling {
            poisson_ratio_bits: HALF
        },
        "coupling_half"
    ),
];

/// The shipped values of `key`'s table, if the library ships it.
pub(super) fn shipped(key: TableKey) -> Option<Vec<f64>> {
    let (_, _, bytes) = SHIPPED.iter().find(|(shipped, _, _)| *shipped == key)?;
    // A file of another length (one being written anew) is not used: the table is computed.
    if bytes.len() != 8 * TABLE_ROWS {
        return None;
    }
    let values = bytes
        .chunks_exact(8)
        .map(|value| f64::from_le_bytes(value.try_into().expect("eight bytes")))
        .collect();
    Some(values)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_is_computed_once_per_key() {
        let key = |bits| TableKey::Normal {
            poisson_ratio_bits: bits,
            base: LayerBase::Bonded,
        };
        // Keys no layer uses (NaN bits), so that other tests' tables do not interfere.
        let (first, second) = (key(f64::NAN.to_bits() ^ 1), key(f64::NAN.to_bits() ^ 2));
        let mut calls = 0;
        let a = table(first, || {
            calls += 1;
            vec![1.0, 2.0]
        });
        let b = table(first, || {
            calls += 1;
            vec![9.0]
        });
        let c = table(second, || vec![3.0]);
        assert_eq!(
            (calls, &a[..], &b[..], &c[..]),
            (1, &[1.0, 2.0][..], &[1.0, 2.0][..], &[3.0][..])
        );
    }
}
