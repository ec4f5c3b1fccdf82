//! Mid-run checkpoints of a translation (`Translation::run_from`): a roll or slide stopped
//! after step k and continued from its checkpoint in a fresh operator and solver gives the
//! records and the summary of the uninterrupted run bit for bit (compared through `{:?}`,
//! which prints every f64's shortest round-trip form, never by tolerance).
//!
//! With the `serde` feature the checkpoint also goes through JSON bytes and back (the form
//! the scenario crate writes); without it, through a clone.

use adhesim::solver::PredictedGrowth;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, CohesiveParams, CohesiveSolver, ElasticMaterial, Exponential,
    FreeOperator, Grid, Kinematics, NormalSolver, Problem, TranslatingContact, Translation, TranslationCheckpoint,
    WavySphere,
};

use crate::checkpoint_common;
use checkpoint_common::{bits, round_trip};

type Taker = checkpoint_common::Taker<TranslationCheckpoint>;

const GAMMA: f64 = 2e-5;

/// A wavy sphere at α ≈ 0.6 (the rough rolling regime of
/// tests/integration/validation_translation.rs) on an n × n free grid, moved by
/// `kinematics` over one wavelength after 12 approach steps.
fn setup(n: usize, kinematics: Kinematics) -> (Grid, TranslatingContact, Translation) {
    let grid = Grid::new(n, 0.4, Boundary::Free).unwrap();
    let amplitude = 7.5e-4;
    let contact = TranslatingContact::new(WavySphere::new(1.0, amplitude, 0.05, 0.0).unwrap(), kinematics);
    let protocol = Translation {
        start_depth: -amplitude,
        depth: 2e-3,
        approach_steps: 12,
        distance: 0.05,
        steps: 16,
        return_stroke: false,
        stationary_from: 0.5,
        jump_force_threshold: 0.0,
    };
    (grid, contact, protocol)
}

type MakeSolver = dyn Fn(&Grid) -> NormalSolver;

fn adhesive(predicted_growth: PredictedGrowth) -> impl Fn(&Grid) -> NormalSolver {
    move |grid: &Grid| {
        let params = AdhesiveParams {
            predicted_growth,
            ..AdhesiveParams::default()
        };
        NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
            *grid,
            1.0,
            vec![GAMMA; grid.len()],
            params,
        )))
    }
}

/// Runs uninterrupted (with and without checkpoints: taking them changes nothing), then
/// continues from each checkpoint in a fresh operator and solver made by `make`. Returns
/// the number of steps and the checkpoints taken.
fn check_resumes(n: usize, kinematics: Kinematics, make: &MakeSolver) -> (usize, Vec<TranslationCheckpoint>) {
    let (grid, contact, protocol) = setup(n, kinematics);
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut plain = Vec::new();
    let plain_summary = protocol
        .run(
            &mut Problem::translating(Box::new(FreeOperator::new(grid, material)), contact.clone()).unwrap(),
            &mut make(&grid),
            &mut plain,
        )
        .unwrap();
    let total = plain.len();
    // In the approach, at its end, the first moving steps, the stationary part, the last
    // step but one.
    let at = vec![1, 6, 12, 13, 14, 21, total - 1];
    let mut taker = Taker {
        records: Vec::new(),
        at: at.clone(),
        taken: Vec::new(),
    };
    let summary = protocol
        .run(
            &mut Problem::translating(Box::new(FreeOperator::new(grid, material)), contact.clone()).unwrap(),
            &mut make(&grid),
            &mut taker,
        )
        .unwrap();
    assert_eq!(bits(&taker.records), bits(&plain), "taking checkpoints changed the run");
    assert_eq!(format!("{summary:?}"), format!("{plain_summary:?}"));
    assert_eq!(taker.taken.len(), at.len(), "a checkpoint after each asked step");
    for checkpoint in &taker.taken {
        let k = checkpoint.steps_done;
        let mut rest = Vec::new();
        let resumed = protocol
            .run_from(
                &mut Problem::translating(Box::new(FreeOperator::new(grid, material)), contact.clone()).unwrap(),
                &mut make(&grid),
                &mut rest,
                Some(&round_trip(checkpoint)),
            )
            .unwrap();
        assert_eq!(bits(&rest), bits(&plain[k..]), "resumed after step {}", k - 1);
        assert_eq!(
            format!("{resumed:?}"),
            format!("{plain_summary:?}"),
            "after step {}",
            k - 1
        );
    }
    (total, taker.taken)
}

/// Rolling with the JKR-type solver, with and without predicted-subset growth (whose
/// ring history the checkpoint must carry).
#[test]
fn adhesive_roll_resumes_bit_for_bit() {
    for growth in [PredictedGrowth::Off, PredictedGrowth::On] {
        let (total, taken) = check_resumes(48, Kinematics::Roll, &adhesive(growth));
        assert_eq!(total, 28);
        // The stationary part's records travel with the checkpoint.
        assert!(taken.iter().any(|c| !c.stationary.is_empty()));
    }
}

/// Sliding on a wavy substrate (rotated by 30°): the tangential force before a change is
/// measured inside the solve.
#[test]
fn adhesive_slide_resumes_bit_for_bit() {
    let slide = Kinematics::Slide {
        substrate_angle: 30f64.to_radians(),
    };
    let (_, taken) = check_resumes(48, slide, &adhesive(PredictedGrowth::Off));
    assert!(taken.iter().all(|c| c.summary.solves > 0));
}

/// Rolling under the exponential cohesive law: the checkpoint carries its tractions and
/// its compressive solver's history.
#[test]
fn exponential_roll_resumes_bit_for_bit() {
    let make = |grid: &Grid| {
        let law = Exponential::new(1e-3, vec![GAMMA; grid.len()]);
        NormalSolver::Cohesive(Box::new(CohesiveSolver::new(
            *grid,
            ElasticMaterial::new(1.0).unwrap(),
            Box::new(law),
            CohesiveParams::default(),
        )))
    };
    check_resumes(32, Kinematics::Roll, &make);
}

/// A checkpoint of another grid, of a run with fewer steps or of another kind of solver
/// is refused with an error naming the checkpoint, not a panic.
#[test]
fn a_checkpoint_that_does_not_fit_is_refused() {
    let (grid, contact, protocol) = setup(32, Kinematics::Roll);
    let material = ElasticMaterial::new(1.0).unwrap();
    let make = adhesive(PredictedGrowth::Off);
    let mut taker = Taker {
        records: Vec::new(),
        at: vec![20],
        taken: Vec::new(),
    };
    protocol
        .run(
            &mut Problem::translating(Box::new(FreeOperator::new(grid, material)), contact.clone()).unwrap(),
            &mut make(&grid),
            &mut taker,
        )
        .unwrap();
    let checkpoint = taker.taken.remove(0);
    let (other, ..) = setup(16, Kinematics::Roll);
    let shorter = Translation { steps: 4, ..protocol };
    let non_adhesive = move |grid: &Grid| adhesim::protocol::non_adhesive_solver(*grid, material);
    let runs: [(Grid, &Translation, &MakeSolver); 3] = [
        (other, &protocol, &make),
        (grid, &shorter, &make),
        (grid, &protocol, &non_adhesive),
    ];
    for (grid, protocol, make) in runs {
        let error = protocol
            .run_from(
                &mut Problem::translating(Box::new(FreeOperator::new(grid, material)), contact.clone()).unwrap(),
                &mut make(&grid),
                &mut Vec::new(),
                Some(&checkpoint),
            )
            .unwrap_err();
        assert!(error.to_string().contains("checkpoint"), "{error}");
    }
}
