//! The layer's kernel tables, kept for the life of the process.
//!
//! A table (`super::layer::PointCorrection`) is a Hankel transform in ρ = r/t: it depends on
//! the layer's Poisson ratio and base and on which kernel it is, not on the grid, the
//! thickness or the modulus. It costs about 6·10⁷ Bessel values, most of a small run on a
//! layer, so a sweep, a study or a Python session that builds many operators on layers of
//! one ν computes each table once. The tables kept are the ones computed, so a run's bits
//! do not depend on what ran before it.

use super::LayerBase;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

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
    let values: Arc<[f64]> = compute().into();
    let mut kept = tables.lock().unwrap_or_else(PoisonError::into_inner);
    if kept.len() >= KEPT {
        kept.clear();
    }
    Arc::clone(kept.entry(key).or_insert(values))
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
