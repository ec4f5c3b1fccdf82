//! Tangential motion: the frictionless controls of paper Sect. 3 and the energy balance
//! F_T = dissipated energy per distance.

use adhesim::analysis::reference::Jkr;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ElasticMaterial, FreeOperator, Grid, Kinematics, NormalSolver, Problem,
    TranslatingContact, Translation, TranslationSummary, WavySphere,
};

const GAMMA: f64 = 2e-5;
const WAVELENGTH: f64 = 0.05;
/// α = √(2λγ0/(π²h²E*)) = 0.6: the rough regime where boundary friction is large.
const AMPLITUDE: f64 = 7.5e-4;

fn run(amplitude: f64, kinematics: Kinematics, steps: usize) -> (TranslationSummary, Jkr) {
    run_with(amplitude, WAVELENGTH, 64, kinematics, steps)
}

fn run_with(
    amplitude: f64,
    wavelength: f64,
    n: usize,
    kinematics: Kinematics,
    steps: usize,
) -> (TranslationSummary, Jkr) {
    let grid = Grid::new(n, 0.4, Boundary::Free).unwrap();
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let indenter = WavySphere::new(1.0, amplitude, wavelength, 0.0).unwrap();
    let contact = TranslatingContact::new(indenter, kinematics);
    let mut problem = Problem::translating(Box::new(operator), contact).unwrap();
    let jkr = Jkr {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion: GAMMA,
    };
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        1.0,
        vec![GAMMA; grid.len()],
        AdhesiveParams::default(),
    )));
    let protocol = Translation {
        start_depth: -amplitude,
        depth: 3.0 * jkr.critical_depth().abs(),
        approach_steps: 60,
        // two wavelengths: the rolling state is periodic in X with period λ, so the
        // averages over the second half cover exactly one period
        distance: 2.0 * wavelength,
        steps,
        return_stroke: false,
        stationary_from: 0.5,
        jump_force_threshold: 0.0,
    };
    let summary = protocol.run(&mut problem, &mut solver, &mut ()).unwrap();
    (summary, jkr)
}

/// Translating the whole rough profile over a smooth half-space is translation invariant:
/// no friction (paper Sect. 3). Rolling a smooth sphere: friction only from the lattice's
/// own small hysteresis (γ2 − γ1 ≈ 0.003γ0 at this resolution). Both per-step mean
/// tangential forces are below 2 % of the boundary-friction scale 2a·γ0 — the F_T that a
/// hysteresis γ2 − γ1 = γ0 would give (Eq. 12) — while rough rolling at α ≈ 0.6 is above
/// 5 % of it (measured: translate 0.4 %, smooth roll 0.3 %, rough roll 13 %; results
/// revision 1: 0.7 %, 0.3 %, 8 %).
#[test]
fn frictionless_controls() {
    let (translate, _) = run(AMPLITUDE, Kinematics::Translate, 100);
    let scale = 2.0 * translate.mean_half_width * GAMMA;
    assert!(
        translate.mean_tangential_force.abs() < 0.02 * scale,
        "translate: F_T = {:.3e}, scale {scale:.3e}",
        translate.mean_tangential_force
    );
    let (smooth, _) = run(0.0, Kinematics::Roll, 100);
    let scale = 2.0 * smooth.mean_half_width * GAMMA;
    assert!(
        smooth.mean_tangential_force.abs() < 0.02 * scale,
        "smooth roll: F_T = {:.3e}, scale {scale:.3e}",
        smooth.mean_tangential_force
    );
    let (rough, _) = run(AMPLITUDE, Kinematics::Roll, 100);
    assert!(
        rough.mean_tangential_force > 0.05 * scale,
        "rough roll: F_T = {:.3e}",
        rough.mean_tangential_force
    );
}

/// Energy balance of steady rolling over one period of the waviness: the work-based mean
/// tangential force equals the energy released per travelled distance within 10 % (they
/// differ by the change of stored energy between the ends of the window, which vanishes
/// in an exactly periodic steady state).
#[test]
fn tangential_force_equals_dissipation_per_distance() {
    let (rough, _) = run(AMPLITUDE, Kinematics::Roll, 200);
    let ratio = rough.dissipation_per_distance / rough.mean_tangential_force_work;
    assert!((ratio - 1.0).abs() < 0.1, "ratio {ratio:.3}");
}
