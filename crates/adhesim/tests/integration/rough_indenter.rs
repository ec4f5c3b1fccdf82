//! Rough indenters (`rough_sphere`, `rough_flat`): a base shape carrying a random
//! self-affine surface, peaks towards the half-space.
//!
//! `cargo test --release -p adhesim --test integration rough_indenter::`

use crate::common;

use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, FreeOperator,
    Grid, HalfSpace, IndentPulloff, Indenter, NormalSolver, Problem, Profile, RmsTarget, RoughBase, RoughProfile,
    SelfAffine, Sphere, StepRecord,
};
use common::JkrCase;

fn surface(grid: &Grid, seed: u64) -> Vec<f64> {
    SelfAffine::new(0.8, RmsTarget::Slope(0.1))
        .with_rolloff_wavelength(grid.size_x() / 4.0)
        .generate(grid, seed)
        .unwrap()
        .heights
}

fn lowest(heights: &[f64]) -> (usize, f64) {
    heights.iter().copied().enumerate().fold(
        (0, f64::INFINITY),
        |best, (k, z)| if z < best.1 { (k, z) } else { best },
    )
}

/// z = base − h − min(base − h), sample by sample, on free and periodic grids; the
/// difference is rounding only (1e-15 of the largest term).
#[test]
fn heights_are_base_minus_roughness_shifted_to_first_contact() {
    for boundary in [Boundary::Free, Boundary::Periodic] {
        let grid = Grid::new(48, 0.6, boundary).unwrap();
        let roughness = surface(&grid, 3);
        let sphere = Sphere::new(2.0).unwrap().heights(&grid);
        for base in [RoughBase::Flat, RoughBase::Sphere(Sphere::new(2.0).unwrap())] {
            let profile = RoughProfile::new(base, roughness.clone(), &grid).unwrap();
            let heights = Indenter::Rough(profile.clone()).heights(&grid);
            let shift = profile.first_contact_offset();
            let scale = sphere.iter().chain(&roughness).fold(0.0_f64, |m, v| m.max(v.abs()));
            for k in 0..grid.len() {
                let smooth = if base == RoughBase::Flat { 0.0 } else { sphere[k] };
                let expected = smooth - roughness[k] - shift;
                assert!(
                    (heights[k] - expected).abs() <= 1e-15 * scale,
                    "{boundary:?} {base:?} element {k}: {} vs {expected}",
                    heights[k]
                );
            }
            // the analytic height at an element centre is the same sample
            let (x, y) = grid.centre(777);
            assert!((profile.height(x, y) - heights[777]).abs() <= 1e-15 * scale);
            // a sideways offset (sub-element and beyond the map's edge): the indexed
            // lattice lookup agrees with the analytic height (rounding of offset/Δ only)
            let offset = (0.3 * grid.dx(), -1.7 * grid.dx());
            let mut moved = vec![0.0; grid.len()];
            profile.fill_heights(&grid, offset, &mut moved);
            for (k, &z) in moved.iter().enumerate() {
                let (x, y) = grid.centre(k);
                let analytic = profile.height(x - offset.0, y - offset.1);
                assert!((z - analytic).abs() <= 1e-12 * scale, "element {k}: {z} vs {analytic}");
            }
            if base == RoughBase::Flat {
                // rough_flat: first contact at the highest asperity
                let highest = roughness.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                assert_eq!(shift, -highest);
            }
        }
    }
}

/// The first contact point is the lowest point of the combined surface: the sample where
/// h − base is largest, at z = 0 exactly; and the elastic solver, pressed with a load far
/// below what closes the next-lowest gap (F = 0.05·E*·Δ·z₂, the force that sinks a
/// Δ×Δ punch by ≈ 0.05·z₂), touches that element and no other.
#[test]
fn first_contact_is_the_lowest_point_of_the_combined_surface() {
    let grid = Grid::new(64, 1.0, Boundary::Periodic).unwrap();
    for seed in 0..3 {
        let roughness = surface(&grid, seed);
        for base in [RoughBase::Flat, RoughBase::Sphere(Sphere::new(1.0).unwrap())] {
            let profile = RoughProfile::new(base, roughness.clone(), &grid).unwrap();
            let heights = profile.heights(&grid);
            let (first, z_first) = lowest(&heights);
            assert_eq!(z_first, 0.0);
            let combined_peak = (0..grid.len())
                .map(|k| {
                    let (x, y) = grid.centre(k);
                    let smooth = if base == RoughBase::Flat { 0.0 } else { x * x + y * y };
                    (k, roughness[k] - smooth / 2.0)
                })
                .fold(
                    (0, f64::NEG_INFINITY),
                    |best, (k, v)| if v > best.1 { (k, v) } else { best },
                );
            assert_eq!(first, combined_peak.0, "seed {seed} {base:?}");
            assert!(heights.iter().all(|&z| z >= 0.0));

            let second = heights
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != first)
                .fold(f64::INFINITY, |m, (_, &z)| m.min(z));
            let mut operator = HalfSpace::new(grid, ElasticMaterial::new(1.0).unwrap());
            let mut state = ContactState::new(&grid);
            let load = 0.05 * grid.dx() * second;
            Ccg::new(CcgParams::default())
                .solve(&mut operator, &heights, Control::Load(load), &mut state)
                .unwrap();
            let touching: Vec<usize> = (0..grid.len()).filter(|&k| state.contact[k]).collect();
            assert_eq!(touching, vec![first], "seed {seed} {base:?}");
        }
    }
}

fn cycle(case: &JkrCase, heights: &[f64]) -> Vec<StepRecord> {
    let d_jkr = case.jkr.critical_depth().abs();
    let operator = FreeOperator::new(case.grid, ElasticMaterial::new(1.0).unwrap());
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        case.grid,
        1.0,
        vec![case.jkr.work_of_adhesion; case.grid.len()],
        AdhesiveParams::default(),
    )));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 3.0 * d_jkr,
        depth_step: d_jkr / 10.0,
        max_retract_steps: 10_000,
        jump_force_threshold: 0.0,
    };
    let mut records = Vec::new();
    let mut problem = Problem::new(Box::new(operator), heights.to_vec()).unwrap();
    protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    records
}

/// A rough sphere with zero roughness is the sphere, bit for bit: same heights, same
/// adhesive indent–pull-off (every step's depth, force, area and contact set size).
#[test]
fn zero_roughness_sphere_is_the_sphere_bit_for_bit() {
    let case = JkrCase::new(8.0, 3.0);
    let sphere = Indenter::Sphere(Sphere::new(1.0).unwrap());
    let rough = Indenter::Rough(RoughProfile::rough_sphere(1.0, vec![0.0; case.grid.len()], &case.grid).unwrap());
    assert_eq!(rough.radius_of_curvature(), Some(1.0));
    let (smooth_heights, rough_heights) = (sphere.heights(&case.grid), rough.heights(&case.grid));
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&smooth_heights), bits(&rough_heights));
    let (smooth, rough) = (cycle(&case, &smooth_heights), cycle(&case, &rough_heights));
    assert!(smooth.len() > 50, "a real cycle: {} steps", smooth.len());
    assert!(
        smooth.iter().any(|r| r.force_normal < 0.0),
        "adhesive: some tensile force"
    );
    assert_eq!(smooth.len(), rough.len());
    for (a, b) in smooth.iter().zip(&rough) {
        assert_eq!(
            (
                a.depth.to_bits(),
                a.force_normal.to_bits(),
                a.area.to_bits(),
                a.contact_elements
            ),
            (
                b.depth.to_bits(),
                b.force_normal.to_bits(),
                b.area.to_bits(),
                b.contact_elements
            ),
            "step {}",
            a.step
        );
    }
}

/// A generated surface put on a base by the generator's own helper is the same profile.
#[test]
fn rough_surface_helper_builds_the_same_profile() {
    let grid = Grid::new(32, 0.4, Boundary::Free).unwrap();
    let drawn = SelfAffine::new(0.7, RmsTarget::Height(1e-3))
        .generate(&grid, 9)
        .unwrap();
    let base = RoughBase::Sphere(Sphere::new(1.0).unwrap());
    assert_eq!(
        drawn.to_rough_profile(base).unwrap(),
        RoughProfile::new(base, drawn.heights.clone(), &grid).unwrap()
    );
}
