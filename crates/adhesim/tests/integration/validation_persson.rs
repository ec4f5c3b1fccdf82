//! Persson's area–load law for non-adhesive contact of a periodic random self-affine
//! surface at small loads: A/A0 = κ·p̄/(E*·h'_rms).
//!
//! Persson (2001), "Theory of rubber friction and contact mechanics", *J. Chem. Phys.* 115,
//! 3840, doi:10.1063/1.1388626, gives κ = √(8/π) ≈ 1.6; finite-element, boundary-element
//! and molecular studies find larger values, up to ≈ 2.2–2.3 (Hyun, Pei, Molinari & Robbins
//! (2004), *Phys. Rev. E* 70, 026117; Campañá & Müser (2007), *EPL* 77, 38005), depending
//! on the breadth of the spectrum (Yastrebov, Anciaux & Molinari (2017), *J. Mech. Phys.
//! Solids* 107, 469). docs/validation.md §9 reports the numbers.
//!
//! Setting: H = 0.8, random-phase amplitudes (the requested h'_rms exactly), roll-off at
//! q_r = 4·2π/L (a plateau of ~50 modes: enough independent long-wavelength hills for the
//! contact to self-average over a seed, which q_r = 2·2π/L is not: κ then spreads from 2.1
//! to 2.9 between seeds), cutoff q_s with 8 elements per shortest wavelength; the rigid
//! surface z = −h is pressed by load control (Ccg, element-consistent periodic kernel)
//! to p̄/(E*h'_rms) = 0.005, 0.01, 0.02 (A/A0 ≈ 1–5 %, tens to hundreds of contact
//! patches). The real area is counted as Δ² per element in contact, which overestimates
//! it by a strip of order Δ along the perimeter; the same surface sampled at every second
//! element (the band stays below the coarse Nyquist, so it is the same continuous surface)
//! gives a second resolution, and κ∞ = 2κ_Δ − κ_2Δ removes the first-order error (the
//! differences 8 → 16 → 32 elements per λ_s halve, as first order requires).

use adhesim::surface::rms_slope;
use adhesim::{
    Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, Grid, HalfSpace, RmsTarget, SelfAffine,
};

const LOADS: [f64; 3] = [0.005, 0.01, 0.02];

/// κ per seed and load at the fine and the coarse resolution.
struct Study {
    fine: Vec<[f64; 3]>,
    coarse: Vec<[f64; 3]>,
}

fn kappa(grid: &Grid, heights: &[f64], slope: f64) -> [f64; 3] {
    let modulus = 1.0;
    let mut operator = HalfSpace::new(*grid, ElasticMaterial::new(modulus).unwrap());
    let mut state = ContactState::new(grid);
    let mut solver = Ccg::new(CcgParams::default());
    let area = grid.size_x() * grid.size_x();
    let mut out = [0.0; 3];
    for (value, load) in out.iter_mut().zip(LOADS) {
        // loads ascend: each solve starts from the previous contact (warm start)
        let mean_pressure = load * modulus * slope;
        let report = solver
            .solve(&mut operator, heights, Control::Load(mean_pressure * area), &mut state)
            .unwrap();
        *value = report.contact_area / area / load;
    }
    out
}

fn study(n: usize, rolloff_index: f64, cutoff_index: f64, seeds: u64) -> Study {
    let size = 1.0;
    let grid = Grid::new(n, size, Boundary::Periodic).unwrap();
    let coarse_grid = Grid::new(n / 2, size, Boundary::Periodic).unwrap();
    let spectrum = SelfAffine::new(0.8, RmsTarget::Slope(0.1))
        .with_rolloff_wavelength(size / rolloff_index)
        .with_cutoff_wavelength(size / cutoff_index);
    let mut result = Study {
        fine: Vec::new(),
        coarse: Vec::new(),
    };
    for seed in 0..seeds {
        let surface = spectrum.generate(&grid, seed).unwrap();
        let slope = rms_slope(&grid, &surface.heights).unwrap();
        assert!((slope / 0.1 - 1.0).abs() < 1e-10);
        let heights: Vec<f64> = surface.heights.iter().map(|h| -h).collect();
        let m = n / 2;
        let coarse: Vec<f64> = (0..m * m).map(|k| heights[2 * (k / m) * n + 2 * (k % m)]).collect();
        // the coarse samples are the same band-limited surface: same rms slope
        let coarse_slope = rms_slope(&coarse_grid, &coarse).unwrap();
        assert!((coarse_slope / slope - 1.0).abs() < 1e-10, "{coarse_slope} vs {slope}");
        result.fine.push(kappa(&grid, &heights, slope));
        result.coarse.push(kappa(&coarse_grid, &coarse, slope));
    }
    result
}

fn mean_and_error(values: &[f64]) -> (f64, f64) {
    let count = values.len() as f64;
    let mean = values.iter().sum::<f64>() / count;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (count - 1.0);
    (mean, (variance / count).sqrt())
}

/// κ of one seed: least-squares slope of A/A0 against p̄/(E*h') through the origin.
fn fit(kappas: &[f64; 3]) -> f64 {
    let (mut numerator, mut denominator) = (0.0, 0.0);
    for (kappa, load) in kappas.iter().zip(LOADS) {
        numerator += kappa * load * load;
        denominator += load * load;
    }
    numerator / denominator
}

/// Asserts the law and returns (κ_fine, κ_coarse, κ∞, standard error of κ∞).
///
/// Tolerances: (1) linearity: the seed-mean κ∞ at each load within 10 % of the fit (the
/// law is the small-load asymptote; the area grows slightly sublinearly, by ≈ 3 % per
/// doubling of the load here); (2) the element-count area converges from above
/// (κ_Δ < κ_2Δ); (3) the seed mean of κ∞ inside the range [1.6, 2.3] of the issue itself
/// (the seeds are fixed, so the mean is deterministic; its standard error, from the physical
/// seed-to-seed spread of ≈ 0.1, is printed, not added to the range).
fn check(label: &str, study: &Study) -> (f64, f64, f64, f64) {
    let extrapolated: Vec<[f64; 3]> = study
        .fine
        .iter()
        .zip(&study.coarse)
        .map(|(f, c)| [2.0 * f[0] - c[0], 2.0 * f[1] - c[1], 2.0 * f[2] - c[2]])
        .collect();
    let fits = |rows: &[[f64; 3]]| rows.iter().map(fit).collect::<Vec<f64>>();
    let (fine, fine_error) = mean_and_error(&fits(&study.fine));
    let (coarse, _) = mean_and_error(&fits(&study.coarse));
    let (limit, error) = mean_and_error(&fits(&extrapolated));
    let per_load: Vec<f64> = (0..3)
        .map(|j| extrapolated.iter().map(|row| row[j]).sum::<f64>() / extrapolated.len() as f64)
        .collect();
    eprintln!(
        "{label}: κ(Δ) = {fine:.3} ± {fine_error:.3}, κ(2Δ) = {coarse:.3}, κ∞ = {limit:.3} ± {error:.3} \
         (seed mean ± standard error, {} seeds); κ∞ at p̄/(E*h') = 0.005, 0.01, 0.02: {:.3}, {:.3}, {:.3}",
        study.fine.len(),
        per_load[0],
        per_load[1],
        per_load[2]
    );
    for (load, value) in LOADS.iter().zip(&per_load) {
        assert!(
            (value / limit - 1.0).abs() < 0.10,
            "{label}: κ∞ = {value:.3} at p̄/(E*h') = {load} vs fit {limit:.3}: A/A0 not linear in the load"
        );
    }
    assert!(fine < coarse, "{label}: κ(Δ) = {fine:.3} not below κ(2Δ) = {coarse:.3}");
    assert!(
        (1.6..=2.3).contains(&limit),
        "{label}: κ∞ = {limit:.3} ± {error:.3} outside Persson's and the published range 1.6–2.3"
    );
    (fine, coarse, limit, error)
}

/// Default suite (≈ 2 s): N = 256 (8 elements per λ_s) and 128, q_r = 4·2π/L,
/// q_s = 32·2π/L, 6 seeds.
#[test]
fn area_grows_linearly_with_load_persson() {
    check("N = 256/128, q_r = 4, q_s = 32 (2π/L)", &study(256, 4.0, 32.0, 6));
}

/// The full study, `cargo test --release -p adhesim --test integration validation_persson::
/// -- --ignored --nocapture` (3.4 min wall on the shared 2-core machine, load ≈ 10): a
/// broader band (q_s = 64·2π/L, N = 512/256) and the band of the default test resolved twice
/// as finely (N = 512/256, 16 elements per λ_s), 8 seeds each.
#[test]
#[ignore = "3.4 min: cargo test --release -p adhesim --test integration validation_persson:: -- --ignored --nocapture"]
fn area_grows_linearly_with_load_persson_full() {
    check("N = 512/256, q_r = 4, q_s = 64 (2π/L)", &study(512, 4.0, 64.0, 8));
    check("N = 512/256, q_r = 4, q_s = 32 (2π/L)", &study(512, 4.0, 32.0, 8));
}
