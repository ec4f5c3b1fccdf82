//! The fast adhesive step (docs/fast-step.md) against the reference rule: certified early
//! stops of the fixed-set CG and certified local release rounds must leave every step's
//! contact set unchanged, and so must a different release order (random half of the
//! violators per round), the independent oracle of the order-independence argument
//! (docs/physics.md §2.4a), and so must the fixed-set CG on the contact's bounding box
//! (`AdhesiveParams::contact_window`). The full case list runs with
//! `cargo run --release -p adhesim --example step_equivalence`.
use adhesim::solver::PredictedGrowth;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Attachment, Boundary, Detachment, ElasticMaterial, FreeOperator, Grid,
    IndentPulloff, NormalSolver, Phase, Problem, Profile, Sphere, WavySphere,
};
use std::num::NonZeroUsize;

/// Contact sets and forces of every step of an indentation–pull-off cycle.
struct Cycle {
    sets: Vec<Vec<bool>>,
    phases: Vec<Option<Phase>>,
    forces: Vec<f64>,
    fft_pairs: u64,
    /// Rings grown through a predicted subset, and predictions that fell back.
    predicted_growth: (u64, u64),
    /// Transform pairs of the fixed-set CGs on contact windows.
    window_pairs: u64,
}

impl adhesim::Observer for Cycle {
    fn on_step(&mut self, view: adhesim::StepView<'_>) -> std::ops::ControlFlow<()> {
        self.sets.push(view.state.contact.clone());
        self.phases.push(view.record.phase);
        self.forces.push(view.record.force_normal);
        self.fft_pairs += view.record.report.operator_applications;
        std::ops::ControlFlow::Continue(())
    }
}

/// Runs an indentation–pull-off cycle to `max_depth` in `steps` approach steps with
/// `observer`; returns the solver (for its counters).
fn run_cycle(
    grid: Grid,
    heights: &[f64],
    (gamma, max_depth, steps): (f64, f64, usize),
    params: AdhesiveParams,
    observer: &mut dyn adhesim::Observer,
) -> NormalSolver {
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let mut problem = Problem::new(Box::new(operator), heights.to_vec()).unwrap();
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        1.0,
        vec![gamma; grid.len()],
        params,
    )));
    let start_depth = heights.iter().cloned().fold(f64::INFINITY, f64::min);
    let protocol = IndentPulloff {
        start_depth,
        max_depth,
        depth_step: (max_depth - start_depth) / steps as f64,
        max_retract_steps: 10_000,
        jump_force_threshold: 0.0,
    };
    protocol.run(&mut problem, &mut solver, observer).unwrap();
    solver
}

fn cycle(grid: Grid, heights: &[f64], gamma: f64, max_depth: f64, steps: usize, params: AdhesiveParams) -> Cycle {
    let mut record = Cycle {
        sets: Vec::new(),
        phases: Vec::new(),
        forces: Vec::new(),
        fft_pairs: 0,
        predicted_growth: (0, 0),
        window_pairs: 0,
    };
    let solver = run_cycle(grid, heights, (gamma, max_depth, steps), params, &mut record);
    if let NormalSolver::Adhesive(adhesive) = &solver {
        record.predicted_growth = adhesive.predicted_growth();
        record.window_pairs = adhesive.window_applications();
    }
    record
}

/// Same sets at every step; forces equal to 1e-5 of the largest |F| (both runs stop the CG
/// at a relative residual of 1e-6 on different iterates, so forces differ at that level).
fn assert_same(reference: &Cycle, other: &Cycle, label: &str) {
    assert_eq!(reference.sets.len(), other.sets.len(), "{label}: number of steps");
    let scale = reference.forces.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    for (step, (a, b)) in reference.sets.iter().zip(&other.sets).enumerate() {
        assert!(a == b, "{label}: contact sets differ at step {step}");
        let (fa, fb) = (reference.forces[step], other.forces[step]);
        assert!(
            (fa - fb).abs() <= 1e-5 * scale,
            "{label}: step {step} force {fa:e} vs {fb:e}"
        );
    }
}

/// Tolerances under which a decision inside the default CG error band (a tie at the
/// reference's precision, docs/fast-step.md) cannot occur on these small cases.
fn tight() -> AdhesiveParams {
    AdhesiveParams {
        relative_tolerance: 1e-10,
        front_tolerance: 1e-8,
        ..AdhesiveParams::default()
    }
}

/// The fast rule (with its certificates checked) against the reference rule at the default
/// tolerances; the random-half order against the reference rule at tight tolerances: a
/// different order may meet an element whose tension lies within the reference's CG error
/// band of σ_c in a different set, and decide that tie otherwise.
fn all_modes(grid: Grid, heights: &[f64], gamma: f64, max_depth: f64, steps: usize) {
    let run = |params| cycle(grid, heights, gamma, max_depth, steps, params);
    let reference = run(AdhesiveParams {
        reference_rule: true,
        ..AdhesiveParams::default()
    });
    // check_certificates panics if a certified bound or decision is wrong.
    let fast = run(AdhesiveParams {
        check_certificates: true,
        predicted_growth: PredictedGrowth::On,
        ..AdhesiveParams::default()
    });
    assert_same(&reference, &fast, "fast");
    // Predicted-subset growth (docs/fast-step.md §3) and the CG's contact windows took
    // part in the fast run; without windows, every CG on the whole grid, the same sets.
    assert!(fast.predicted_growth.0 > 0, "{:?}", fast.predicted_growth);
    assert!(fast.window_pairs > 0, "no CG ran on a window");
    let whole_grid = run(AdhesiveParams {
        check_certificates: true,
        predicted_growth: PredictedGrowth::On,
        contact_window: false,
        ..AdhesiveParams::default()
    });
    assert_same(&reference, &whole_grid, "whole grid");
    assert_eq!(whole_grid.window_pairs, 0);
    let plain = run(AdhesiveParams::default());
    assert!(
        plain.fft_pairs < reference.fft_pairs,
        "{} ≥ {}",
        plain.fft_pairs,
        reference.fft_pairs
    );
    let tight_reference = run(AdhesiveParams {
        reference_rule: true,
        ..tight()
    });
    let oracle = run(AdhesiveParams {
        detachment: Detachment::RandomHalf { seed: 7 },
        ..tight()
    });
    assert_same(&tight_reference, &oracle, "random half");
}

/// Smooth sphere, a_JKR/Δ = 8, to 3|d_JKR| and back.
#[test]
fn smooth_sphere_sets_are_unchanged() {
    let a_jkr: f64 = 0.05;
    let gamma = a_jkr.powi(3) * 8.0 / (9.0 * std::f64::consts::PI);
    let d_jkr = (3.0 * std::f64::consts::PI.powi(2) * gamma * gamma / 64.0).cbrt();
    let grid = Grid::new(32, 32.0 * a_jkr / 8.0, Boundary::Free).unwrap();
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    all_modes(grid, &heights, gamma, 3.0 * d_jkr, 40);
}

/// The Fig. 1 wavy sphere (α = 1) at n = 48, to 6|d_JKR| and back: trial rings, cascades
/// and jumps.
#[test]
fn wavy_sphere_sets_are_unchanged() {
    let gamma = 6.168_502_750_680_85e-4;
    let d_jkr = (3.0 * std::f64::consts::PI.powi(2) * gamma * gamma / 64.0).cbrt();
    let grid = Grid::new(48, 0.6, Boundary::Free).unwrap();
    let heights = WavySphere::new(1.0, 0.0025, 0.05, 0.0).unwrap().heights(&grid);
    all_modes(grid, &heights, gamma, 6.0 * d_jkr, 30);
}

/// Two layers per trial ring (`AdhesiveParams::trial_ring_layers` = 2, a different closure
/// rule measured in BENCHMARKS.md §What did not pay) on the wavy sphere of the test above: the
/// fast rule, its certificates checked, reaches the reference rule's sets under that rule too
/// (the trial test of the certified stops must see the same two-step reach as the candidates,
/// or a step would end on an unconverged state), and the approach contact is never smaller than
/// with one layer (F2, docs/fast-step.md §1: the inner layer is tested with the outer one
/// attached) and larger at some step (the option takes effect).
#[test]
fn two_layer_rings_keep_the_fast_rule_exact() {
    let gamma = 6.168_502_750_680_85e-4;
    let d_jkr = (3.0 * std::f64::consts::PI.powi(2) * gamma * gamma / 64.0).cbrt();
    let grid = Grid::new(48, 0.6, Boundary::Free).unwrap();
    let heights = WavySphere::new(1.0, 0.0025, 0.05, 0.0).unwrap().heights(&grid);
    let run = |params| cycle(grid, &heights, gamma, 6.0 * d_jkr, 30, params);
    let two = NonZeroUsize::new(2).unwrap();
    let reference = run(AdhesiveParams {
        reference_rule: true,
        trial_ring_layers: two,
        ..AdhesiveParams::default()
    });
    let fast = run(AdhesiveParams {
        check_certificates: true,
        trial_ring_layers: two,
        ..AdhesiveParams::default()
    });
    assert_same(&reference, &fast, "two layers, fast");
    let one = run(AdhesiveParams {
        reference_rule: true,
        ..AdhesiveParams::default()
    });
    let size = |set: &Vec<bool>| set.iter().filter(|&&c| c).count();
    let mut larger = 0;
    for (step, phase) in one.phases.iter().enumerate() {
        if *phase != Some(Phase::Approach) {
            break;
        }
        let (one_layer, two_layers) = (size(&one.sets[step]), size(&reference.sets[step]));
        assert!(
            two_layers >= one_layer,
            "approach step {step}: {two_layers} elements with two layers, {one_layer} with one"
        );
        larger += usize::from(two_layers > one_layer);
    }
    assert!(larger > 0, "two layers never attached more than one");
}

/// Options without a test elsewhere: worst-first releases and penetration-only attachment
/// run a cycle on the smooth sphere; worst-first reaches the same sets (any release order
/// gives the same stable set), penetration-only attaches later on the approach (its
/// largest contact is not larger than with trial attachment).
#[test]
fn worst_first_and_penetration_only_options() {
    let a_jkr: f64 = 0.05;
    let gamma = a_jkr.powi(3) * 8.0 / (9.0 * std::f64::consts::PI);
    let d_jkr = (3.0 * std::f64::consts::PI.powi(2) * gamma * gamma / 64.0).cbrt();
    let grid = Grid::new(32, 32.0 * a_jkr / 8.0, Boundary::Free).unwrap();
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let reference = cycle(
        grid,
        &heights,
        gamma,
        3.0 * d_jkr,
        40,
        AdhesiveParams {
            reference_rule: true,
            ..AdhesiveParams::default()
        },
    );
    let worst = cycle(
        grid,
        &heights,
        gamma,
        3.0 * d_jkr,
        40,
        AdhesiveParams {
            detachment: Detachment::WorstFirst { fraction: 0.01 },
            ..AdhesiveParams::default()
        },
    );
    assert_same(&reference, &worst, "worst first");
    let penetration = cycle(
        grid,
        &heights,
        gamma,
        3.0 * d_jkr,
        40,
        AdhesiveParams {
            attachment: Attachment::PenetrationOnly,
            ..AdhesiveParams::default()
        },
    );
    let largest = |c: &Cycle| c.sets.iter().map(|s| s.iter().filter(|&&x| x).count()).max().unwrap();
    assert!(
        largest(&penetration) <= largest(&reference),
        "{} > {}",
        largest(&penetration),
        largest(&reference)
    );
}

/// The displacement of every step's state is K p on the whole grid: outside the CG's
/// window it lags during a step (docs/physics.md §3.2) and must be brought up before the
/// step ends. Checked on the wavy sphere's cycle, in which windows, cascades and predicted
/// growth all run, against K p applied in double precision. The tolerance, 1e-7 of the
/// largest |u|, covers the single-precision updates of u within a step (≈ 6e-8 of each
/// change, measured 1.2e-8 in all); the smallest lag a step could end with, the change of
/// its last, polishing CG, is 6.4e-7 here. And no free element penetrates.
#[test]
fn a_step_ends_with_the_displacement_of_its_pressure_everywhere() {
    struct Consistency<'a> {
        operator: FreeOperator,
        heights: &'a [f64],
        exact: Vec<f64>,
        worst: f64,
        deepest: f64,
        steps: usize,
    }
    impl adhesim::Observer for Consistency<'_> {
        fn on_step(&mut self, view: adhesim::StepView<'_>) -> std::ops::ControlFlow<()> {
            use adhesim::ElasticOperator;
            self.operator.apply(&view.state.pressure, &mut self.exact);
            let scale = self.exact.iter().fold(0.0f64, |m, u| m.max(u.abs()));
            let error = (view.state.displacement.iter().zip(&self.exact))
                .fold(0.0f64, |m, (u, exact)| m.max((u - exact).abs()));
            self.worst = self.worst.max(error / scale.max(f64::MIN_POSITIVE));
            for (k, &height) in self.heights.iter().enumerate() {
                if !view.state.contact[k] && height.is_finite() {
                    let gap = height - view.record.depth + self.exact[k];
                    self.deepest = self.deepest.min(gap / scale.max(f64::MIN_POSITIVE));
                }
            }
            self.steps += 1;
            std::ops::ControlFlow::Continue(())
        }
    }
    let gamma = 6.168_502_750_680_85e-4;
    let d_jkr = (3.0 * std::f64::consts::PI.powi(2) * gamma * gamma / 64.0).cbrt();
    let grid = Grid::new(48, 0.6, Boundary::Free).unwrap();
    let heights = WavySphere::new(1.0, 0.0025, 0.05, 0.0).unwrap().heights(&grid);
    let params = AdhesiveParams {
        predicted_growth: PredictedGrowth::On,
        ..AdhesiveParams::default()
    };
    let mut check = Consistency {
        operator: FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap()),
        heights: &heights,
        exact: vec![0.0; grid.len()],
        worst: 0.0,
        deepest: 0.0,
        steps: 0,
    };
    let solver = run_cycle(grid, &heights, (gamma, 6.0 * d_jkr, 30), params, &mut check);
    let NormalSolver::Adhesive(adhesive) = &solver else {
        unreachable!()
    };
    assert!(adhesive.window_applications() > 0, "no CG ran on a window");
    assert!(check.steps > 40, "{} steps", check.steps);
    assert!(
        check.worst <= 1e-7,
        "u differs from K p by {:e} of max |u|",
        check.worst
    );
    // No free element penetrates at the end of a step (the growth read current gaps).
    assert!(check.deepest >= -1e-7, "a free gap of {:e} of max |u|", check.deepest);
    println!(
        "largest |u − K p| / max |u| over {} steps: {:e}; deepest free gap / max |u|: {:e}",
        check.steps, check.worst, check.deepest
    );
}
