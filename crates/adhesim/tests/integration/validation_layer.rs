//! Non-adhesive sphere on an elastic layer of finite thickness on a rigid base
//! (docs/validation.md, "Elastic layer of finite thickness").

use adhesim::analysis::reference::Hertz;
use adhesim::{
    Boundary, Ccg, CcgParams, ContactState, Control, ElasticLayer, ElasticMaterial, Grid, LayerBase, LayerOperator,
    Profile, Sphere,
};

/// A rigid sphere of radius 1 pressed to depth `depth` into a layer on a free n² grid of
/// side n/128 (Δ = 1/128): the force and the area-equivalent contact radius √(A/π).
fn indent(n: usize, layer: ElasticLayer, depth: f64) -> (f64, f64) {
    let grid = Grid::new(n, n as f64 / 128.0, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let mut operator = LayerOperator::new(grid, material, layer).unwrap();
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    let mut state = ContactState::new(&grid);
    let report = Ccg::new(CcgParams::default())
        .solve(&mut operator, &heights, Control::Displacement(depth), &mut state)
        .unwrap();
    (report.force, (report.contact_area / std::f64::consts::PI).sqrt())
}

/// The thin-layer closed form at a/t, t = `thickness_elements`·Δ: the relative errors of the
/// force against P = 2πG R² d³/t³ and of √(A/π) against a = 2√(Rd), with the depth set so
/// that the closed-form radius is a/t·t (d = a²/(4R), R = 1, G = E*/4 at ν = 1/2).
fn lubrication_errors(n: usize, a_over_t: f64, thickness_elements: f64) -> (f64, f64) {
    let (radius, shear_modulus) = (1.0f64, 0.25);
    let thickness = thickness_elements / 128.0;
    let contact_radius = a_over_t * thickness;
    let depth = contact_radius * contact_radius / (4.0 * radius);
    let layer = ElasticLayer::new(thickness, 0.5, LayerBase::Bonded).unwrap();
    let (force, area_radius) = indent(n, layer, depth);
    let expected = 2.0 * std::f64::consts::PI * shear_modulus * radius.powi(2) * depth.powi(3) / thickness.powi(3);
    let errors = (force / expected - 1.0, area_radius / contact_radius - 1.0);
    println!(
        "a/t = {a_over_t:2.0}, t = {thickness_elements}Δ, a = {}Δ: F/F_thin − 1 = {:+.4e}, a/a_thin − 1 = {:+.4e}",
        a_over_t * thickness_elements,
        errors.0,
        errors.1
    );
    errors
}

/// (c0, c1) of c0 + c1 ε + c2 ε² through three points (ε, e(ε)): Lagrange's polynomial
/// and its slope at ε = 0.
fn extrapolate(points: [(f64, f64); 3]) -> (f64, f64) {
    let (mut value, mut slope) = (0.0, 0.0);
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let (ei, ej, ek) = (points[i].0, points[j].0, points[k].0);
        let denominator = (ei - ej) * (ei - ek);
        value += points[i].1 * ej * ek / denominator;
        slope -= points[i].1 * (ej + ek) / denominator;
    }
    (value, slope)
}

/// Thin bonded incompressible layer, frictionless sphere (lubrication limit, t ≪ a):
/// P = 2πG R² d³/t³ and a = 2√(Rd) (docs/physics.md, "Elastic layer of finite thickness")
/// are the leading terms of an expansion in t/a, which neglects the edge region of width
/// ~t where the layer is not thin. At t = 2Δ and a/t = 10, 20, 40 (a = 20, 40, 80Δ) the
/// deviations are measured (F: +17.7 %, +4.6 %, +1.0 %; a: −10.9 %, −6.2 %, −3.3 %; they
/// fall as (t/a)² and t/a), and their quadratic extrapolation to t/a → 0 must give the
/// closed form within 1 %: the layer's discretisation at two elements per thickness moves
/// the force by 0.25 % (a/t = 10 at t = 2Δ and 4Δ: within 0.5 % here), and the cubic
/// remainder of the extrapolation is estimated from the spread of the terms at well below
/// 1 %. The force's first-order term must be small (|c1| < 1: measured 0.26), its error
/// shrinking by more than 3 per halving of t/a; the radius's by 1.5–2.5 (first order).
#[test]
fn thin_incompressible_layer_is_the_lubrication_limit() {
    let runs =
        [(64, 10.0), (128, 20.0), (256, 40.0)].map(|(n, a_over_t)| (a_over_t, lubrication_errors(n, a_over_t, 2.0)));
    let force = extrapolate(runs.map(|(a_over_t, (force, _))| (1.0 / a_over_t, force)));
    let radius = extrapolate(runs.map(|(a_over_t, (_, radius))| (1.0 / a_over_t, radius)));
    println!(
        "extrapolated to t/a → 0: F/F_thin − 1 = {:+.2e}, a/a_thin − 1 = {:+.2e}",
        force.0, radius.0
    );
    assert!(force.0.abs() < 0.01 && radius.0.abs() < 0.01, "{force:?} {radius:?}");
    let force_c1 = force.1;
    println!("force: first-order coefficient c1 = {force_c1:+.3}");
    assert!(force_c1.abs() < 1.0, "{force_c1}");
    let [(_, (f10, r10)), (_, (f20, r20)), (_, (f40, r40))] = runs;
    assert!(f10 / f20 > 3.0 && f20 / f40 > 3.0, "force errors {f10} {f20} {f40}");
    for ratio in [r10 / r20, r20 / r40] {
        assert!((1.5..2.5).contains(&ratio), "radius errors {r10} {r20} {r40}");
    }
    // Mesh: the same a/t = 10 at t = 4Δ.
    let (finer_force, finer_radius) = lubrication_errors(128, 10.0, 4.0);
    assert!(
        ((1.0 + f10) / (1.0 + finer_force) - 1.0).abs() < 5e-3,
        "{f10} vs {finer_force}"
    );
    assert!(
        ((1.0 + r10) / (1.0 + finer_radius) - 1.0).abs() < 5e-3,
        "{r10} vs {finer_radius}"
    );
}

/// A layer much thicker than the contact is the half-space: Hertz to the tolerances of
/// tests/integration/validation_hertz.rs (force within 0.5 % at a = 32Δ; radius within one
/// element).
#[test]
fn thick_layer_is_hertz() {
    let depth = (32.0f64 / 128.0).powi(2);
    let layer = ElasticLayer::new(1e6, 0.5, LayerBase::Bonded).unwrap();
    let (force, area_radius) = indent(128, layer, depth);
    let hertz = Hertz {
        radius: 1.0,
        contact_modulus: 1.0,
    };
    let force_error = force / hertz.force(depth) - 1.0;
    println!("t = 1e6: F/F_Hertz − 1 = {force_error:+.3e}, a = {area_radius}");
    assert!(force_error.abs() < 5e-3, "force error {force_error}");
    assert!(
        (area_radius - depth.sqrt()).abs() <= 1.0 / 128.0,
        "radius {area_radius}"
    );
}

/// The thin frictionless-base layer at a/t, t = 2Δ: errors of the force against the Winkler
/// foundation's P = πE*Rd²/t and of √(A/π) against a = √(2Rd), at the depth d = a²/(2R).
fn winkler_errors(n: usize, a_over_t: f64) -> (f64, f64) {
    let radius = 1.0f64;
    let thickness = 2.0 / 128.0;
    let contact_radius = a_over_t * thickness;
    let depth = contact_radius * contact_radius / (2.0 * radius);
    let layer = ElasticLayer::new(thickness, 0.3, LayerBase::Frictionless).unwrap();
    let (force, area_radius) = indent(n, layer, depth);
    let expected = std::f64::consts::PI * radius * depth * depth / thickness;
    let errors = (force / expected - 1.0, area_radius / contact_radius - 1.0);
    println!(
        "frictionless base, a/t = {a_over_t:2.0}: F/F_Winkler − 1 = {:+.4e}, a/a_Winkler − 1 = {:+.4e}",
        errors.0, errors.1
    );
    errors
}

/// Thin layer on a frictionless base: at kt ≪ 1 its compliance is t/E* for every ν
/// (f = s/2 + O(s⁵), docs/physics.md §9.1), a Winkler foundation: p = (E*/t)(d − r²/(2R)),
/// a = √(2Rd), P = πE*Rd²/t. The foundation's pressure ends with a finite slope, which the
/// layer rounds off over ~t: at a/t = 10, 20, 40 (t = 2Δ) the deviations must fall with t/a
/// and extrapolate (quadratically, as above) to the closed form within 1 %.
#[test]
fn thin_frictionless_base_is_a_winkler_foundation() {
    let runs = [(64, 10.0), (128, 20.0), (256, 40.0)].map(|(n, a_over_t)| (a_over_t, winkler_errors(n, a_over_t)));
    let force = extrapolate(runs.map(|(a_over_t, (force, _))| (1.0 / a_over_t, force)));
    let radius = extrapolate(runs.map(|(a_over_t, (_, radius))| (1.0 / a_over_t, radius)));
    println!(
        "extrapolated to t/a → 0: F/F_Winkler − 1 = {:+.2e}, a/a_Winkler − 1 = {:+.2e}",
        force.0, radius.0
    );
    assert!(force.0.abs() < 0.01 && radius.0.abs() < 0.01, "{force:?} {radius:?}");
    let [(_, (f10, r10)), (_, (f20, r20)), (_, (f40, r40))] = runs;
    assert!(
        f10.abs() > f20.abs() && f20.abs() > f40.abs(),
        "force errors {f10} {f20} {f40}"
    );
    assert!(
        r10.abs() > r20.abs() && r20.abs() > r40.abs(),
        "radius errors {r10} {r20} {r40}"
    );
}
