//! The layer tables the library ships ([`super::layer_tables::SHIPPED`]) against the
//! tables its code computes: a run on an incompressible layer reads the shipped values, so
//! they must be the computed ones, bit for bit.

use super::bessel::Bessel;
use super::layer::{normal_table_integrand, PointCorrection};
use super::layer_coupling::coupling_table_integrand;
use super::layer_shear::{deviatoric_table_integrand, isotropic_table_integrand};
use super::layer_tables::{shipped, TableKey, SHIPPED, TABLE_ROWS};

/// Every `STRIDE`-th row is recomputed: a change to an integrand, the quadrature or the
/// Bessel functions moves every row, so a sample of rows tells, at an eighth of the cost.
const STRIDE: usize = 8;

/// Every `stride`-th row of `key`'s table, computed as a run computes it.
fn computed(key: TableKey, stride: usize) -> Vec<f64> {
    let (integrand, bessel): (Box<dyn Fn(f64) -> f64>, Bessel) = match key {
        TableKey::Normal {
            poisson_ratio_bits,
            base,
        } => (
            Box::new(normal_table_integrand(f64::from_bits(poisson_ratio_bits), base)),
            Bessel::J0,
        ),
        TableKey::ShearIsotropic { poisson_ratio_bits } => (
            Box::new(isotropic_table_integrand(f64::from_bits(poisson_ratio_bits))),
            Bessel::J0,
        ),
        TableKey::ShearDeviatoric { poisson_ratio_bits } => (
            Box::new(deviatoric_table_integrand(f64::from_bits(poisson_ratio_bits))),
            Bessel::J2,
        ),
        TableKey::Coupling { poisson_ratio_bits } => (
            Box::new(coupling_table_integrand(f64::from_bits(poisson_ratio_bits))),
            Bessel::J1OverX,
        ),
    };
    PointCorrection::compute_rows(integrand, bessel, stride)
}

/// Every shipped table holds [`TABLE_ROWS`] values, and every 8th row is the computed
/// one, bit for bit. With `ADHESIM_WRITE_LAYER_TABLES=1` the tables are computed whole and
/// written instead (then build again, and run this test without it).
#[test]
fn shipped_tables_are_the_computed_ones() {
    let write = std::env::var_os("ADHESIM_WRITE_LAYER_TABLES").is_some();
    for (key, name, bytes) in SHIPPED {
        let file = format!("{}/src/elastic/layer_tables/{name}.f64", env!("CARGO_MANIFEST_DIR"));
        if write {
            let values: Vec<u8> = computed(key, 1).iter().flat_map(|value| value.to_le_bytes()).collect();
            std::fs::write(&file, values).unwrap();
            continue;
        }
        let Some(values) = shipped(key) else {
            panic!(
                "{key:?}: {file} holds {} bytes, not {TABLE_ROWS} rows of 8: write it anew (ADHESIM_WRITE_LAYER_TABLES=1)",
                bytes.len()
            );
        };
        let computed = computed(key, STRIDE);
        let sampled: Vec<f64> = values.into_iter().step_by(STRIDE).collect();
        assert_eq!(sampled.len(), computed.len(), "{key:?}");
        for (row, (shipped, computed)) in sampled.iter().zip(&computed).enumerate() {
            assert_eq!(
                shipped.to_bits(),
                computed.to_bits(),
                "{key:?}, row {}: shipped {shipped:e}, computed {computed:e}: write the tables anew (ADHESIM_WRITE_LAYER_TABLES=1)",
                row * STRIDE
            );
        }
    }
}
