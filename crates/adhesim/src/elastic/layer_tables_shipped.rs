//! The layer tables the library ships ([`super::layer_tables::SHIPPED`]) against the
//! tables its code computes: a run on an incompressible layer reads the shipped values, so
//! they must be the computed ones, bit for bit.

use super::bessel::Bessel;
use super::layer::{normal_table_integrand, PointCorrection};
use super::layer_coupling::coupling_table_integrand;
use super::layer_shear::{deviatoric_table_integrand, isotropic_table_integrand};
use super::layer_tables::{TableKey, SHIPPED, TABLE_ROWS};
use super::LayerBase;
use std::path::PathBuf;

/// Every `STRIDE`-th row is recomputed: a change to an integrand, the quadrature or the
/// Bessel functions moves every row, so a sample of rows tells, at an eighth of the cost.
const STRIDE: usize = 8;

/// `key`'s rows `rows` (every `stride`-th), computed as a run computes them.
fn computed(key: TableKey, stride: usize) -> Vec<f64> {
    let rows = 0..TABLE_ROWS;
    match key {
        TableKey::Normal {
            poisson_ratio_bits,
            base,
        } => PointCorrection::compute_rows(
            normal_table_integrand(f64::from_bits(poisson_ratio_bits), base),
            Bessel::J0,
            rows,
            stride,
        ),
        TableKey::ShearIsotropic { poisson_ratio_bits } => PointCorrection::compute_rows(
            isotropic_table_integrand(f64::from_bits(poisson_ratio_bits)),
            Bessel::J0,
            rows,
            stride,
        ),
        TableKey::ShearDeviatoric { poisson_ratio_bits } => PointCorrection::compute_rows(
            deviatoric_table_integrand(f64::from_bits(poisson_ratio_bits)),
            Bessel::J2,
            rows,
            stride,
        ),
        TableKey::Coupling { poisson_ratio_bits } => PointCorrection::compute_rows(
            coupling_table_integrand(f64::from_bits(poisson_ratio_bits)),
            Bessel::J1OverX,
            rows,
            stride,
        ),
    }
}

/// The file of `key`'s shipped table (`include_bytes!` in `layer_tables.rs`).
fn file_of(key: TableKey) -> PathBuf {
    let name = match key {
        TableKey::Normal {
            base: LayerBase::Bonded,
            ..
        } => "normal_bonded_half",
        TableKey::Normal {
            base: LayerBase::Frictionless,
            ..
        } => "normal_frictionless_half",
        TableKey::ShearIsotropic { .. } => "shear_isotropic_half",
        TableKey::ShearDeviatoric { .. } => "shear_deviatoric_half",
        TableKey::Coupling { .. } => "coupling_half",
    };
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("src/elastic/layer_tables/{name}.f64"))
}

/// Every shipped table holds [`TABLE_ROWS`] values, and every 8th row is the computed
/// one, bit for bit. With `ADHESIM_WRITE_LAYER_TABLES=1` the tables are computed whole and
/// written instead (then build again, and run this test without it).
#[test]
fn shipped_tables_are_the_computed_ones() {
    let write = std::env::var_os("ADHESIM_WRITE_LAYER_TABLES").is_some();
    for (key, bytes) in SHIPPED {
        assert_eq!(
            f64::from_bits(key_bits(key)),
            0.5,
            "{key:?}: the shipped tables are those of ν = 1/2"
        );
        if write {
            let values: Vec<u8> = computed(key, 1).iter().flat_map(|value| value.to_le_bytes()).collect();
            std::fs::write(file_of(key), values).unwrap();
            continue;
        }
        assert_eq!(
            bytes.len(),
            8 * TABLE_ROWS,
            "{key:?}: {} holds {} bytes, not {} rows of 8: write it anew (ADHESIM_WRITE_LAYER_TABLES=1)",
            file_of(key).display(),
            bytes.len(),
            TABLE_ROWS
        );
        let shipped: Vec<f64> = bytes
            .chunks_exact(8)
            .step_by(STRIDE)
            .map(|value| f64::from_le_bytes(value.try_into().unwrap()))
            .collect();
        let computed = computed(key, STRIDE);
        assert_eq!(shipped.len(), computed.len(), "{key:?}");
        for (row, (shipped, computed)) in shipped.iter().zip(&computed).enumerate() {
            assert_eq!(
                shipped.to_bits(),
                computed.to_bits(),
                "{key:?}, row {}: shipped {shipped:e}, computed {computed:e}: write the tables anew (ADHESIM_WRITE_LAYER_TABLES=1)",
                row * STRIDE
            );
        }
    }
}

/// The Poisson ratio's bits of `key`.
fn key_bits(key: TableKey) -> u64 {
    match key {
        TableKey::Normal { poisson_ratio_bits, .. }
        | TableKey::ShearIsotropic { poisson_ratio_bits }
        | TableKey::ShearDeviatoric { poisson_ratio_bits }
        | TableKey::Coupling { poisson_ratio_bits } => poisson_ratio_bits,
    }
}
