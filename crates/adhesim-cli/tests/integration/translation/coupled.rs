//! End-to-end tests of the coupled operator (`friction.coupling = "full"`, ν < 1/2;
//! docs/tangential.md): the bonded punch against Mossakovskii's closed form, a slide in
//! gross slip against the first-order moment of its pressure, and the combinations refused
//! by name. A module of the translation tests.

use super::common::{assert_fails_with, column, column_values, curve_with_sets, repo, run_with_sets};

/// The normal force at the end of the approach of scenarios/friction/bonded_punch.toml
/// with the overrides `sets`.
fn punch_force(dir: &std::path::Path, name: &str, sets: &[&str]) -> f64 {
    let out = dir.join(name);
    let (header, rows) = curve_with_sets(&repo().join("scenarios/friction/bonded_punch.toml"), &out, sets);
    let normal = column_values(&header, &rows, "force_normal");
    let approach = 4;
    assert!(rows.len() > approach, "{name}: {} rows", rows.len());
    normal[approach - 1]
}

#[test]
fn bonded_punch_is_stiffer_by_mossakovskiis_factor() {
    // A rigid flat punch glued to the half-space from first contact (law = "no_slip")
    // carries (1 − ν)·ln(3 − 4ν)/(1 − 2ν) times the frictionless punch's force at the same
    // depth (Mossakovskii 1954; Spence 1968): 1.0287 at ν = 0.3, ln 3 = 1.0986 at ν = 0.
    // The frictionless reference is the same run with coupling = "none" (Goodman's
    // approximation leaves the normal problem frictionless), so the ratio shares the
    // punch edge's staircase; tolerance 0.3 % of the ratio, a tenth of the effect at
    // ν = 0.3 (measured: see docs/validation.md).
    let dir = tempfile::tempdir().unwrap();
    for (poisson_ratio, youngs_modulus) in [(0.3, 2.6), (0.0, 2.0)] {
        let material = [
            format!("material.poisson_ratio={poisson_ratio}"),
            format!("material.youngs_modulus={youngs_modulus}"),
        ];
        let material: Vec<&str> = material.iter().map(String::as_str).collect();
        let coupled = punch_force(dir.path(), &format!("full_{poisson_ratio}"), &material);
        let mut goodman = material.clone();
        goodman.push("friction.coupling=\"none\"");
        let frictionless = punch_force(dir.path(), &format!("none_{poisson_ratio}"), &goodman);
        let nu: f64 = poisson_ratio;
        let expected = (1.0 - nu) * (3.0 - 4.0 * nu).ln() / (1.0 - 2.0 * nu);
        let ratio = coupled / frictionless;
        assert!(
            (ratio / expected - 1.0).abs() < 3e-3,
            "ν = {nu}: bonded/frictionless {ratio} vs {expected}"
        );
    }
}

#[test]
fn a_coupled_slide_in_gross_slip_moves_the_pressure_rearward_by_the_first_order_moment() {
    // scenarios/friction/slide_coupled.toml: a sphere (a = 12.8Δ) slid in gross slip with
    // Coulomb μ = 0.3 on ν = 0.3. The tractions μp press the surface in ahead of each
    // element, so the pressure's moment about the axis turns negative and with it the
    // boundary force F_B = F_T − μP (all slip: the interface carries μP exactly):
    // F_B/(μP) = −(3/(4π))·(1 − 2ν)/(1 − ν)·a/R to first order in μ(1 − 2ν)/(2(1 − ν))
    // (Betti's theorem twice, docs/physics.md §8.4a), with a = (3PR/(4E*))^(1/3) each
    // step. Tolerance 2 % over the stroke's last six steps: the second order, (βμ)² =
    // 0.7 %, and the contact edge's staircase at 12.8 elements (measured 0.993–0.998 of
    // the closed form at 128², 0.998 at 256²). The same run under Goodman's approximation
    // must show no such force (below 1e-3 of μP; measured 7e-5): the effect is the
    // coupling's.
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/friction/slide_coupled.toml");
    let (nu, radius, contact_modulus, mu) = (0.3, 1.0, 2.6 / (1.0 - 0.3 * 0.3), 0.3);
    let expected_per_radius = -3.0 / (4.0 * std::f64::consts::PI) * (1.0 - 2.0 * nu) / (1.0 - nu);
    for (name, sets) in [("coupled", &[][..]), ("goodman", &["friction.coupling=\"none\""][..])] {
        let (header, rows) = curve_with_sets(&scenario, &dir.path().join(name), sets);
        assert_eq!(rows.len(), 30, "{name}");
        let normal = column_values(&header, &rows, "force_normal");
        let tangential = column_values(&header, &rows, "force_tangential");
        let stick = column_values(&header, &rows, "n_stick");
        for k in rows.len() - 6..rows.len() {
            assert_eq!(stick[k], 0.0, "{name} step {k}: not in gross slip");
            let boundary = (tangential[k] - mu * normal[k]) / (mu * normal[k]);
            let radius_of_contact = (3.0 * normal[k] * radius / (4.0 * contact_modulus)).cbrt();
            let expected = expected_per_radius * radius_of_contact / radius;
            if name == "coupled" {
                assert!(
                    (boundary / expected - 1.0).abs() < 0.02,
                    "step {k}: F_B/(μP) = {boundary:e}, first order {expected:e}"
                );
            } else {
                assert!(boundary.abs() < 1e-3, "step {k}: Goodman's F_B/(μP) = {boundary:e}");
            }
        }
    }
}

#[test]
fn a_coupled_slide_at_one_half_is_goodmans() {
    // The slide of slide_coupled.toml at ν = 1/2 (E = 3, G = 1), coarsened to 64²: the
    // coupling terms vanish on a half-space, so each step's coupled rounds must give the
    // uncoupled step: the same contact, stick, slip, front and rear counts at every step
    // (the approach's too, whose tractions vanish), forces and friction's dissipation to
    // 1e-12 of their largest (measured: identical to 7e-17).
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/friction/slide_coupled.toml");
    let half = ["grid.n=64", "material.poisson_ratio=0.5", "material.youngs_modulus=3"];
    let (header, coupled) = curve_with_sets(&scenario, &dir.path().join("coupled"), &half);
    let goodman_sets = [&half[..], &["friction.coupling=\"none\""]].concat();
    let (header_goodman, goodman) = curve_with_sets(&scenario, &dir.path().join("goodman"), &goodman_sets);
    assert_eq!(coupled.len(), goodman.len());
    for name in ["n_contact", "n_stick", "n_slip", "area_front", "area_rear"] {
        assert_eq!(
            column(&header, &coupled, name),
            column(&header_goodman, &goodman, name),
            "{name}"
        );
    }
    for name in ["force_normal", "force_tangential", "frictional_dissipation"] {
        let (a, b) = (
            column_values(&header, &coupled, name),
            column_values(&header_goodman, &goodman, name),
        );
        let largest = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(largest > 0.0, "{name} vanishes");
        for (k, (a, b)) in a.iter().zip(&b).enumerate() {
            assert!((a - b).abs() <= 1e-12 * largest, "row {k}: {name} {a} vs {b}");
        }
    }
}

#[test]
fn a_compliant_drive_with_the_coupled_operator_is_refused_by_name() {
    // A spring's rounds (the profile moved to where the indenter goes) are not built around
    // the coupled rounds: the refusal names both keys.
    let dir = tempfile::tempdir().unwrap();
    let output = run_with_sets(
        &repo().join("scenarios/friction/slide_coupled.toml"),
        &dir.path().join("spring"),
        &["protocol.drive_stiffness=1.0"],
    );
    assert_fails_with(&output, &["protocol.drive_stiffness", "friction.coupling = \"full\""]);
}

#[test]
fn an_imposed_force_with_the_coupled_operator_finds_the_shift_that_carries_it() {
    // The glued punch of bonded_punch.toml at ν = 0.3 sheared by 0.0005 in four steps, then
    // loaded by the tangential force that shift carried, ramped in four steps: its contact
    // never changes, so the coupled problem is linear and the force's shift must be the
    // imposed one, to the force tolerance (1e-8) over the contact's stiffness; every step
    // carries its share of the force to 1e-8, and the normal forces agree to 1e-9.
    let dir = tempfile::tempdir().unwrap();
    let punch = repo().join("scenarios/friction/bonded_punch.toml");
    let (header, rows) = curve_with_sets(&punch, &dir.path().join("shift"), &[]);
    let force = *column_values(&header, &rows, "force_tangential").last().unwrap();
    let normal = *column_values(&header, &rows, "force_normal").last().unwrap();
    let text = std::fs::read_to_string(&punch).unwrap();
    assert!(text.contains("\ndistance = 0.0005"), "bonded_punch.toml changed");
    let imposed = text.replace("\ndistance = 0.0005", &format!("\ntangential_force = {force:e}"));
    let scenario = dir.path().join("force.toml");
    std::fs::write(&scenario, imposed).unwrap();
    let (header, rows) = curve_with_sets(&scenario, &dir.path().join("force"), &[]);
    let shifts = column_values(&header, &rows, "x");
    let forces = column_values(&header, &rows, "force_tangential");
    let approach = 4;
    for (k, (shift, carried)) in shifts[approach..].iter().zip(&forces[approach..]).enumerate() {
        let share = (k + 1) as f64 / 4.0;
        assert!(
            (carried / (share * force) - 1.0).abs() < 1e-8,
            "step {k}: {carried} vs {}",
            share * force
        );
        assert!((shift / (share * 0.0005) - 1.0).abs() < 1e-7, "step {k}: shift {shift}");
    }
    let last_normal = *column_values(&header, &rows, "force_normal").last().unwrap();
    assert!((last_normal / normal - 1.0).abs() < 1e-9, "{last_normal} vs {normal}");
}

#[test]
fn an_alternating_contact_set_stops_the_run_with_its_reason() {
    // The adhesive sphere under a shear strength at ν = 0.3: the tractions' lift flips a
    // ring of the adhesive edge in and out round after round (6,205 ↔ 6,221 elements at the
    // second approach step). The run stops there naming the cause, after a few rounds
    // rather than the round limit, and keeps the steps done.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("alternating");
    let output = run_with_sets(
        &repo().join("scenarios/friction/shear_strength.toml"),
        &out,
        &[
            "material.poisson_ratio=0.3",
            "material.youngs_modulus=2.6",
            "friction.coupling=\"full\"",
        ],
    );
    assert_fails_with(
        &output,
        &["coupled normal and tangential solves", "alternates", "step 1"],
    );
    assert!(out.join("curve.csv.partial").exists());
}

#[test]
fn a_held_normal_force_with_the_coupled_operator_keeps_the_step_its_depth_gives() {
    // The paper's R = 22 mm sphere on the 5 mm layer (scenarios/layer/paper_r22_shear.toml,
    // coarsened to 64² and a 10-step approach), sheared by 0.02 in one step at the held
    // normal force. At the held depth the coupled shear moves the normal force by −1.1e-3
    // of it (measured), so the step must find its depth: the force is held to the search's
    // tolerance (1e-8 of it). Each trial depth starts from the step's start, the coupled
    // rounds' lift and the pressure's pull put back with the rest, so the kept step is the
    // depth-controlled step at its depth. Checked against a run that reaches that depth on
    // its own: one step up an incline chosen so that depth + shift·tan(incline) is the
    // found depth to the last bit. Its forces, areas and stick and slip counts agree to
    // 1e-12 (bit for bit on one thread; the reductions' order may differ on more). Trials
    // that left the rounds' lift behind moved the kept step's tangential force by 7e-9 of
    // it and its depth by 4e-9 (measured).
    let dir = tempfile::tempdir().unwrap();
    let layer = repo().join("scenarios/layer/paper_r22_shear.toml");
    let (depth, shift) = (0.2, 0.02);
    let one_step = [
        "grid.n=64",
        "protocol.approach_steps=10",
        "protocol.steps=1",
        "protocol.distance=0.02",
    ];
    let force_sets = [&one_step[..], &["protocol.normal_control=\"force\""]].concat();
    let (header, rows) = curve_with_sets(&layer, &dir.path().join("force"), &force_sets);
    let approach = 10;
    assert_eq!(rows.len(), approach + 1);
    let normal = column_values(&header, &rows, "force_normal");
    let (held, kept) = (normal[approach - 1], normal[approach]);
    assert!((kept / held - 1.0).abs() <= 1e-8, "F_N {kept} vs held {held}");
    let found = column_values(&header, &rows, "d")[approach];
    assert!((found / depth - 1.0).abs() > 1e-6, "the depth did not move: {found}");
    // The incline whose one step of `shift` lands on the found depth exactly, as the
    // protocol computes it (degrees to radians, the tangent, depth + shift·slope).
    let lands = |degrees: f64| depth + shift * degrees.to_radians().tan() == found;
    let guess = ((found - depth) / shift).atan().to_degrees();
    let degrees = (0..100_000u64)
        .flat_map(|k| [f64::from_bits(guess.to_bits() + k), f64::from_bits(guess.to_bits() - k)])
        .find(|&degrees| lands(degrees))
        .expect("an incline that lands on the found depth");
    let incline = format!("protocol.incline={degrees}");
    let (header_up, rows_up) = curve_with_sets(
        &layer,
        &dir.path().join("incline"),
        &[&one_step[..], &[incline.as_str()]].concat(),
    );
    assert_eq!(column_values(&header_up, &rows_up, "d")[approach], found);
    for name in [
        "force_normal",
        "force_tangential",
        "area",
        "area_front",
        "area_rear",
        "n_contact",
        "n_stick",
        "n_slip",
    ] {
        let at_held_force = column_values(&header, &rows, name)[approach];
        let up_the_incline = column_values(&header_up, &rows_up, name)[approach];
        assert!(
            (at_held_force - up_the_incline).abs() <= 1e-12 * at_held_force.abs(),
            "{name}: {at_held_force} at the held force, {up_the_incline} up the incline"
        );
    }
}

#[test]
fn a_shear_weakened_edge_with_the_coupled_operator_at_one_half_is_goodmans() {
    // scenarios/friction/adhesive_shear.toml (the adhesive sphere glued and sheared with
    // mode mixity 1, a0 = 36Δ, ν = 1/2; Savkoor–Briggs within its tolerances) with the
    // coupled operator: at ν = 1/2 on a half-space its coupling terms vanish, so the
    // coupled rounds, which weaken the edge after each tangential solve, must give the
    // weakened Goodman step: the same contact, front, rear, stick and slip counts at every
    // step, the tangential force to 1e-9 of its largest (measured 1.2e-11) and the normal
    // force to 1e-6 of its largest (measured 2.2e-8: the normal solves' tolerance, reached
    // from other starting points, since a coupled round solves the normal problem first).
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo().join("scenarios/friction/adhesive_shear.toml");
    let (header, goodman) = curve_with_sets(&scenario, &dir.path().join("goodman"), &[]);
    let (header_coupled, coupled) =
        curve_with_sets(&scenario, &dir.path().join("coupled"), &["friction.coupling=\"full\""]);
    assert_eq!(goodman.len(), coupled.len());
    for name in ["n_contact", "area_front", "area_rear", "n_stick", "n_slip"] {
        assert_eq!(
            column(&header, &goodman, name),
            column(&header_coupled, &coupled, name),
            "{name}"
        );
    }
    for (name, tolerance) in [("force_tangential", 1e-9), ("force_normal", 1e-6)] {
        let (a, b) = (
            column_values(&header, &goodman, name),
            column_values(&header_coupled, &coupled, name),
        );
        let largest = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, (a, b)) in a.iter().zip(&b).enumerate() {
            assert!((a - b).abs() <= tolerance * largest, "row {k}: {name} {a} vs {b}");
        }
    }
    // The edge was weakened: the contact lost area over the shift.
    let contact = column_values(&header_coupled, &coupled, "n_contact");
    assert!(contact[contact.len() - 1] < 0.95 * contact[19], "{contact:?}");
}
