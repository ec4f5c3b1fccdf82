//! One adhesive indent–pull-off cycle of a rough sphere on a free half-space: the cost and
//! the outputs of one case of the rough-sphere study (docs/rough-spheres.md).
//!
//! `cargo run --release -p adhesim --example rough_sphere_cycle -- [n] [hurst] [rms_slope] [seed] [steps]`
//! (defaults 128 0.8 0.05 1 300)
//!
//! The smooth part is the paper's Fig. 1 set-up: R = E* = 1, γ0 = 6.1685e-4 (a_JKR ≈ 0.28),
//! a square of side 0.8, indentation to 15·|d_JKR| in `steps` equal steps and back until
//! contact is lost. The roughness is a random-phase self-affine surface of the given Hurst
//! exponent and rms slope (over the band) with a spectrum fixed in physical units so that
//! every n draws the same band: roll-off λ_r = 0.2 (≈ 0.7·a_JKR: the contact spans a few
//! roll-off wavelengths), cutoff λ_s = 0.05 (4 elements at n = 64, 8 at n = 128), peaks
//! towards the half-space, depth counted from first contact ([`adhesim::RoughProfile`]).
//! The surface differs between n (the generator's random stream fills a different
//! lattice), so the two resolutions are two samples of one ensemble, not a refinement.
//! γ1 and γ2 are the JKR fits of the approach and pull-off branches for contact radii
//! ≥ 0.5·a_JKR (`adhesim::analysis::curve`, as the CLI does).
//!
//! Measured on the shared 2-core machine (load average 8.5–10: six engineers' builds and
//! tests, so wall times are upper bounds; user CPU time in brackets where taken), hurst
//! 0.8, seed 1, 300 approach steps; the rms slope 1e-9 rows are the smooth sphere at the
//! same settings (the discretisation baseline). γ1/γ0 and γ2/γ0 are given with the
//! farthest-contact radius the CLI's fits use, then with the area-equivalent radius √(A/π):
//!
//! | n   | rms_slope | h_rms/\|d_JKR\| | steps | wall (CPU)    | FFT pairs/step | solves/step | CG it./solve | F_ad/\|F_JKR\| | γ1/γ0, γ2/γ0 | same, √(A/π) |
//! |-----|-----------|-----------------|-------|---------------|----------------|-------------|--------------|-----------------|---------------|---------------|
//! | 64  | 0.05      | 0.200           | 640   | 9.8–12.4 s (3.6) | 87.1        | 11.7        | 6.5          | 1.089           | 1.249, 1.245  | 1.030, 1.030  |
//! | 64  | 1e-9      | 0               | 648   | 3.8–4.5 s     | 29.6           | 5.3         | 4.8          | 1.114           | 1.050, 1.051  | 1.065, 1.066  |
//! | 128 | 0.05      | 0.198           | 644   | 44–51 s (17.8–18.7) | 144.6    | 18.7        | 6.8          | 1.031           | 1.356, 1.350  | 1.011, 1.011  |
//! | 128 | 1e-9      | 0               | 645   | 13.5–17.7 s (7.8–8.1) | 58.8   | 9.2         | 5.5          | 1.064           | 1.031, 1.031  | 1.033, 1.033  |
//!
//! Roughness makes a step 2–3 times dearer than the smooth sphere (more contact-set
//! changes: more solves per step) and n = 128 costs about 4–5 times n = 64 per cycle: a
//! study of, say, 10 seeds × 5 rms slopes at n = 128 is about 15 CPU-minutes (40 minutes
//! wall at this load). At this weak roughness (h_rms = 0.2·|d_JKR|) the pull-off force
//! drops by 2–3 % against the smooth sphere at the same n, and γ1 ≈ γ2 (no measurable
//! hysteresis). γ1, γ2 > γ0 with the farthest-contact radius come from that radius (an
//! outlying asperity contact lengthens it), not from stronger adhesion: with √(A/π) they
//! fall back to the smooth values. The study must choose its radius measure before
//! reading γ1/γ2.
use adhesim::analysis::curve::{analyse_indentation, CurveAnalysisOptions};
use adhesim::analysis::fit::fit_jkr_work_of_adhesion;
use adhesim::analysis::reference::Jkr;
use adhesim::surface::{rms_height, rms_slope};
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Amplitudes, Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff,
    NormalSolver, Phase, Problem, Profile, RmsTarget, RoughBase, SelfAffine, Sphere, StepRecord,
};
use std::process::ExitCode;

const USAGE: &str = "usage: rough_sphere_cycle [n] [hurst] [rms_slope] [seed] [steps]";

fn argument<T: std::str::FromStr>(values: &[String], index: usize, name: &str, default: T) -> Result<T, String> {
    match values.get(index) {
        None => Ok(default),
        Some(text) => text
            .parse()
            .map_err(|_| format!("argument {name} must be a number, got {text:?}\n{USAGE}")),
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("rough_sphere_cycle: {message}");
            ExitCode::from(2)
        }
    }
}

fn run() -> Result<(), String> {
    let values: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = argument(&values, 0, "n", 128)?;
    let hurst: f64 = argument(&values, 1, "hurst", 0.8)?;
    let slope: f64 = argument(&values, 2, "rms_slope", 0.05)?;
    let seed: u64 = argument(&values, 3, "seed", 1)?;
    let steps: usize = argument(&values, 4, "steps", 300)?;
    if steps == 0 {
        return Err(format!("argument steps must be >= 1, got 0\n{USAGE}"));
    }
    let (radius, modulus, work_of_adhesion) = (1.0, 1.0, 6.168_502_750_680_85e-4);
    let jkr = Jkr {
        radius,
        contact_modulus: modulus,
        work_of_adhesion,
    };
    let grid = Grid::new(n, 0.8, Boundary::Free).map_err(|e| format!("argument n: {e}"))?;
    let surface = SelfAffine::new(hurst, RmsTarget::Slope(slope))
        .with_rolloff_wavelength(0.2)
        .with_cutoff_wavelength(0.05)
        .with_amplitudes(Amplitudes::RandomPhase)
        .generate(&grid, seed)
        .map_err(|e| format!("roughness (hurst {hurst}, rms_slope {slope}, n {n}): {e}"))?;
    let sphere = Sphere::new(radius).map_err(|e| e.to_string())?;
    let profile = surface
        .to_rough_profile(RoughBase::Sphere(sphere))
        .map_err(|e| e.to_string())?;
    let heights = profile.heights(&grid);
    let d_jkr = jkr.critical_depth().abs();
    let max_depth = 15.0 * d_jkr;
    let operator = FreeOperator::new(grid, ElasticMaterial::new(modulus).map_err(|e| e.to_string())?);
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        modulus,
        vec![work_of_adhesion; grid.len()],
        AdhesiveParams::default(),
    )));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth,
        depth_step: max_depth / steps as f64,
        max_retract_steps: 100 * steps,
        jump_force_threshold: 0.0,
    };
    let mut records: Vec<StepRecord> = Vec::new();
    let start = std::time::Instant::now();
    let mut problem = Problem::new(Box::new(operator), heights.clone()).map_err(|e| e.to_string())?;
    let summary = protocol
        .run(&mut problem, &mut solver, &mut records)
        .map_err(|e| format!("cycle: {e}"))?;
    let wall = start.elapsed().as_secs_f64();
    let analysis = analyse_indentation(
        &records,
        &CurveAnalysisOptions {
            radius,
            contact_modulus: modulus,
            work_of_adhesion,
            min_fit_radius: 0.5 * jkr.critical_radius(),
        },
    );
    let ratio = |fit: Option<adhesim::analysis::fit::JkrFit>| {
        fit.map_or("null".to_string(), |f| {
            format!("{:.4}", f.work_of_adhesion / work_of_adhesion)
        })
    };
    // The same fits with the area-equivalent radius √(A/π) in place of the farthest contact.
    let min_fit_radius = 0.5 * jkr.critical_radius();
    let area_fit = |phase: Phase, skip: usize| {
        let points: Vec<(f64, f64)> = records
            .iter()
            .filter(|r| r.phase == Some(phase))
            .skip(skip)
            .map(|r| ((r.area / std::f64::consts::PI).sqrt(), r.force_normal))
            .filter(|&(a, _)| a > 0.0 && a >= min_fit_radius)
            .collect();
        fit_jkr_work_of_adhesion(&points, radius, modulus)
    };
    let per_step = |total: f64| total / summary.steps as f64;
    println!(
        "n = {n}, hurst = {hurst}, rms_slope = {:.4} (grid), h_rms = {:.3e} = {:.3} |d_JKR|, seed = {seed}",
        rms_slope(&grid, &surface.heights).map_err(|e| e.to_string())?,
        rms_height(&grid, &surface.heights).map_err(|e| e.to_string())?,
        rms_height(&grid, &surface.heights).map_err(|e| e.to_string())? / d_jkr,
    );
    println!(
        "pull-off force / |F_JKR| = {:.4}, gamma1/gamma0 = {}, gamma2/gamma0 = {}, touches border: {}",
        summary.max_adhesive_force / jkr.critical_force().abs(),
        ratio(analysis.gamma_approach),
        ratio(analysis.gamma_pulloff),
        summary.touches_border
    );
    println!(
        "with the area-equivalent radius sqrt(A/pi): gamma1/gamma0 = {}, gamma2/gamma0 = {}",
        ratio(area_fit(Phase::Approach, 0)),
        ratio(area_fit(Phase::Retract, analysis.pinned_steps)),
    );
    println!(
        "{} steps in {wall:.1} s ({:.3} s/step), {:.1} FFT pairs/step, {:.2} solves/step, {:.2} CG iterations/solve",
        summary.steps,
        wall / summary.steps as f64,
        per_step(summary.operator_applications as f64),
        per_step(summary.solves as f64),
        summary.cg_iterations as f64 / summary.solves.max(1) as f64,
    );
    Ok(())
}
