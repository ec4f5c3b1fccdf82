//! Equivalence harness of the fast adhesive step (docs/fast-step.md): runs each case with
//! the reference rule (`AdhesiveParams::reference_rule`, every solve converged), with the
//! default (certified) solver with predicted-subset growth forced on, and with the
//! random-half release order (an independent oracle), and reports per case whether the
//! contact sets are identical at every step, the largest force difference relative to the
//! largest |F| of the run, and the work per step (approach and retraction apart).
//!
//! `cargo run --release -p adhesim --example step_equivalence -- [--check] [CASE ...]`
//!
//! Cases: sphere8 sphere16 sphere32 fig1_64_75 fig1_64_150 fig1_128_75 fig1_128_150
//! fig2_h120 fig12_homogeneous fig12_ratio13 fig12_ratio20 fig6_roll (default: all), and
//! fig1_256_start (the first 3 steps of the Fig. 1 case at n = 256: a tie, docs/fast-step.md §2).
//! `--tight` runs all three with CG tolerances 1e-10 (relative) and 1e-8 (front) instead
//! of 1e-6 and 1e-4, to tell ties inside the default CG error band from real differences.
//! `ADHESIM_VERBOSE=1` lists the differing steps and the pressures there.
//! `--check` converges every certified early stop on a copy and panics if the certified
//! bound or a decision fails. Exit status 1 if any set differs.
use adhesim::analysis::reference::Jkr;
use adhesim::solver::PredictedGrowth;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Axis, Boundary, Detachment, ElasticMaterial, EllipticPunch, FreeOperator, Grid,
    IndentPulloff, Kinematics, NormalSolver, Observer, Phase, Problem, Profile, Sphere, StepView, TranslatingContact,
    Translation, WavySphere, WorkOfAdhesion,
};
use std::ops::ControlFlow;

/// Contact set, force and work of every step.
#[derive(Default)]
struct Run {
    sets: Vec<Vec<bool>>,
    /// Pressures of every step (kept only with ADHESIM_VERBOSE, to look at ties).
    pressures: Vec<Vec<f64>>,
    forces: Vec<f64>,
    phases: Vec<Phase>,
    solves: Vec<usize>,
    fft_pairs: Vec<u64>,
    cg_iterations: Vec<usize>,
    wall: f64,
}

impl Observer for Run {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.sets.push(view.state.contact.clone());
        if std::env::var("ADHESIM_VERBOSE").is_ok() {
            self.pressures.push(view.state.pressure.clone());
        }
        self.forces.push(view.record.force_normal);
        self.phases.push(view.record.phase.unwrap_or(Phase::Approach));
        self.solves.push(view.record.report.solves);
        self.fft_pairs.push(view.record.report.operator_applications);
        self.cg_iterations.push(view.record.report.cg_iterations);
        ControlFlow::Continue(())
    }
}

impl Run {
    /// (steps, FFT pairs/step, solves/step, CG iterations/solve) of one phase group.
    fn work(&self, approach: bool) -> (usize, f64, f64, f64) {
        let pick: Vec<usize> = (0..self.phases.len())
            .filter(|&i| (self.phases[i] == Phase::Approach) == approach)
            .collect();
        let steps = pick.len().max(1) as f64;
        let fft: u64 = pick.iter().map(|&i| self.fft_pairs[i]).sum();
        let solves: usize = pick.iter().map(|&i| self.solves[i]).sum();
        let cg: usize = pick.iter().map(|&i| self.cg_iterations[i]).sum();
        (
            pick.len(),
            fft as f64 / steps,
            solves as f64 / steps,
            cg as f64 / solves.max(1) as f64,
        )
    }
}

/// A case: grid, γ per element, and how to drive it.
struct Case {
    grid: Grid,
    gamma: Vec<f64>,
    drive: Drive,
}

enum Drive {
    Indent {
        heights: Vec<f64>,
        max_depth: f64,
        steps: usize,
    },
    Roll {
        contact: TranslatingContact,
        protocol: Translation,
    },
}

fn sphere(resolution: f64) -> Case {
    let a_jkr: f64 = 0.05;
    let gamma = a_jkr.powi(3) * 8.0 / (9.0 * std::f64::consts::PI);
    let jkr = Jkr {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion: gamma,
    };
    let delta = a_jkr / resolution;
    let reach = jkr
        .radius_at_depth(3.0 * jkr.critical_depth().abs())
        .expect("JKR radius");
    let n = ((2.3 * reach / delta).ceil() as usize).max(16);
    let grid = Grid::new(n + n % 2, (n + n % 2) as f64 * delta, Boundary::Free).expect("grid");
    let heights = Sphere::new(1.0).expect("sphere").heights(&grid);
    let max_depth = 3.0 * jkr.critical_depth().abs();
    Case {
        grid,
        gamma: vec![gamma; grid.len()],
        drive: Drive::Indent {
            heights,
            max_depth,
            steps: 60,
        },
    }
}

/// scenarios/fig1.toml (and fig2_h120 with `amplitude` = 0.006).
fn wavy(n: usize, steps: usize, amplitude: f64) -> Case {
    let gamma = 6.168_502_750_680_85e-4;
    let jkr = Jkr {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion: gamma,
    };
    let grid = Grid::new(n, 0.8, Boundary::Free).expect("grid");
    let heights = WavySphere::new(1.0, amplitude, 0.05, 0.0)
        .expect("profile")
        .heights(&grid);
    let max_depth = 15.0 * jkr.critical_depth().abs();
    Case {
        grid,
        gamma: vec![gamma; grid.len()],
        drive: Drive::Indent {
            heights,
            max_depth,
            steps,
        },
    }
}

/// scenarios/fig12_*.toml: elliptic punch (1, 0.5), γ quadratic along x with `ratio`.
fn punch(ratio: f64) -> Case {
    let grid = Grid::new(128, 2.4, Boundary::Free).expect("grid");
    let field = WorkOfAdhesion::Quadratic {
        middle: 1e-4,
        ratio_end_to_middle: ratio,
        half_length: 1.0,
        axis: Axis::X,
    };
    let gamma = field.on_grid(&grid).expect("γ field");
    let heights = EllipticPunch::new((1.0, 0.5), 0.0).expect("punch").heights(&grid);
    Case {
        grid,
        gamma,
        drive: Drive::Indent {
            heights,
            max_depth: 0.005,
            steps: 25,
        },
    }
}

/// scenarios/fig6.toml, shortened to a 0.5 λ roll.
fn roll() -> Case {
    let gamma = 2e-5;
    let jkr = Jkr {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion: gamma,
    };
    let grid = Grid::new(64, 0.4, Boundary::Free).expect("grid");
    let indenter = WavySphere::new(1.0, 5.627e-4, 0.05, 0.0).expect("profile");
    let start_depth = indenter.heights(&grid).iter().cloned().fold(f64::INFINITY, f64::min);
    let protocol = Translation {
        start_depth,
        depth: 5.0 * jkr.critical_depth().abs(),
        approach_steps: 60,
        distance: 0.5 * 0.05,
        steps: 25,
        return_stroke: false,
        stationary_from: 0.5,
        jump_force_threshold: 0.0,
    };
    Case {
        grid,
        gamma: vec![gamma; grid.len()],
        drive: Drive::Roll {
            contact: TranslatingContact::new(indenter, Kinematics::Roll),
            protocol,
        },
    }
}

fn case(name: &str) -> Option<Case> {
    Some(match name {
        "sphere8" => sphere(8.0),
        "sphere16" => sphere(16.0),
        "sphere32" => sphere(32.0),
        "fig1_64_75" => wavy(64, 75, 0.0025),
        "fig1_64_150" => wavy(64, 150, 0.0025),
        "fig1_128_75" => wavy(128, 75, 0.0025),
        "fig1_128_150" => wavy(128, 150, 0.0025),
        "fig2_h120" => wavy(128, 300, 0.006),
        "fig12_homogeneous" => punch(1.0),
        "fig12_ratio13" => punch(13.0),
        "fig12_ratio20" => punch(20.0),
        "fig6_roll" => roll(),
        "fig1_256_start" => {
            let mut case = wavy(256, 150, 0.0025);
            if let Drive::Indent {
                heights,
                max_depth,
                steps,
            } = &mut case.drive
            {
                let start = heights.iter().cloned().fold(f64::INFINITY, f64::min);
                *max_depth = start + 3.0 * (*max_depth - start) / 150.0;
                *steps = 3;
            }
            case
        }
        _ => return None,
    })
}

fn run(case: &Case, params: AdhesiveParams) -> Run {
    let operator = Box::new(FreeOperator::new(
        case.grid,
        ElasticMaterial::new(1.0).expect("modulus"),
    ));
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        case.grid,
        1.0,
        case.gamma.clone(),
        params,
    )));
    let mut record = Run::default();
    let start = std::time::Instant::now();
    match &case.drive {
        Drive::Indent {
            heights,
            max_depth,
            steps,
        } => {
            let start_depth = heights.iter().cloned().fold(f64::INFINITY, f64::min);
            let protocol = IndentPulloff {
                start_depth,
                max_depth: *max_depth,
                depth_step: (max_depth - start_depth) / *steps as f64,
                max_retract_steps: 100_000,
                jump_force_threshold: 0.0,
            };
            let mut problem = Problem::new(operator, heights.clone()).expect("a valid problem");
            protocol
                .run(&mut problem, &mut solver, &mut record)
                .expect("indentation");
        }
        Drive::Roll { contact, protocol } => {
            let mut problem = Problem::translating(operator, contact.clone()).expect("a valid problem");
            protocol.run(&mut problem, &mut solver, &mut record).expect("roll");
        }
    }
    record.wall = start.elapsed().as_secs_f64();
    record
}

/// (steps whose sets differ, max |ΔF| / max |F|).
fn compare(a: &Run, b: &Run) -> (usize, f64) {
    let steps = a.sets.len().max(b.sets.len());
    let differing = (0..steps).filter(|&i| a.sets.get(i) != b.sets.get(i)).count();
    if std::env::var("ADHESIM_VERBOSE").is_ok() {
        for i in (0..steps).filter(|&i| a.sets.get(i) != b.sets.get(i)) {
            let size = |r: &Run| r.sets.get(i).map_or(0, |s| s.iter().filter(|&&c| c).count());
            let only_a = a.sets[i].iter().zip(&b.sets[i]).filter(|(x, y)| **x && !**y).count();
            let only_b = a.sets[i].iter().zip(&b.sets[i]).filter(|(x, y)| !**x && **y).count();
            eprintln!(
                "  step {i} ({:?}): sizes {} vs {}, only in first {only_a}, only in second {only_b}",
                a.phases[i],
                size(a),
                size(b)
            );
            if let (Some(pa), Some(pb)) = (a.pressures.get(i), b.pressures.get(i)) {
                let differing: Vec<(f64, f64)> = (0..pa.len())
                    .filter(|&k| a.sets[i][k] != b.sets[i][k])
                    .map(|k| (pa[k], pb[k]))
                    .collect();
                eprintln!("    pressures there (first, second): {differing:?}");
            }
        }
    }
    let scale = a
        .forces
        .iter()
        .fold(0.0f64, |m, f| m.max(f.abs()))
        .max(f64::MIN_POSITIVE);
    let force = a
        .forces
        .iter()
        .zip(&b.forces)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    (differing, force / scale)
}

fn main() {
    let mut check = false;
    let mut tight = false;
    let mut names: Vec<String> = Vec::new();
    for arg in std::env::args().skip(1) {
        if arg == "--check" {
            check = true;
        } else if arg == "--tight" {
            tight = true;
        } else {
            names.push(arg);
        }
    }
    if names.is_empty() {
        names = "sphere8 sphere16 sphere32 fig1_64_75 fig1_64_150 fig1_128_75 fig1_128_150 fig2_h120 fig12_homogeneous fig12_ratio13 fig12_ratio20 fig6_roll"
            .split(' ')
            .map(String::from)
            .collect();
    }
    let base = if tight {
        AdhesiveParams {
            relative_tolerance: 1e-10,
            front_tolerance: 1e-8,
            ..AdhesiveParams::default()
        }
    } else {
        AdhesiveParams::default()
    };
    let reference = AdhesiveParams {
        reference_rule: true,
        ..base
    };
    // Predicted-subset growth on at every size (by default it starts at 256²).
    let fast = AdhesiveParams {
        check_certificates: check,
        predicted_growth: PredictedGrowth::On,
        ..base
    };
    let oracle = AdhesiveParams {
        detachment: Detachment::RandomHalf { seed: 0x5eed },
        ..reference
    };
    println!("case | steps | sets differing (fast, random-half) | max |ΔF|/max|F| (fast, random-half) | FFT pairs/step approach ref→fast | retraction ref→fast | solves/step appr. | CG it./solve | wall ref→fast s");
    let mut failures = 0;
    for name in &names {
        let Some(case) = case(name) else {
            eprintln!("unknown case `{name}`");
            std::process::exit(2);
        };
        let reference_run = run(&case, reference);
        let fast_run = run(&case, fast);
        let oracle_run = run(&case, oracle);
        let (fast_sets, fast_force) = compare(&reference_run, &fast_run);
        let (oracle_sets, oracle_force) = compare(&reference_run, &oracle_run);
        failures += fast_sets + oracle_sets;
        let (ra, rr) = (reference_run.work(true), reference_run.work(false));
        let (fa, fr) = (fast_run.work(true), fast_run.work(false));
        println!(
            "{name} | {} | {fast_sets}, {oracle_sets} | {fast_force:.1e}, {oracle_force:.1e} | {:.1} → {:.1} | {:.1} → {:.1} | {:.2} → {:.2} | {:.2} → {:.2} | {:.2} → {:.2}",
            reference_run.sets.len(),
            ra.1, fa.1, rr.1, fr.1, ra.2, fa.2, ra.3, fa.3, reference_run.wall, fast_run.wall
        );
    }
    if failures > 0 {
        std::process::exit(1);
    }
}
