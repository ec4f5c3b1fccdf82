//! Mid-run checkpoints of an indentation (`IndentPulloff::run_from`): a run stopped after
//! step k and continued from its checkpoint in a fresh operator and solver gives the
//! records and the summary of the uninterrupted run bit for bit. The claim is byte
//! identity of the outputs, so every f64 is compared by its bits (through `{:?}`, which
//! prints the shortest round-trip form and tells −0 from +0), never by tolerance.
//!
//! With the `serde` feature the checkpoint also goes through JSON bytes and back (the form
//! the scenario crate writes); without it, through a clone.

use adhesim::analysis::reference::cohesive_stress_for;
use adhesim::solver::PredictedGrowth;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, Ccg, CcgParams, CohesiveLaw, CohesiveParams, CohesiveSolver, Detachment,
    Dugdale, ElasticMaterial, Exponential, FreeOperator, Grid, IndentCheckpoint, IndentPulloff, NormalSolver, Observer,
    PeriodicKernel, PeriodicOperator, Problem, Profile, ProtocolSummary, Sphere, WavySphere,
};

use crate::checkpoint_common;
use checkpoint_common::{bits, round_trip};

type Taker = checkpoint_common::Taker<IndentCheckpoint>;

/// The Fig. 1 wavy sphere (α ≈ 1, scenarios/fig1.toml's kind) on an n × n free grid.
fn wavy_sphere(n: usize) -> (Grid, Vec<f64>, f64) {
    let grid = Grid::new(n, 0.3 * n as f64 / 48.0, Boundary::Free).unwrap();
    let heights = WavySphere::new(1.0, 5e-4, 0.025, 0.0).unwrap().heights(&grid);
    let start = heights.iter().cloned().fold(f64::INFINITY, f64::min);
    (grid, heights, start)
}

fn protocol(start: f64) -> IndentPulloff {
    IndentPulloff {
        start_depth: start,
        max_depth: 3e-3,
        depth_step: 1e-4,
        max_retract_steps: 10_000,
        jump_force_threshold: 0.0,
    }
}

fn summary_bits(summary: &ProtocolSummary) -> String {
    format!("{summary:?}")
}

/// Runs the wavy sphere of [`check_resumes_on`] on an n × n grid.
fn check_resumes(
    n: usize,
    make: impl Fn(&Grid) -> NormalSolver,
    at: impl Fn(usize, usize) -> Vec<usize>,
) -> (usize, usize) {
    let (grid, heights, start) = wavy_sphere(n);
    check_resumes_on((grid, &heights), &protocol(start), make, at).0
}

/// Runs uninterrupted (with and without checkpoints taken: taking them changes nothing),
/// then continues from each checkpoint in a fresh operator and solver made by `make`.
/// Returns the approach and total steps, and the checkpoints taken.
fn check_resumes_on(
    (grid, heights): (Grid, &[f64]),
    protocol: &IndentPulloff,
    make: impl Fn(&Grid) -> NormalSolver,
    at: impl Fn(usize, usize) -> Vec<usize>,
) -> ((usize, usize), Vec<IndentCheckpoint>) {
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut plain = Vec::new();
    let plain_summary = protocol
        .run(
            &mut Problem::new(Box::new(FreeOperator::new(grid, material)), heights.to_vec()).unwrap(),
            &mut make(&grid),
            &mut plain,
        )
        .unwrap();
    let approach = plain
        .iter()
        .filter(|r| r.phase == Some(adhesim::Phase::Approach))
        .count();
    let mut taker = Taker {
        records: Vec::new(),
        at: at(approach, plain.len()),
        taken: Vec::new(),
    };
    let summary = protocol
        .run(
            &mut Problem::new(Box::new(FreeOperator::new(grid, material)), heights.to_vec()).unwrap(),
            &mut make(&grid),
            &mut taker,
        )
        .unwrap();
    assert_eq!(bits(&taker.records), bits(&plain), "taking checkpoints changed the run");
    assert_eq!(summary_bits(&summary), summary_bits(&plain_summary));
    assert_eq!(taker.taken.len(), taker.at.len(), "a checkpoint after each asked step");
    for checkpoint in &taker.taken {
        let k = checkpoint.steps_done;
        let restored = round_trip(checkpoint);
        let mut rest = Vec::new();
        let resumed = protocol
            .run_from(
                &mut Problem::new(Box::new(FreeOperator::new(grid, material)), heights.to_vec()).unwrap(),
                &mut make(&grid),
                &mut rest,
                Some(&restored),
            )
            .unwrap();
        assert_eq!(bits(&rest), bits(&plain[k..]), "resumed after step {}", k - 1);
        assert_eq!(
            summary_bits(&resumed),
            summary_bits(&plain_summary),
            "summary after step {}",
            k - 1
        );
    }
    ((approach, plain.len()), taker.taken)
}

fn adhesive(params: AdhesiveParams) -> impl Fn(&Grid) -> NormalSolver {
    move |grid: &Grid| {
        NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
            *grid,
            1.0,
            vec![2e-5; grid.len()],
            params,
        )))
    }
}

/// Stops in the approach, right after the deepest step, just after the retraction
/// starts, in mid-retraction and one step before pull-off.
fn spread(approach: usize, total: usize) -> Vec<usize> {
    vec![
        1,
        approach / 2,
        approach,
        approach + 1,
        (approach + total) / 2,
        total - 1,
    ]
}

/// The default adhesive solver (fast certified rule, local peels, bans carried while
/// retracting, failed-ring prediction): every checkpoint resumes bit for bit.
#[test]
fn adhesive_wavy_sphere_resumes_bit_for_bit() {
    let (approach, total) = check_resumes(40, adhesive(AdhesiveParams::default()), spread);
    assert!(approach > 10 && total > approach + 5, "{approach} of {total}");
}

/// The same with predicted-subset growth forced on (its ring records survive the steps)
/// and resumes after every step of the retraction (where bans and failed rings carry over).
#[test]
fn adhesive_with_predicted_growth_resumes_after_every_retraction_step() {
    let params = AdhesiveParams {
        predicted_growth: PredictedGrowth::On,
        ..AdhesiveParams::default()
    };
    check_resumes(32, adhesive(params), |approach, total| (approach..total).collect());
}

/// `Detachment::RandomHalf` releases a random half of the violators: the generator's state
/// is part of the checkpoint.
#[test]
fn random_half_detachment_resumes_bit_for_bit() {
    let params = AdhesiveParams {
        detachment: Detachment::RandomHalf { seed: 7 },
        ..AdhesiveParams::default()
    };
    check_resumes(32, adhesive(params), spread);
}

/// The periodic non-adhesive CCG carries nothing between steps: a checkpoint is its state.
#[test]
fn periodic_ccg_resumes_bit_for_bit() {
    let n = 32;
    let grid = Grid::new(n, 0.2, Boundary::Periodic).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let heights: Vec<f64> = (0..grid.len())
        .map(|k| {
            let (x, y) = grid.centre(k);
            1e-3 * ((x * 31.4).cos() + (y * 31.4).cos() + 2.0)
        })
        .collect();
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 2e-3,
        depth_step: 2e-4,
        max_retract_steps: 100,
        jump_force_threshold: 0.0,
    };
    let make = || NormalSolver::NonAdhesive(Ccg::new(CcgParams::default()));
    let mut plain = Vec::new();
    protocol
        .run(
            &mut Problem::new(
                Box::new(PeriodicOperator::new(grid, material, PeriodicKernel::ElementConsistent)),
                heights.clone(),
            )
            .unwrap(),
            &mut make(),
            &mut plain,
        )
        .unwrap();
    let mut taker = Taker {
        records: Vec::new(),
        at: (1..plain.len()).collect(),
        taken: Vec::new(),
    };
    protocol
        .run(
            &mut Problem::new(
                Box::new(PeriodicOperator::new(grid, material, PeriodicKernel::ElementConsistent)),
                heights.clone(),
            )
            .unwrap(),
            &mut make(),
            &mut taker,
        )
        .unwrap();
    assert_eq!(taker.taken.len(), plain.len() - 1);
    for checkpoint in &taker.taken {
        let mut rest = Vec::new();
        protocol
            .run_from(
                &mut Problem::new(
                    Box::new(PeriodicOperator::new(grid, material, PeriodicKernel::ElementConsistent)),
                    heights.clone(),
                )
                .unwrap(),
                &mut make(),
                &mut rest,
                Some(&round_trip(checkpoint)),
            )
            .unwrap();
        assert_eq!(bits(&rest), bits(&plain[checkpoint.steps_done..]));
    }
}

/// The nested non-adhesive active set of a free grid at n = 64 (one coarse level of 32, so
/// the coarse level's window and operator are in play): its contact windows keep their
/// sides from step to step, and the retraction's unloads restart cold from the last depth,
/// so both are part of its checkpoint. Resumes after every step.
#[test]
fn nested_non_adhesive_resumes_after_every_step() {
    let make = |grid: &Grid| adhesim::protocol::non_adhesive_solver(*grid, ElasticMaterial::new(1.0).unwrap());
    let (grid, heights, start) = wavy_sphere(64);
    assert!(make(&grid).supports_checkpoints());
    let ((approach, total), taken) = check_resumes_on((grid, &heights), &protocol(start), make, |_, total| {
        (1..total).collect()
    });
    assert!(approach > 10 && total > approach, "{approach} of {total}");
    assert_carries_windows(&taken);
}

/// Some checkpoint holds a fine and a coarse contact window and a last depth (else the
/// test would not exercise what the nested solver carries).
fn assert_carries_windows(taken: &[IndentCheckpoint]) {
    let texts: Vec<String> = taken.iter().map(|c| format!("{:?}", c.solver)).collect();
    assert!(
        texts.iter().any(|t| t.contains("fine_window: Some(")
            && t.contains("LevelCheckpoint { window: Some(")
            && t.contains("last_depth: Some(")),
        "no checkpoint with windows: {:?}",
        texts.first()
    );
}

/// The smooth sphere R = E* = 1 on an n × n free grid of side `size`, indented to 2e-3
/// from first contact and pulled off in steps of `depth_step`.
fn smooth_sphere(n: usize, size: f64, depth_step: f64) -> (Grid, Vec<f64>, IndentPulloff) {
    let grid = Grid::new(n, size, Boundary::Free).unwrap();
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 2e-3,
        depth_step,
        max_retract_steps: 10_000,
        jump_force_threshold: 0.0,
    };
    (grid, heights, protocol)
}

/// A cohesive solver of `law` (made for the grid), nested (free grids) or CCG.
fn cohesive(law: impl Fn(&Grid) -> Box<dyn CohesiveLaw>, params: CohesiveParams) -> impl Fn(&Grid) -> NormalSolver {
    move |grid: &Grid| {
        let material = ElasticMaterial::new(1.0).unwrap();
        NormalSolver::Cohesive(Box::new(CohesiveSolver::new(*grid, material, law(grid), params)))
    }
}

fn dugdale(grid: &Grid) -> Box<dyn CohesiveLaw> {
    // Maugis' λ = 0.3 at γ0 = 1e-4 (tests/integration/validation_maugis.rs's fast case).
    let sigma = cohesive_stress_for(1.0, 1.0, 1e-4, 0.3);
    Box::new(Dugdale::new(sigma, vec![1e-4; grid.len()]))
}

fn exponential(grid: &Grid) -> Box<dyn CohesiveLaw> {
    // Tabor's μ = 1 at γ0 = 1e-4: ρ = γ0^(2/3) (tests/integration/validation_exponential.rs).
    Box::new(Exponential::new(1e-8f64.cbrt(), vec![1e-4; grid.len()]))
}

/// Maugis–Dugdale (plain rounds on the zone's active set) at n = 64 with the nested
/// compressive solver: its tractions, the compressive warm start and the nested solver's
/// windows carry from step to step; every checkpoint resumes bit for bit (force, contact,
/// dissipated energy and every other field of every record, and the totals).
#[test]
fn dugdale_smooth_sphere_resumes_bit_for_bit() {
    let (grid, heights, protocol) = smooth_sphere(64, 0.45, 1e-4);
    let make = cohesive(dugdale, CohesiveParams::default());
    let ((approach, total), taken) = check_resumes_on((grid, &heights), &protocol, make, spread);
    assert!(approach > 10 && total > approach + 5, "{approach} of {total}");
    assert!(
        taken.iter().any(|c| c.summary.dissipated_energy != 0.0),
        "a jump dissipated"
    );
    assert_carries_windows(&taken);
}

/// The exponential law (Anderson-mixed rounds, an approach from where its pull is
/// negligible, a pull-off that ends when the tension does) at n = 64: resumes bit for bit
/// at the checkpoints of [`spread`].
#[test]
fn exponential_smooth_sphere_resumes_bit_for_bit() {
    exponential_smooth_sphere_resumes(spread);
}

/// The same after every step of the retraction (each resumed run goes to the pull-off).
#[test]
#[ignore = "15 s: cargo test --release -p adhesim --test integration checkpoint:: -- --ignored"]
fn exponential_smooth_sphere_resumes_bit_for_bit_after_every_retraction_step() {
    exponential_smooth_sphere_resumes(|approach, total| {
        let mut at = vec![1, approach / 2, approach];
        at.extend(approach + 1..total);
        at
    });
}

fn exponential_smooth_sphere_resumes(at: impl Fn(usize, usize) -> Vec<usize>) {
    let (grid, heights, protocol) = smooth_sphere(64, 0.41, 2e-4);
    let make = cohesive(exponential, CohesiveParams::default());
    let ((approach, total), taken) = check_resumes_on((grid, &heights), &protocol, make, at);
    assert!(approach > 10 && total > approach + 5, "{approach} of {total}");
    assert_carries_windows(&taken);
}

/// With the CCG compressive solver (`nested = false`), which carries nothing of its own:
/// the tractions and the compressive warm start suffice.
#[test]
fn dugdale_with_ccg_compressive_solver_resumes_bit_for_bit() {
    let (grid, heights, protocol) = smooth_sphere(32, 0.45, 2e-4);
    let params = CohesiveParams {
        nested: false,
        ..CohesiveParams::default()
    };
    check_resumes_on((grid, &heights), &protocol, cohesive(dugdale, params), spread);
}

/// A maker of a solver for a grid.
type MakeSolver = dyn Fn(&Grid) -> NormalSolver;

/// A checkpoint of one kind of solver put into another is an error naming both, not a
/// panic or a silently different run: cohesive → JKR-type, JKR-type → cohesive, nested
/// non-adhesive → cohesive, and a cohesive law's nested compressive solver → its CCG.
#[test]
fn a_checkpoint_of_another_kind_of_solver_is_refused() {
    let (grid, heights, protocol) = smooth_sphere(64, 0.45, 2e-4);
    let protocol = IndentPulloff {
        max_depth: 1e-3,
        ..protocol
    };
    let material = ElasticMaterial::new(1.0).unwrap();
    let take = |make: &MakeSolver| {
        let mut taker = Taker {
            records: Vec::new(),
            at: vec![3],
            taken: Vec::new(),
        };
        let _ = protocol.run(
            &mut Problem::new(Box::new(FreeOperator::new(grid, material)), heights.clone()).unwrap(),
            &mut make(&grid),
            &mut taker,
        );
        taker.taken.remove(0)
    };
    let nested_cohesive = cohesive(dugdale, CohesiveParams::default());
    let ccg_cohesive = cohesive(
        dugdale,
        CohesiveParams {
            nested: false,
            ..CohesiveParams::default()
        },
    );
    let jkr = adhesive(AdhesiveParams::default());
    let nested = move |grid: &Grid| adhesim::protocol::non_adhesive_solver(*grid, material);
    let cases: [(&MakeSolver, &MakeSolver, &str); 4] = [
        (&nested_cohesive, &jkr, "JKR-type"),
        (&jkr, &nested_cohesive, "cohesive"),
        (&nested, &nested_cohesive, "nested active set"),
        (&nested_cohesive, &ccg_cohesive, "other compressive solver"),
    ];
    for (from, into, says) in cases {
        let checkpoint = round_trip(&take(from));
        let error = protocol
            .run_from(
                &mut Problem::new(Box::new(FreeOperator::new(grid, material)), heights.clone()).unwrap(),
                &mut into(&grid),
                &mut Vec::new(),
                Some(&checkpoint),
            )
            .unwrap_err();
        let text = error.to_string();
        assert!(text.contains("checkpoint") && text.contains(says), "{text}");
    }
}

/// A checkpoint of another grid is refused with an error, not a panic.
#[test]
fn a_checkpoint_of_another_grid_is_refused() {
    let (grid, heights, start) = wavy_sphere(32);
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut taker = Taker {
        records: Vec::new(),
        at: vec![3],
        taken: Vec::new(),
    };
    let protocol = IndentPulloff {
        max_depth: start + 5e-4,
        ..protocol(start)
    };
    let make = adhesive(AdhesiveParams::default());
    protocol
        .run(
            &mut Problem::new(Box::new(FreeOperator::new(grid, material)), heights.clone()).unwrap(),
            &mut make(&grid),
            &mut taker,
        )
        .unwrap();
    let (other, other_heights, _) = wavy_sphere(16);
    let error = protocol
        .run_from(
            &mut Problem::new(Box::new(FreeOperator::new(other, material)), other_heights.clone()).unwrap(),
            &mut make(&other),
            &mut Vec::new(),
            Some(&taker.taken[0]),
        )
        .unwrap_err();
    assert!(error.to_string().contains("checkpoint"), "{error}");
}

/// The reference rule (exact peels, no local release rounds, which would clear the ring
/// records) in quarter steps to half the depth, and 20 retraction steps (the run ends there
/// with `ContactNotLost`, after the records): between the jumps of the wavy front the
/// contact stays put while the same trial ring fails, and the failed-ring prediction of
/// quiet steps (from the records of the last two steps, which a checkpoint must carry: the
/// test fails without them) saves the solves the records count.
#[test]
fn quiet_steps_predicted_from_failed_ring_records_resume_bit_for_bit() {
    let params = AdhesiveParams {
        reference_rule: true,
        ..AdhesiveParams::default()
    };
    let (grid, heights, start) = wavy_sphere(32);
    let material = ElasticMaterial::new(1.0).unwrap();
    let protocol = IndentPulloff {
        depth_step: 2.5e-5,
        max_depth: 1.5e-3,
        max_retract_steps: 20,
        ..protocol(start)
    };
    let make = adhesive(params);
    let run = |observer: &mut dyn Observer, start: Option<&IndentCheckpoint>| {
        let mut problem = Problem::new(Box::new(FreeOperator::new(grid, material)), heights.clone()).unwrap();
        let _ = protocol.run_from(&mut problem, &mut make(&grid), observer, start);
    };
    let mut plain = Vec::new();
    run(&mut plain, None);
    assert!(plain.len() > 60, "{} steps", plain.len());
    let mut taker = Taker {
        records: Vec::new(),
        at: (1..plain.len()).collect(),
        taken: Vec::new(),
    };
    run(&mut taker, None);
    assert_eq!(bits(&taker.records), bits(&plain));
    for checkpoint in &taker.taken {
        let mut rest = Vec::new();
        run(&mut rest, Some(&round_trip(checkpoint)));
        let k = checkpoint.steps_done;
        assert_eq!(bits(&rest), bits(&plain[k..]), "after step {}", k - 1);
    }
}
