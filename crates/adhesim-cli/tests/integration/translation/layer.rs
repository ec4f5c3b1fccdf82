//! End-to-end tests of friction on an elastic layer (`material.thickness` with
//! `[friction]`; docs/tangential.md): the thin layer's local shear limit, a slide on a
//! layer, and what a layer does not combine with, refused by name. A module of the
//! translation tests.

use super::common::{assert_fails_with, column, column_values, curve_with_sets, repo, run_with_sets};
use std::f64::consts::PI;

/// The run's tangential force over the thin-layer (local) limit at the first shift step,
/// and a/t. A thin bonded layer shears locally: a stuck element carries q = Gδ/t, so with
/// the thin-layer pressure p = 3P(a² − r²)²/(πa⁶) of the run's own P and a (from its area)
/// the stick zone is r < c with μp(c) = Gδ/t and F = πc²·Gδ/t + μP((a² − c²)/a²)³.
fn over_local_limit(dir: &std::path::Path, thickness: f64, distance: f64) -> (f64, f64) {
    let out = dir.join(format!("t{thickness}"));
    let sets = [
        format!("material.thickness={thickness}"),
        format!("protocol.distance={distance}"),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (header, rows) = curve_with_sets(&repo().join("scenarios/layer/thin_sphere_shear.toml"), &out, &sets);
    let phase = column(&header, &rows, "phase");
    let shift = column_values(&header, &rows, "x");
    let normal = column_values(&header, &rows, "force_normal");
    let tangential = column_values(&header, &rows, "force_tangential");
    let area = column_values(&header, &rows, "area");
    let last = rows.len() - 1;
    let (mu, shear_modulus) = (0.3, 1.0);
    let (force, radius) = (normal[last], (area[last] / PI).sqrt());
    // Gross slip at the end: F_T = μP, up to the sideways relaxation the last stick zone
    // leaves in the tractions, which the further shift wears off (as on the half-space,
    // docs/tangential.md; 4e-7 measured at 1.3δ*): tolerance 1e-5.
    assert!(
        (tangential[last] / (mu * force) - 1.0).abs() < 1e-5,
        "t = {thickness}: {} vs μP = {}",
        tangential[last],
        mu * force
    );
    let first = phase.iter().position(|p| p != "approach").unwrap();
    let stuck_traction = shear_modulus * shift[first] / thickness;
    let squared = (stuck_traction * PI * radius.powi(6) / (3.0 * mu * force)).sqrt();
    let stick_squared = (radius * radius - squared).max(0.0);
    let local = PI * stick_squared * stuck_traction
        + mu * force * ((radius * radius - stick_squared) / (radius * radius)).powi(3);
    (tangential[first] / local, radius / thickness)
}

#[test]
fn thin_layer_under_shear_tends_to_local_shear() {
    // scenarios/layer/thin_sphere_shear.toml (R = 1, d = 0.01, G = 1, ν = 1/2, μ = 0.3) at
    // t = 0.01 and 0.005 (a/t ≈ 19 and 39): the layer's shear spreads about t beyond each
    // stuck element, so the run exceeds the local limit by a first-order term c·t/a
    // (measured c ≈ 2.1–2.2: 11.4 % and 5.6 %, docs/validation.md). Asserted: the excess
    // falls as t/a (the ratio of the excesses within 15 % of the ratio of a/t), and its
    // first-order extrapolation to t/a → 0 is the local limit within 1 %, which holds what
    // the extrapolation leaves: second-order terms, (t/a)² ≈ 0.3 % at the thicker layer,
    // and the contact's staircase edge.
    let dir = tempfile::tempdir().unwrap();
    let (thick, thick_ratio) = over_local_limit(dir.path(), 0.01, 0.7);
    let (thin, thin_ratio) = over_local_limit(dir.path(), 0.005, 2.8);
    let (thick_excess, thin_excess) = (thick - 1.0, thin - 1.0);
    println!("F_T/F_local = {thick:.4} at a/t = {thick_ratio:.1}, {thin:.4} at a/t = {thin_ratio:.1}");
    assert!(thick_excess > 0.0 && thin_excess > 0.0, "{thick}, {thin}");
    let order = (thick_excess / thin_excess) / (thin_ratio / thick_ratio);
    assert!((order - 1.0).abs() < 0.15, "the excess falls as (t/a)^{order:.2}");
    let extrapolated = (thin * thin_ratio - thick * thick_ratio) / (thin_ratio - thick_ratio);
    assert!(
        (extrapolated - 1.0).abs() < 0.01,
        "extrapolated to t/a → 0: {extrapolated}"
    );
}

#[test]
fn a_layer_on_a_frictionless_base_refuses_a_shear() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/layer/thin_sphere_shear.toml");
    let output = run_with_sets(
        &scenario,
        &dir.path().join("refused"),
        &["material.base=\"frictionless\""],
    );
    assert_fails_with(&output, &["material.base", "slides"]);
}

/// The normal force at the end of the approach of scenarios/friction/bonded_punch.toml on
/// a bonded incompressible layer of `thickness` (G = 1), with `coupling`.
fn punch_on_layer(dir: &std::path::Path, thickness: f64, coupling: &str) -> f64 {
    let out = dir.join(format!("{coupling}_{thickness}"));
    let sets = [
        "material.youngs_modulus=3.0".to_string(),
        "material.poisson_ratio=0.5".to_string(),
        format!("material.thickness={thickness}"),
        format!("friction.coupling=\"{coupling}\""),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (header, rows) = curve_with_sets(&repo().join("scenarios/friction/bonded_punch.toml"), &out, &sets);
    let phase = column(&header, &rows, "phase");
    let normal = column_values(&header, &rows, "force_normal");
    let last_approach = phase.iter().rposition(|p| p == "approach").unwrap();
    normal[last_approach]
}

#[test]
fn glued_punch_on_a_thin_rubber_layer_tends_to_four_times_the_frictionless_one() {
    // A flat punch (a = 32Δ) glued from first contact to a bonded incompressible layer: the
    // layer's coupling, which Goodman's approximation drops even at ν = 1/2, makes the glued
    // face hold the material that the frictionless punch squeezes out. In the thin-layer
    // limit the squeeze flux between two no-slip faces is a quarter of that under a free
    // face (t³/(12G) against t³/(3G)), so the force tends to 4× the frictionless punch's
    // (docs/physics.md §9.5). Asserted here at a/t = 8: the coupled punch is stiffer and
    // below the limit. The test below adds a/t = 16: its distance from 4 falls at least by
    // √2 per halving of t/a (a rate at least (t/a)^½; measured 1.61: the ratio is 2.57 and
    // 3.11, and 3.50 at a/t = 32 with t = 2Δ on 256², docs/validation.md §18.1).
    let dir = tempfile::tempdir().unwrap();
    let thick = glued_over_frictionless(dir.path(), 0.0625);
    assert!(1.0 < thick && thick < 4.0, "{thick} at a/t = 8");
}

#[test]
#[ignore = "the rate towards the thin-layer limit, 10 s: cargo test --release -p adhesim-cli --test integration glued_punch -- --ignored"]
fn glued_punch_on_thinner_rubber_layers_approaches_four_times_the_frictionless_one() {
    let dir = tempfile::tempdir().unwrap();
    let (thick, thin) = (
        glued_over_frictionless(dir.path(), 0.0625),
        glued_over_frictionless(dir.path(), 0.03125),
    );
    println!("glued over frictionless punch: {thick:.4} at a/t = 8, {thin:.4} at a/t = 16");
    assert!(1.0 < thick && thick < thin && thin < 4.0, "{thick}, {thin}");
    assert!(
        (4.0 - thick) / (4.0 - thin) > 2f64.sqrt(),
        "the distance from the thin-layer limit falls by {:.2} only",
        (4.0 - thick) / (4.0 - thin)
    );
}

/// The glued punch's normal force over the frictionless one's on a layer of `thickness`.
fn glued_over_frictionless(dir: &std::path::Path, thickness: f64) -> f64 {
    punch_on_layer(dir, thickness, "full") / punch_on_layer(dir, thickness, "none")
}

#[test]
fn rubber_layer_coupling_moves_the_sheared_contact_forward() {
    // The paper's sliding experiment at d = 0.2 mm (scenarios/layer/paper_r22_shear.toml,
    // at 64² here): a thin-ish rubber layer sheared forward carries material forward, which
    // lifts its surface against the indenter ahead of the contact and lowers it behind
    // (w = −(t²/(2G))∇·τ in the thin limit, docs/physics.md §9.5). With the layer's coupling
    // the front area must grow and the rear shrink; without it (Goodman) both stay as they
    // are, the normal problem being held. Both slide at τ = F_T/A = τ0 = 36 kPa, to the
    // solver's tolerance (1e-6 asserted).
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/layer/paper_r22_shear.toml");
    for coupling in ["full", "none"] {
        let out = dir.path().join(coupling);
        let set = format!("friction.coupling=\"{coupling}\"");
        let (header, rows) = curve_with_sets(&scenario, &out, &["grid.n=64", &set]);
        let phase = column(&header, &rows, "phase");
        let front = column_values(&header, &rows, "area_front");
        let rear = column_values(&header, &rows, "area_rear");
        let tangential = column_values(&header, &rows, "force_tangential");
        let area = column_values(&header, &rows, "area");
        let start = phase.iter().rposition(|p| p == "approach").unwrap();
        let last = rows.len() - 1;
        let tau = tangential[last] / area[last];
        assert!((tau / 0.036 - 1.0).abs() < 1e-6, "{coupling}: τ = {tau}");
        if coupling == "full" {
            assert!(
                front[last] > front[start] && rear[last] < rear[start],
                "front {} → {}, rear {} → {}",
                front[start],
                front[last],
                rear[start],
                rear[last]
            );
        } else {
            assert_eq!((front[last], rear[last]), (front[start], rear[start]));
        }
    }
}

#[test]
fn a_shear_weakened_edge_shrinks_the_contact_held_by_adhesion_on_the_layer() {
    // The paper's sphere pressed to 0.2 mm and lifted to d = 0, the contact held by adhesion
    // (scenarios/layer/paper_r22_shear.toml, 64² here), sheared with mode mixity 1 and
    // Goodman's approximation: the edge's shear lowers its detachment stress
    // (Savkoor–Briggs' balance, docs/physics.md §8.5, with the half-space element's energy
    // ratio, exact to O(Δ/t) on a layer as the JKR-type rule's stress is), so the contact
    // shrinks while it sticks and then slides whole at τ0 = 36 kPa on what is left. Without
    // the mode mixity it does not change.
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/layer/paper_r22_shear.toml");
    let mut areas = Vec::new();
    for mixity in ["1.0", "0.0"] {
        let out = dir.path().join(mixity);
        let sets = [
            "grid.n=64".to_string(),
            "friction.coupling=\"none\"".to_string(),
            "protocol.press_depth=0.2".to_string(),
            "protocol.depth=0.0".to_string(),
            "protocol.approach_steps=40".to_string(),
            format!("friction.mode_mixity={mixity}"),
        ];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let (header, rows) = curve_with_sets(&scenario, &out, &sets);
        let phase = column(&header, &rows, "phase");
        let area = column_values(&header, &rows, "area");
        let tangential = column_values(&header, &rows, "force_tangential");
        let held = phase.iter().rposition(|p| p != "shear").unwrap();
        let last = rows.len() - 1;
        assert!(
            (tangential[last] / area[last] / 0.036 - 1.0).abs() < 1e-6,
            "mode mixity {mixity}"
        );
        areas.push((area[held], area[last]));
    }
    let ((weakened_start, weakened_end), (sharp_start, sharp_end)) = (areas[0], areas[1]);
    assert_eq!(weakened_start, sharp_start, "the same contact before the shear");
    assert!(weakened_end < weakened_start, "{weakened_start} → {weakened_end}");
    assert_eq!(sharp_end, sharp_start);
}

/// (n_contact, force_tangential, area) per row of `scenarios/friction/slide_shear_strength.toml`
/// at 64² with `extra` overrides.
fn slide_rows(dir: &std::path::Path, name: &str, extra: &[&str]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let out = dir.join(name);
    let mut sets = vec!["grid.n=64", "protocol.steps=30"];
    sets.extend_from_slice(extra);
    let (header, rows) = curve_with_sets(
        &repo().join("scenarios/friction/slide_shear_strength.toml"),
        &out,
        &sets,
    );
    let values = |name| column_values(&header, &rows, name);
    (values("n_contact"), values("force_tangential"), values("area"))
}

#[test]
fn a_slide_with_friction_on_a_thick_layer_is_the_half_space_slide() {
    // The adhesive sphere translated with a shear strength at the interface, there and
    // back, on the half-space and on a layer of t = 10⁶ (the layer's normal and tangential
    // operators are the half-space's to 2e-8 at that thickness, docs/validation.md §18).
    // Asserted: the same contact size at every step, and tangential forces within 1e-6
    // of the largest (the layer runs the adhesive solver's reference rule, the half-space
    // its fast rule: the same contact sets, forces to the solves' tolerance; measured
    // 8.8e-8).
    let dir = tempfile::tempdir().unwrap();
    let (half_contact, half_force, _) = slide_rows(dir.path(), "half", &[]);
    let (layer_contact, layer_force, _) = slide_rows(dir.path(), "layer", &["material.thickness=1e6"]);
    assert_eq!(half_contact, layer_contact);
    let largest = half_force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    for (k, (half, layer)) in half_force.iter().zip(&layer_force).enumerate() {
        assert!((half - layer).abs() < 1e-6 * largest, "row {k}: {half} vs {layer}");
    }
}

#[test]
fn a_slide_on_a_thin_layer_slides_at_its_shear_strength() {
    // The same slide on a layer of t = 0.02 (a/t ≈ 8): once the whole contact slides, the
    // interface's force is τ0·A exactly (the law bounds every element), so the run's
    // F_T = F_B + τ0·A with the boundary part F_B of the moving contact; the stiffer layer
    // has a smaller contact than the half-space at the same depth (190 elements against
    // 364). Asserted: F_T/A at mid-stroke lies within 10 % of τ0 = 0.05 (measured +5.9 %:
    // the boundary part; +0.4 % on the half-space), and the thin layer's contact is smaller
    // than the half-space's at every stroke step.
    let dir = tempfile::tempdir().unwrap();
    let (half_contact, _, _) = slide_rows(dir.path(), "half", &[]);
    let (thin_contact, thin_force, thin_area) = slide_rows(dir.path(), "thin", &["material.thickness=0.02"]);
    let stroke = 20;
    for k in stroke..thin_contact.len() {
        assert!(
            thin_contact[k] < half_contact[k],
            "row {k}: {} vs {}",
            thin_contact[k],
            half_contact[k]
        );
    }
    let middle = stroke + 10;
    let stress = thin_force[middle] / thin_area[middle];
    assert!((stress / 0.05 - 1.0).abs() < 0.1, "F_T/A = {stress}");
}
