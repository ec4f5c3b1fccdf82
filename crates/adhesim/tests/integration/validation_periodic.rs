//! Periodic contact of a 1-D wavy surface against Westergaard (1939) / Johnson (1995):
//! z = h(1 − cos 2πx/λ), contact strips of half-width a, ψ = πa/λ, p* = πE*h/λ:
//! mean pressure p̄ = p*·sin²ψ and mean gap ḡ = h(cos²ψ + 2 sin²ψ ln sin ψ) (physics
//! notes §4, non-adhesive branch). On a periodic half-space the displacement has zero mean
//! (K̂(0) = 0), so the mean gap is mean(z) − d = h − d.

use adhesim::{Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, Grid, HalfSpace};
use std::f64::consts::{PI, TAU};

/// λ = L = 128Δ; for ψ = π/4 and π/3 the load-controlled solve at p̄ = p*·sin²ψ gives a
/// contact half-width within one element of λψ/π and a mean gap within 1 % of h (the
/// element-consistent kernel of a 128-element period; the edge square root is resolved by
/// several elements); displacement control at d = h − ḡ returns the force within 1 %.
#[test]
fn wavy_contact_matches_westergaard() {
    let n = 128;
    let size = 1.0;
    let amplitude = 1e-3;
    let modulus = 1.0;
    let grid = Grid::new(n, size, Boundary::Periodic).unwrap();
    let delta = grid.dx();
    let mut operator = HalfSpace::new(grid, ElasticMaterial::new(modulus).unwrap());
    let heights: Vec<f64> = (0..grid.len())
        .map(|k| amplitude * (1.0 - (TAU * grid.centre(k).0 / size).cos()))
        .collect();
    let full_contact_pressure = PI * modulus * amplitude / size;
    for psi in [PI / 4.0, PI / 3.0] {
        let mean_pressure = full_contact_pressure * psi.sin().powi(2);
        let mean_gap = amplitude * (psi.cos().powi(2) + 2.0 * psi.sin().powi(2) * psi.sin().ln());
        let mut state = ContactState::new(&grid);
        let report = Ccg::new(CcgParams::default())
            .solve(
                &mut operator,
                &heights,
                Control::Load(mean_pressure * size * size),
                &mut state,
            )
            .unwrap();
        // half-width: largest |x| in contact along a row
        let half_width = (0..n)
            .filter(|&j| state.contact[j])
            .map(|j| grid.x(j).abs())
            .fold(0.0, f64::max);
        let expected = size * psi / PI;
        assert!(
            (half_width - expected).abs() <= delta,
            "ψ = {psi}: a = {half_width} vs {expected}"
        );
        let simulated_gap = amplitude - report.depth;
        assert!(
            (simulated_gap - mean_gap).abs() < 0.01 * amplitude,
            "ψ = {psi}: mean gap {simulated_gap:e} vs {mean_gap:e}"
        );
        let mut state = ContactState::new(&grid);
        let report = Ccg::new(CcgParams::default())
            .solve(
                &mut operator,
                &heights,
                Control::Displacement(amplitude - mean_gap),
                &mut state,
            )
            .unwrap();
        let force = mean_pressure * size * size;
        assert!(
            (report.force / force - 1.0).abs() < 0.01,
            "ψ = {psi}: F = {} vs {force}",
            report.force
        );
    }
}
