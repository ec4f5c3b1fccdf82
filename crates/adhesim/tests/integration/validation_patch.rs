//! Elements without adhesion (γ = 0) in the adhesive solver (docs/physics.md §2.2): they
//! detach under any tension and attach only by penetration. Checked on an adhesive
//! circular patch on a non-adhesive background (closed form below) and on a quadratic γ
//! field that reaches 0, in the fast rule and the reference rule.
#![allow(clippy::needless_range_loop)]

use adhesim::analysis::reference::{FlatPunchReference, Hertz, Jkr};
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Axis, Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial,
    FreeOperator, Grid, IndentPulloff, NormalSolver, Observer, Problem, Profile, ProtocolSummary, Sphere, StepView,
    WorkOfAdhesion,
};
use std::ops::ControlFlow;

/// Watches every step: contact outside the adhesive patch, the largest contact, and
/// whether every force stayed finite.
struct PatchWatch {
    patch: Vec<bool>,
    outside_patch: usize,
    largest_contact: usize,
    all_finite: bool,
}

impl Observer for PatchWatch {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        let contact = &view.state.contact;
        let outside = (0..contact.len()).filter(|&k| contact[k] && !self.patch[k]).count();
        self.outside_patch = self.outside_patch.max(outside);
        self.largest_contact = self.largest_contact.max(view.record.contact_elements);
        self.all_finite &= view.record.force_normal.is_finite()
            && view.record.report.dissipated_energy.is_finite()
            && view.state.pressure.iter().all(|p| p.is_finite());
        ControlFlow::Continue(())
    }
}

const N: usize = 64;
const SPHERE_RADIUS: f64 = 1.0;
const GAMMA: f64 = 0.012;

/// Sphere (R = 1, E* = 1) on an adhesive disc of radius b = 16Δ (γ = 0.012) on a γ = 0
/// background, pressed to d = 0.03 (Hertz radius √(Rd) = 0.17 < b, so nothing outside
/// the patch penetrates) and pulled off.
fn patch_pull_off(params: AdhesiveParams) -> (ProtocolSummary, PatchWatch, f64) {
    let delta = 1.0 / N as f64;
    let patch_radius = 16.0 * delta;
    let grid = Grid::new(N, 1.0, Boundary::Free).unwrap();
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = Sphere::new(SPHERE_RADIUS).unwrap().heights(&grid);
    let patch: Vec<bool> = (0..grid.len())
        .map(|k| {
            let (x, y) = grid.centre(k);
            x.hypot(y) < patch_radius
        })
        .collect();
    let gamma = patch.iter().map(|&inside| if inside { GAMMA } else { 0.0 }).collect();
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(grid, 1.0, gamma, params)));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 0.03,
        depth_step: 2.5e-4,
        max_retract_steps: 2_000,
        jump_force_threshold: 0.0,
    };
    let mut watch = PatchWatch {
        patch,
        outside_patch: 0,
        largest_contact: 0,
        all_finite: true,
    };
    let mut problem = Problem::new(Box::new(operator), heights.clone()).unwrap();
    let summary = protocol.run(&mut problem, &mut solver, &mut watch).unwrap();
    (summary, watch, patch_radius)
}

/// Pinned contact. With the contact held at radius b, the state at depth d is Hertz's at
/// b plus a flat punch of radius b (Johnson, Kendall & Roberts 1971; Boussinesq):
/// F = 4E*b³/(3R) + 2E*b(d − b²/R), with the edge's energy release rate
/// G = E*(b²/R − d)²/(2πb). Adhesion cannot spread the contact beyond b (γ = 0 there), and
/// it stays pinned while G < γ: it lets go at G = γ, d = b²/R − √(2πbγ/E*), with
/// F = 4E*b³/(3R) − √(8πE*γb³) (Kendall 1971's flat punch plus the Hertz load of the cap;
/// Maugis 2000, *Contact, Adhesion and Rupture of Elastic Solids*, the JKR branch at
/// a = b). For b below the JKR radius of largest tension a_F = (9πγR²/(8E*))^{1/3} = 0.35
/// the JKR branch below b carries less tension, so this is the pull-off force, 16 % below
/// JKR's (3/2)πγR. Tolerance: 5 % of the flat-punch term √(8πE*γb³), the mesh error of
/// Kendall's force with a 16Δ rim in validation_punch.rs (the rim's staircase dominates;
/// Hertz at 16Δ is within 1 %, zero_adhesion_everywhere_is_non_adhesive_contact below).
/// Measured: 1.0 % of the punch term (1.5 % of F) in both rules.
fn check_patch(params: AdhesiveParams) {
    let (summary, watch, patch_radius) = patch_pull_off(params);
    let patch_elements = watch.patch.iter().filter(|&&inside| inside).count();
    assert_eq!(watch.outside_patch, 0, "contact spread beyond the adhesive patch");
    assert_eq!(watch.largest_contact, patch_elements, "the contact fills the patch");
    assert!(watch.all_finite);
    let jkr = Jkr {
        radius: SPHERE_RADIUS,
        contact_modulus: 1.0,
        work_of_adhesion: GAMMA,
    };
    assert!(patch_radius < jkr.critical_radius());
    let pinned = -jkr.force(patch_radius);
    let punch_term = -FlatPunchReference {
        radius: patch_radius,
        contact_modulus: 1.0,
    }
    .kendall_force(GAMMA)
    .abs();
    let error = (summary.max_adhesive_force - pinned).abs() / punch_term.abs();
    assert!(
        error < 0.05,
        "pull-off {:.5} vs pinned {pinned:.5} (JKR {:.5}): error {error:.4} of the punch term",
        summary.max_adhesive_force,
        -jkr.critical_force()
    );
    assert!(summary.pull_off_depth.is_some());
}

#[test]
fn adhesive_patch_on_non_adhesive_background_pins_the_contact() {
    check_patch(AdhesiveParams::default());
}

#[test]
fn adhesive_patch_reference_rule() {
    check_patch(AdhesiveParams {
        reference_rule: true,
        ..AdhesiveParams::default()
    });
}

/// A quadratic γ field with edge ratio 1e-20 along x: 1 + (1e-20 − 1)s² is exactly 0 at
/// s = ±1, put on the outermost columns, so γ falls from γ_middle to 0 (a field that
/// reaches 0 from above; negative values are input errors). A sphere (R = 1, E* = 1,
/// γ_middle = 0.01) is pressed until its contact reaches those columns (√(Rd) = 0.55 >
/// L/2) and pulled off.
fn sphere_on_quadratic_to_zero(params: AdhesiveParams) -> (ProtocolSummary, PatchWatch, usize) {
    let n = 32;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = Sphere::new(SPHERE_RADIUS).unwrap().heights(&grid);
    let outermost = (0..grid.len()).map(|k| grid.centre(k).0.abs()).fold(0.0, f64::max);
    let field = WorkOfAdhesion::Quadratic {
        middle: QUADRATIC_MIDDLE,
        ratio_end_to_middle: 1e-20,
        half_length: outermost,
        axis: Axis::X,
    };
    let values = field.on_grid(&grid).unwrap();
    assert!(values.iter().all(|&g| (0.0..=QUADRATIC_MIDDLE).contains(&g)));
    let zero: Vec<bool> = values.iter().map(|&g| g == 0.0).collect();
    assert!(zero.iter().filter(|&&z| z).count() >= n, "γ = 0 on a whole column");
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(grid, 1.0, values, params)));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 0.3,
        depth_step: 2e-3,
        max_retract_steps: 2_000,
        jump_force_threshold: 0.0,
    };
    let mut watch = ZeroTension {
        zero,
        most_held: 0,
        forces: PatchWatch {
            patch: vec![true; grid.len()],
            outside_patch: 0,
            largest_contact: 0,
            all_finite: true,
        },
    };
    let mut problem = Problem::new(Box::new(operator), heights.clone()).unwrap();
    let summary = protocol.run(&mut problem, &mut solver, &mut watch).unwrap();
    (summary, watch.forces, watch.most_held)
}

const QUADRATIC_MIDDLE: f64 = 0.01;

/// Counts γ = 0 elements in contact under tension at the end of a step.
struct ZeroTension {
    zero: Vec<bool>,
    most_held: usize,
    forces: PatchWatch,
}

impl Observer for ZeroTension {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        let held = (0..self.zero.len())
            .filter(|&k| self.zero[k] && view.state.contact[k] && view.state.pressure[k] < -1e-9)
            .count();
        self.most_held = self.most_held.max(held);
        self.forces.on_step(view)
    }
}

/// γ = 0 elements never hold tension: every step ends on a solve whose release decisions
/// were made on its own pressures, so p ≥ 0 on them up to the final convergence after a
/// certified stop (1e-9 ≈ 1e-9 σ_c,middle). Before the fix, trial neighbours with γ = 0
/// stayed attached under tension (2 at once here). Forces are finite, the sphere comes
/// off, its pull-off force is below JKR's (3/2)πγ_middle R (γ ≤ γ_middle everywhere; 5 %
/// for the mesh as for the patch), and the fast and reference rules agree.
#[test]
fn quadratic_field_reaching_zero_holds_no_tension() {
    let mut forces = Vec::new();
    for reference_rule in [false, true] {
        let (summary, watch, most_held) = sphere_on_quadratic_to_zero(AdhesiveParams {
            reference_rule,
            ..AdhesiveParams::default()
        });
        assert_eq!(
            most_held, 0,
            "γ = 0 elements held in tension (reference rule: {reference_rule})"
        );
        assert!(watch.all_finite, "non-finite force or pressure");
        assert!(summary.pull_off_depth.is_some() && summary.dissipated_energy.is_finite());
        let jkr = Jkr {
            radius: SPHERE_RADIUS,
            contact_modulus: 1.0,
            work_of_adhesion: QUADRATIC_MIDDLE,
        };
        let ratio = summary.max_adhesive_force / jkr.critical_force().abs();
        assert!(ratio > 0.0 && ratio < 1.05, "F/F_JKR(γ_middle) = {ratio:.4}");
        forces.push(summary.max_adhesive_force);
    }
    // The two rules reach the same contact sets (docs/fast-step.md); the forces agree to
    // the CG tolerance.
    assert!((forces[0] / forces[1] - 1.0).abs() < 1e-6, "{forces:?}");
}

/// γ = 0 everywhere: the adhesive step is non-adhesive contact (release at p < 0,
/// attachment by penetration), so it reaches the unique solution of the discrete
/// complementarity problem that the non-adhesive CCG solver finds: the same contact set and
/// the same force to the CG tolerances (1e-5), and Hertz's force to 1 % at a = 16Δ (the
/// discretisation error, cf. 0.5 % at 32Δ in validation_hertz.rs). Before the fix no
/// element was ever released (the ratio −p/0 was never a finite violator).
#[test]
fn zero_adhesion_everywhere_is_non_adhesive_contact() {
    let n = 64;
    let delta = 1.0 / n as f64;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = Sphere::new(SPHERE_RADIUS).unwrap().heights(&grid);
    let a = 16.0 * delta;
    let depth = a * a / SPHERE_RADIUS;
    for reference_rule in [false, true] {
        let params = AdhesiveParams {
            reference_rule,
            ..AdhesiveParams::default()
        };
        let mut solver = AdhesiveSolver::new(grid, 1.0, vec![0.0; grid.len()], params);
        let mut state = ContactState::new(&grid);
        // To 1.5 times the check depth and back: on retraction the contact must recede.
        let steps = 30;
        let depths = (1..=steps).chain((steps * 2 / 3..steps).rev());
        for step in depths {
            let d = 1.5 * depth * step as f64 / steps as f64;
            solver.step(&mut operator, &heights, d, &mut state).unwrap();
        }
        let force = state.force(grid.element_area());
        let mut reference = ContactState::new(&grid);
        let report = Ccg::new(CcgParams::default())
            .solve(&mut operator, &heights, Control::Displacement(depth), &mut reference)
            .unwrap();
        assert_eq!(
            state.contact, reference.contact,
            "contact sets (reference rule: {reference_rule})"
        );
        assert!(
            (force / report.force - 1.0).abs() < 1e-5,
            "{force} vs CCG {}",
            report.force
        );
        let hertz = Hertz {
            radius: SPHERE_RADIUS,
            contact_modulus: 1.0,
        };
        assert!(
            (force / hertz.force(depth) - 1.0).abs() < 0.01,
            "{force} vs Hertz {}",
            hertz.force(depth)
        );
        assert!(state.pressure.iter().all(|&p| p >= 0.0));
    }
}
