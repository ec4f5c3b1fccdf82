//! Random self-affine surfaces (`adhesim::surface`): requested rms, spectrum, plateau,
//! determinism and parameter errors.

use adhesim::surface::{isotropic_psd, rms_height, rms_slope, statistics};
use adhesim::{Amplitudes, Boundary, Grid, RmsTarget, SelfAffine, SurfaceError};
use std::f64::consts::TAU;

/// Random-phase amplitudes make the periodic map's rms height or rms slope the requested
/// value to rounding: the prefactor comes from the same discrete sums the statistics
/// evaluate (Parseval). 1e-10 relative leaves 10⁵ ulps for the two FFTs and the sums.
#[test]
fn random_phase_rms_is_exact() {
    for n in [64, 75, 128] {
        let grid = Grid::new(n, 2.5, Boundary::Periodic).unwrap();
        for (target, hurst) in [(RmsTarget::Height(0.37), 0.8), (RmsTarget::Slope(0.11), 0.3)] {
            for spectrum in [
                SelfAffine::new(hurst, target),
                SelfAffine::new(hurst, target)
                    .with_rolloff_wavelength(0.5)
                    .with_cutoff_wavelength(0.1),
                SelfAffine::new(1.0, target).with_rolloff_wavelength(2.5),
            ] {
                let surface = spectrum.generate(&grid, 42).unwrap();
                let stats = statistics(&grid, &surface.heights).unwrap();
                let (value, wanted) = match target {
                    RmsTarget::Height(h) => (stats.rms_height, h),
                    RmsTarget::Slope(s) => (stats.rms_slope, s),
                };
                assert!(
                    (value / wanted - 1.0).abs() < 1e-10,
                    "N = {n}, {spectrum:?}: rms {value} vs {wanted}"
                );
                let mean = surface.heights.iter().sum::<f64>() / surface.heights.len() as f64;
                assert!(mean.abs() < 1e-12 * stats.rms_height, "mean {mean}");
            }
        }
    }
}

/// Each random-phase mode carries exactly the target C(q): a plateau bin (q < q_r, one
/// value C₀·q_r^(−2−2H)) returns it to rounding, and bins above q_s are empty of power.
#[test]
fn random_phase_plateau_and_cutoff_are_exact() {
    let grid = Grid::new(128, 1.0, Boundary::Periodic).unwrap();
    let surface = SelfAffine::new(0.7, RmsTarget::Height(1e-3))
        .with_rolloff_wavelength(1.0 / 10.0)
        .with_cutoff_wavelength(1.0 / 32.0)
        .generate(&grid, 3)
        .unwrap();
    let plateau = surface.target_psd(surface.rolloff_wavevector);
    let bins = isotropic_psd(&grid, &surface.heights, 40).unwrap();
    let mut checked = (0, 0);
    for bin in &bins {
        if bin.edges.1 < surface.rolloff_wavevector {
            assert!(
                (bin.psd / plateau - 1.0).abs() < 1e-10,
                "plateau bin {bin:?} vs {plateau}"
            );
            checked.0 += 1;
        }
        if bin.edges.0 > surface.cutoff_wavevector * 1.001 {
            assert!(bin.psd < 1e-20 * plateau, "bin above cutoff {bin:?}");
            checked.1 += 1;
        }
    }
    assert!(checked.0 >= 5 && checked.1 >= 5, "{checked:?}");
}

/// Filtered (Gaussian) amplitudes: the isotropic PSD averaged over 16 seeds follows
/// C₀q^(−2−2H) within 5 % in each decade of the power-law range (N = 256, q_r = 8·2π/L,
/// q_s = Nyquist = 128·2π/L: decades [q_r, 10q_r) and [10q_r, q_s]) and the plateau
/// C₀q_r^(−2−2H) within 10 % below q_r. Each mode's |H|² is exponentially distributed
/// (relative sd 1), so a decade of ≥ 8 000 independent modes over 16 seeds has a relative
/// standard error below 0.5 % and the ~100 plateau modes × 16 seeds about 2.5 %; the
/// 40 bins per decade bias the comparison at q̄ by < 0.5 %. The bounds are ≥ 4σ.
#[test]
fn filtered_psd_matches_the_target_per_decade() {
    let (n, size, hurst) = (256, 1.0, 0.8);
    let grid = Grid::new(n, size, Boundary::Periodic).unwrap();
    let spectrum = SelfAffine::new(hurst, RmsTarget::Slope(0.1))
        .with_rolloff_wavelength(size / 8.0)
        .with_amplitudes(Amplitudes::Filtered);
    let seeds = 16;
    let bins_count = 85; // log10(128) = 2.1 decades: 40 bins per decade
    let mut ratio_sums = Vec::new();
    let mut template = Vec::new();
    let mut reference = None;
    for seed in 0..seeds {
        let surface = spectrum.generate(&grid, seed).unwrap();
        let bins = isotropic_psd(&grid, &surface.heights, bins_count).unwrap();
        // the same grid gives the same (non-empty) bins for every seed
        ratio_sums.resize(bins.len(), 0.0);
        for (sum, bin) in ratio_sums.iter_mut().zip(&bins) {
            *sum += bin.psd / surface.target_psd(bin.wavevector) / seeds as f64;
        }
        template = bins;
        reference = Some(surface);
    }
    let surface = reference.unwrap();
    let (q_r, q_s) = (surface.rolloff_wavevector, surface.cutoff_wavevector);
    let ranges = [
        ("plateau", 0.0, q_r, 0.10),
        ("decade 1", q_r, 10.0 * q_r, 0.05),
        ("decade 2", 10.0 * q_r, q_s * 1.0001, 0.05),
    ];
    for (name, low, high, tolerance) in ranges {
        let (mut weighted, mut modes) = (0.0, 0usize);
        for (ratio, bin) in ratio_sums.iter().zip(&template) {
            // a bin straddling q_r mixes plateau and power law: left out
            let straddles = bin.edges.0 < q_r && bin.edges.1 > q_r;
            if !straddles && bin.wavevector >= low && bin.wavevector < high {
                weighted += ratio * bin.modes as f64;
                modes += bin.modes;
            }
        }
        let ratio = weighted / modes as f64;
        eprintln!("{name}: <C/C_target> = {ratio:.4} over {modes} modes");
        assert!(modes > 50, "{name}: only {modes} modes");
        assert!(
            (ratio - 1.0).abs() < tolerance,
            "{name}: <C/C_target> = {ratio:.4} over {modes} modes"
        );
    }
}

/// The stream is drawn sequentially: the same seed gives bit-identical heights inside
/// rayon pools of 1 and 2 threads, for both modes and both boundaries; another seed gives
/// another surface.
#[test]
fn same_seed_same_heights_on_one_and_two_threads() {
    let run = |threads: usize, boundary: Boundary, amplitudes: Amplitudes, seed: u64| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let grid = Grid::new(96, 1.0, boundary).unwrap();
            SelfAffine::new(0.6, RmsTarget::Height(1.0))
                .with_amplitudes(amplitudes)
                .generate(&grid, seed)
                .unwrap()
                .heights
        })
    };
    for boundary in [Boundary::Periodic, Boundary::Free] {
        for amplitudes in [Amplitudes::RandomPhase, Amplitudes::Filtered] {
            let one = run(1, boundary, amplitudes, 11);
            let two = run(2, boundary, amplitudes, 11);
            assert!(one.iter().zip(&two).all(|(a, b)| a.to_bits() == b.to_bits()));
            assert_ne!(one, run(2, boundary, amplitudes, 12));
        }
    }
}

/// A free grid is the first N×N block of the periodic surface on a patch `patch_factor`
/// times larger: bit-identical to generating that patch as a periodic grid. Its rms is the
/// patch's (exact) one only on average; a window of a quarter of the patch area deviates by
/// the long-wavelength modes it cannot see whole (here within 30 %).
#[test]
fn free_grid_is_cut_from_a_periodic_patch() {
    let spectrum = SelfAffine::new(0.8, RmsTarget::Height(2.0)).with_rolloff_wavelength(0.5);
    let free = Grid::new(50, 1.0, Boundary::Free).unwrap();
    let patch = Grid::new(100, 2.0, Boundary::Periodic).unwrap();
    let cut = spectrum.generate(&free, 5).unwrap();
    let whole = spectrum.generate(&patch, 5).unwrap();
    assert_eq!(cut.patch_size, 2.0);
    for row in 0..50 {
        assert_eq!(
            cut.heights[row * 50..(row + 1) * 50],
            whole.heights[row * 100..row * 100 + 50]
        );
    }
    assert!((rms_height(&patch, &whole.heights).unwrap() / 2.0 - 1.0).abs() < 1e-10);
    let window_rms = rms_height(&free, &cut.heights).unwrap();
    assert!((window_rms / 2.0 - 1.0).abs() < 0.3, "window rms {window_rms}");
    let factor3 = spectrum.with_patch_factor(3).generate(&free, 5).unwrap();
    assert_eq!(factor3.patch_size, 3.0);
    // a finite-difference rms slope exists for the non-periodic window
    assert!(rms_slope(&free, &cut.heights).unwrap() > 0.0);
}

#[test]
fn invalid_parameters_are_named_errors() {
    let grid = Grid::new(32, 1.0, Boundary::Periodic).unwrap();
    let free = Grid::new(32, 1.0, Boundary::Free).unwrap();
    let base = SelfAffine::new(0.8, RmsTarget::Height(1.0));
    let error = |spectrum: SelfAffine, grid: &Grid| spectrum.generate(grid, 0).unwrap_err();
    for hurst in [0.0, -0.5, 1.5, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(error(SelfAffine { hurst, ..base }, &grid), SurfaceError::Hurst(h) if h.to_bits() == hurst.to_bits())
        );
    }
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = error(SelfAffine::new(0.8, RmsTarget::Height(bad)), &grid);
        assert!(matches!(e, SurfaceError::NotPositive { name: "rms_height", .. }), "{e}");
        let e = error(SelfAffine::new(0.8, RmsTarget::Slope(bad)), &grid);
        assert!(matches!(e, SurfaceError::NotPositive { name: "rms_slope", .. }), "{e}");
        let e = error(base.with_rolloff_wavelength(bad), &grid);
        assert!(
            matches!(
                e,
                SurfaceError::NotPositive {
                    name: "rolloff_wavelength",
                    ..
                }
            ),
            "{e}"
        );
        let e = error(base.with_cutoff_wavelength(bad), &grid);
        assert!(
            matches!(
                e,
                SurfaceError::NotPositive {
                    name: "cutoff_wavelength",
                    ..
                }
            ),
            "{e}"
        );
    }
    // q_r ≥ q_s: roll-off wavelength not longer than the cutoff wavelength
    let e = error(base.with_rolloff_wavelength(0.1).with_cutoff_wavelength(0.1), &grid);
    assert_eq!(
        e,
        SurfaceError::RolloffNotBelowCutoff {
            rolloff: 0.1,
            cutoff: 0.1
        }
    );
    assert!(e.to_string().contains("rolloff_wavelength (0.1)"), "{e}");
    // default cutoff (Nyquist, 2Δ = 1/16) against a roll-off inside the band edge
    assert!(matches!(
        error(base.with_rolloff_wavelength(0.05), &grid),
        SurfaceError::RolloffNotBelowCutoff { .. }
    ));
    assert!(matches!(
        error(base.with_cutoff_wavelength(0.05), &grid),
        SurfaceError::CutoffBelowNyquist { .. }
    ));
    assert!(matches!(
        error(base.with_cutoff_wavelength(2.0), &grid),
        SurfaceError::EmptyBand { .. }
    ));
    assert_eq!(error(base.with_patch_factor(0), &free), SurfaceError::PatchFactor(0));
    assert!(base.validate(&grid).is_ok());
    // the wavevectors reported are 2π/λ
    let surface = base
        .with_rolloff_wavelength(0.25)
        .with_cutoff_wavelength(0.125)
        .generate(&grid, 1)
        .unwrap();
    assert!((surface.rolloff_wavevector - TAU / 0.25).abs() < 1e-12);
    assert!((surface.cutoff_wavevector - TAU / 0.125).abs() < 1e-12);
}

/// Rectangular grids (docs/validation.md §12): on a free rectangle of square elements the
/// surface is the square grid's of the longer side, cut (the same realisation, bit for bit); a
/// periodic rectangle or rectangular elements are refused with the grid named.
#[test]
fn rectangles_cut_the_square_realisation_or_are_refused() {
    use adhesim::{Boundary, Grid, RmsTarget, SelfAffine, SurfaceError};
    let generator = SelfAffine::new(0.8, RmsTarget::Height(1e-3));
    let square = generator
        .generate(&Grid::new(48, 1.5, Boundary::Free).unwrap(), 7)
        .unwrap();
    let wide = Grid::rectangular(48, 32, 1.5, 1.0, Boundary::Free).unwrap();
    let cut = generator.generate(&wide, 7).unwrap();
    assert_eq!(cut.heights.len(), 48 * 32);
    assert_eq!(cut.grid, wide);
    for row in 0..32 {
        assert_eq!(
            cut.heights[row * 48..(row + 1) * 48],
            square.heights[row * 48..(row + 1) * 48]
        );
    }
    let tall = Grid::rectangular(32, 48, 1.0, 1.5, Boundary::Free).unwrap();
    let cut = generator.generate(&tall, 7).unwrap();
    assert_eq!(cut.heights[32..64], square.heights[48..80]);
    for grid in [
        Grid::rectangular(48, 32, 1.5, 1.0, Boundary::Periodic).unwrap(),
        Grid::rectangular(48, 32, 1.0, 1.0, Boundary::Free).unwrap(),
    ] {
        assert!(matches!(
            generator.generate(&grid, 7),
            Err(SurfaceError::RectangularGrid { nx: 48, ny: 32, .. })
        ));
    }
}
