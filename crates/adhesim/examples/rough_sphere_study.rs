//! The rough-sphere study: adhesive indent–pull-off cycles of spheres
//! carrying random self-affine roughness on a free half-space, for several Hurst exponents,
//! rms slopes and seeds; one table row per case (docs/rough-spheres.md).
//!
//! ```text
//! cargo run --release -p adhesim --example rough_sphere_study -- study  OUT.csv [n] [threads] [steps]
//! cargo run --release -p adhesim --example rough_sphere_study -- strong OUT.csv [n] [threads] [steps]
//! cargo run --release -p adhesim --example rough_sphere_study -- wide   OUT.csv [n] [threads] [steps]
//! cargo run --release -p adhesim --example rough_sphere_study -- refine OUT.csv [n] [threads] [steps]
//! cargo run --release -p adhesim --example rough_sphere_study -- case   n hurst rms_slope seed [steps]
//! ```
//! (defaults n = 128, threads = 2, steps = 300). `study` runs hurst ∈ {0.3, 0.5, 0.8} ×
//! rms slope ∈ {0.05, 0.1, 0.2, 0.3} × seeds 1–3 at n, `strong` the same at rms slope 0.5;
//! `wide` hurst ∈ {0.3, 0.8} × rms slope ∈ {0.1, 0.2} × seeds 1–3 with the roll-off at
//! λ_r = 0.8 (a 16-fold band); `refine` runs three representative
//! cases at n and at 2n; `case` prints one row. Rows are appended to OUT.csv as cases finish
//! (the header is written when the file is new), so an interrupted run keeps what it did.
//!
//! Set-up (the paper's Fig. 1 sphere, `rough_sphere_cycle`'s band): R = E* = 1,
//! γ0 = 6.1685e-4 (a_JKR = 0.1297, |d_JKR| = 5.604e-3), a square of side 0.8, indentation to
//! 15·|d_JKR| in `steps` equal steps, then back until contact is lost. The roughness is a
//! random-phase self-affine surface with roll-off λ_r = 0.2 and cutoff λ_s = 0.05, its rms
//! slope fixed over the band, peaks towards the half-space, depth counted from first
//! contact. Every case draws its surface on the grid of 2n elements and averages 2×2 blocks
//! down to n, so that a case and its refinement carry the same surface (the generator's
//! random stream fills a different lattice at each n; the block average damps the shortest
//! band wavelength, 16 fine elements, by 2 % per axis). The table records the rms height and
//! slope of the surface actually pressed (at n).
//!
//! γ1, γ2 are the JKR fits of the approach and pull-off branches for contact radii ≥
//! 0.5·a_JKR with the paper's contact radius (the farthest contact element,
//! `analysis::curve`, as the CLI and the wavy-sphere master curves use), and again with the
//! area-equivalent radius √(A/π) (`*_area_norm` columns).
use adhesim::analysis::curve::{analyse_indentation, CurveAnalysisOptions};
use adhesim::analysis::fit::fit_jkr_work_of_adhesion;
use adhesim::analysis::johnson::{rough_sphere_parameter, roughness_depth_ratio};
use adhesim::analysis::reference::Jkr;
use adhesim::surface::{rms_height, rms_slope};
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Amplitudes, Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff,
    NormalSolver, Phase, Problem, Profile, RmsTarget, RoughProfile, SelfAffine, StepRecord,
};
use rayon::prelude::*;
use std::io::Write;
use std::process::ExitCode;
use std::sync::Mutex;

const USAGE: &str = "usage: rough_sphere_study study|strong|wide|refine OUT.csv [n] [threads] [steps]\n       rough_sphere_study case n hurst rms_slope seed [steps]";
const RADIUS: f64 = 1.0;
const MODULUS: f64 = 1.0;
const WORK_OF_ADHESION: f64 = 6.168_502_750_680_85e-4;
const SIDE: f64 = 0.8;
const ROLLOFF_WAVELENGTH: f64 = 0.2;
const CUTOFF_WAVELENGTH: f64 = 0.05;
const WIDE_ROLLOFF_WAVELENGTH: f64 = 0.8;
const HEADER: &str = "case,series,n,hurst,rms_slope_target,seed,radius,contact_modulus,work_of_adhesion,rms_height,rms_slope,rough_sphere_parameter,roughness_depth_ratio,adhesive_force_ratio,gamma_approach_norm,gamma_pulloff_norm,gamma_approach_area_norm,gamma_pulloff_area_norm,touches_border,steps,wall_s,status";

/// One cycle to run.
#[derive(Debug, Clone, Copy)]
struct Case {
    n: usize,
    hurst: f64,
    slope: f64,
    seed: u64,
    steps: usize,
    /// The surface is drawn on a grid of `n * fine_factor` elements and block-averaged to n.
    fine_factor: usize,
    /// Roll-off wavelength λ_r of the spectrum.
    rolloff: f64,
}

impl Case {
    fn name(&self) -> String {
        let band = if self.rolloff == ROLLOFF_WAVELENGTH {
            String::new()
        } else {
            format!("_r{}", self.rolloff)
        };
        format!("h{}_s{}_seed{}_n{}{band}", self.hurst, self.slope, self.seed, self.n)
    }
}

fn parse<T: std::str::FromStr>(values: &[String], index: usize, name: &str, default: Option<T>) -> Result<T, String> {
    match (values.get(index), default) {
        (None, Some(default)) => Ok(default),
        (None, None) => Err(format!("argument {name} is missing\n{USAGE}")),
        (Some(text), _) => text
            .parse()
            .map_err(|_| format!("argument {name} must be a number, got {text:?}\n{USAGE}")),
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("rough_sphere_study: {message}");
            ExitCode::from(2)
        }
    }
}

fn run() -> Result<(), String> {
    let values: Vec<String> = std::env::args().skip(1).collect();
    let mode = values.first().map(String::as_str).unwrap_or("");
    if mode == "case" {
        let case = Case {
            n: parse(&values, 1, "n", None)?,
            hurst: parse(&values, 2, "hurst", None)?,
            slope: parse(&values, 3, "rms_slope", None)?,
            seed: parse(&values, 4, "seed", None)?,
            steps: parse(&values, 5, "steps", Some(300))?,
            fine_factor: 2,
            rolloff: ROLLOFF_WAVELENGTH,
        };
        println!("{HEADER}\n{}", row(&case));
        return Ok(());
    }
    if !["study", "strong", "wide", "refine"].contains(&mode) {
        return Err(format!("unknown mode {mode:?}\n{USAGE}"));
    }
    let out: String = parse(&values, 1, "OUT.csv", None)?;
    let n: usize = parse(&values, 2, "n", Some(128))?;
    let threads: usize = parse(&values, 3, "threads", Some(2))?;
    let steps: usize = parse(&values, 4, "steps", Some(300))?;
    if steps == 0 || threads == 0 {
        return Err(format!("arguments threads and steps must be >= 1\n{USAGE}"));
    }
    let mut cases = Vec::new();
    let case = |n, hurst, slope, seed, fine_factor| Case {
        n,
        hurst,
        slope,
        seed,
        steps,
        fine_factor,
        rolloff: ROLLOFF_WAVELENGTH,
    };
    if mode == "study" || mode == "strong" {
        let slopes: &[f64] = if mode == "study" {
            &[0.05, 0.1, 0.2, 0.3]
        } else {
            &[0.5]
        };
        for &slope in slopes {
            for hurst in [0.3, 0.5, 0.8] {
                for seed in 1..=3 {
                    cases.push(case(n, hurst, slope, seed, 2));
                }
            }
        }
    } else if mode == "wide" {
        // A 16-fold band (λ_r = 0.8, the domain's side), where h_rms/h'_rms grows by a
        // factor 1.75 from H = 0.3 to 0.8 (1.17 in the 4-fold band of `study`).
        for slope in [0.1, 0.2] {
            for hurst in [0.3, 0.8] {
                for seed in 1..=3 {
                    cases.push(Case {
                        rolloff: WIDE_ROLLOFF_WAVELENGTH,
                        ..case(n, hurst, slope, seed, 2)
                    });
                }
            }
        }
    } else {
        // Weak, intermediate and strong roughness; the fine case draws at its own grid.
        for (hurst, slope) in [(0.8, 0.1), (0.5, 0.2), (0.3, 0.3)] {
            cases.push(case(2 * n, hurst, slope, 1, 1));
            cases.push(case(n, hurst, slope, 1, 2));
        }
    }
    let new_file = !std::path::Path::new(&out).exists();
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&out)
        .map_err(|e| format!("cannot open {out}: {e}"))?;
    if new_file {
        writeln!(file, "{HEADER}").map_err(|e| format!("cannot write {out}: {e}"))?;
    }
    let file = Mutex::new(file);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| e.to_string())?;
    let total = cases.len();
    pool.install(|| {
        cases.par_iter().try_for_each(|case| {
            let line = row(case);
            eprintln!("{} of {total}: {line}", case.name());
            let mut file = file.lock().expect("writer lock");
            writeln!(file, "{line}")
                .and_then(|()| file.flush())
                .map_err(|e| format!("cannot write {out}: {e}"))
        })
    })
}

/// One table row: the case's inputs and results, or its error in the status column.
fn row(case: &Case) -> String {
    let series = if case.rolloff == ROLLOFF_WAVELENGTH {
        format!("H = {}", case.hurst)
    } else {
        format!("H = {} (λ_r = {})", case.hurst, case.rolloff)
    };
    let inputs = format!(
        "{},{series},{},{},{},{},{RADIUS},{MODULUS},{WORK_OF_ADHESION:e}",
        case.name(),
        case.n,
        case.hurst,
        case.slope,
        case.seed
    );
    match cycle(case) {
        Ok(result) => format!("{inputs},{result},ok"),
        Err(message) => format!("{inputs},,,,,,,,,,,,,\"{}\"", message.replace('"', "'")),
    }
}

/// The roughness of `case` on its grid: drawn on the fine grid, block-averaged to n.
fn roughness(case: &Case, grid: &Grid) -> Result<Vec<f64>, String> {
    let factor = case.fine_factor;
    let fine_grid = Grid::new(case.n * factor, SIDE, Boundary::Free).map_err(|e| e.to_string())?;
    let fine = SelfAffine::new(case.hurst, RmsTarget::Slope(case.slope))
        .with_rolloff_wavelength(case.rolloff)
        .with_cutoff_wavelength(CUTOFF_WAVELENGTH)
        .with_amplitudes(Amplitudes::RandomPhase)
        .generate(&fine_grid, case.seed)
        .map_err(|e| format!("roughness of {}: {e}", case.name()))?;
    let (n, fine_n) = (grid.nx(), fine_grid.nx());
    let mut heights = vec![0.0; grid.len()];
    for (k, height) in heights.iter_mut().enumerate() {
        let (row, column) = (k / n, k % n);
        let mut sum = 0.0;
        for i in 0..factor {
            for j in 0..factor {
                sum += fine.heights[(row * factor + i) * fine_n + column * factor + j];
            }
        }
        *height = sum / (factor * factor) as f64;
    }
    Ok(heights)
}

/// Runs one cycle; returns the result columns (from rms_height to wall_s).
fn cycle(case: &Case) -> Result<String, String> {
    let jkr = Jkr {
        radius: RADIUS,
        contact_modulus: MODULUS,
        work_of_adhesion: WORK_OF_ADHESION,
    };
    let grid = Grid::new(case.n, SIDE, Boundary::Free).map_err(|e| e.to_string())?;
    let map = roughness(case, &grid)?;
    let (h_rms, slope_rms) = (
        rms_height(&grid, &map).map_err(|e| e.to_string())?,
        rms_slope(&grid, &map).map_err(|e| e.to_string())?,
    );
    let profile = RoughProfile::rough_sphere(RADIUS, map, &grid).map_err(|e| e.to_string())?;
    let heights = profile.heights(&grid);
    let max_depth = 15.0 * jkr.critical_depth().abs();
    let operator = FreeOperator::new(grid, ElasticMaterial::new(MODULUS).map_err(|e| e.to_string())?);
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        MODULUS,
        vec![WORK_OF_ADHESION; grid.len()],
        AdhesiveParams::default(),
    )));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth,
        depth_step: max_depth / case.steps as f64,
        max_retract_steps: 100 * case.steps,
        jump_force_threshold: 0.0,
    };
    let mut records: Vec<StepRecord> = Vec::new();
    let start = std::time::Instant::now();
    let mut problem = Problem::new(Box::new(operator), heights).map_err(|e| e.to_string())?;
    let summary = protocol
        .run(&mut problem, &mut solver, &mut records)
        .map_err(|e| format!("cycle of {}: {e}", case.name()))?;
    let wall = start.elapsed().as_secs_f64();
    let min_fit_radius = 0.5 * jkr.critical_radius();
    let analysis = analyse_indentation(
        &records,
        &CurveAnalysisOptions {
            radius: RADIUS,
            contact_modulus: MODULUS,
            work_of_adhesion: WORK_OF_ADHESION,
            min_fit_radius,
        },
    );
    // The same fits with the area-equivalent radius √(A/π) in place of the farthest contact.
    let area_fit = |phase: Phase, skip: usize| {
        let points: Vec<(f64, f64)> = records
            .iter()
            .filter(|r| r.phase == Some(phase))
            .skip(skip)
            .map(|r| ((r.area / std::f64::consts::PI).sqrt(), r.force_normal))
            .filter(|&(a, _)| a > 0.0 && a >= min_fit_radius)
            .collect();
        fit_jkr_work_of_adhesion(&points, RADIUS, MODULUS)
    };
    let ratio = |fit: Option<adhesim::analysis::fit::JkrFit>| {
        fit.map_or(String::new(), |f| {
            format!("{:.5}", f.work_of_adhesion / WORK_OF_ADHESION)
        })
    };
    let optional = |value: Option<f64>| value.map_or(String::new(), |v| format!("{v:.5}"));
    Ok(format!(
        "{h_rms:.6e},{slope_rms:.6},{},{},{:.5},{},{},{},{},{},{},{wall:.1}",
        optional(rough_sphere_parameter(h_rms, slope_rms, WORK_OF_ADHESION, MODULUS)),
        optional(roughness_depth_ratio(h_rms, RADIUS, WORK_OF_ADHESION, MODULUS)),
        summary.max_adhesive_force / jkr.critical_force().abs(),
        ratio(analysis.gamma_approach),
        ratio(analysis.gamma_pulloff),
        ratio(area_fit(Phase::Approach, 0)),
        ratio(area_fit(Phase::Retract, analysis.pinned_steps)),
        summary.touches_border,
        summary.steps,
    ))
}
