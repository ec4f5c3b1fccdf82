//! Friction through the scenario layer: the static law reaches the tangential solver (slip
//! comes later, sliding stays at the kinetic τ0·A) and its keys are refused where they do
//! not belong; a compliant drive saws; roll, slide and translate carry friction too.

use crate::tests::error_of;
use crate::*;

/// An adhesive sphere on 48², shifted into gross sliding under a shear strength in steps
/// of a tenth of the slip distance τ0·a/G ≈ 2e-4 (a = √(Rd) = 0.1, G = 1): a coarser step
/// breaks the whole contact loose in one step, and no peak can show.
const TRESCA: &str = r#"
[grid]
n = 48
size = 0.5
[material]
youngs_modulus = 3.0
poisson_ratio = 0.5
[adhesion]
work_of_adhesion = 2e-3
[indenter]
shape = "sphere"
radius = 1.0
[friction]
law = "shear_strength"
shear_strength = 0.002
[protocol]
kind = "shear"
depth = 0.01
depth_unit = "length"
approach_steps = 5
distance = 0.002
steps = 20
"#;

/// The results and records of the scenario `text` with `overrides`.
fn outcome_of(text: &str, overrides: &[&str]) -> (RunResults, Vec<adhesim::StepRecord>) {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let scenario = load(text, "friction.toml", Path::new("."), &overrides).unwrap();
    let outcome = run(&scenario, &mut ()).unwrap();
    (outcome.results, outcome.records)
}

fn shear_run(overrides: &[&str]) -> (ShearResults, Vec<adhesim::StepRecord>) {
    let (RunResults::Shear(results), records) = outcome_of(TRESCA, overrides) else {
        panic!("not a shear run")
    };
    (results, records)
}

/// The static value reaches the solver: at every shift step the contact holds at least as
/// many elements stuck and at least the kinetic run's force, strictly more stuck at some
/// step, never above τs·A; both slide at the kinetic τ0·A (1e-9: every element at its
/// kinetic bound).
#[test]
fn a_static_shear_strength_delays_slip_and_slides_at_the_kinetic_bound() {
    let (kinetic, kinetic_records) = shear_run(&[]);
    let (with_static, static_records) = shear_run(&["friction.static_shear_strength=0.004"]);
    let area = with_static.contact_area;
    assert_eq!(kinetic_records.len(), static_records.len());
    for (s, k) in static_records.iter().zip(&kinetic_records) {
        assert!(
            s.stick_elements >= k.stick_elements && s.force_tangential >= k.force_tangential * (1.0 - 1e-9),
            "step {}: stuck {} against {}, force {} against {}",
            s.step,
            s.stick_elements,
            k.stick_elements,
            s.force_tangential,
            k.force_tangential
        );
        assert!(s.force_tangential <= 0.004 * area * (1.0 + 1e-9));
    }
    assert!(static_records
        .iter()
        .zip(&kinetic_records)
        .any(|(s, k)| s.stick_elements > k.stick_elements));
    for results in [&with_static, &kinetic] {
        let sliding = results.sliding_friction_force.expect("gross slip");
        assert!(
            (sliding / (0.002 * area) - 1.0).abs() < 1e-9,
            "{sliding} vs τ0·A {}",
            0.002 * area
        );
    }
}

#[test]
fn static_keys_are_refused_below_their_kinetic_keys_or_with_another_law() {
    let below = error_of(TRESCA, &["friction.static_shear_strength=0.001"]);
    assert!(
        below.contains("friction.static_shear_strength must be finite and at least the kinetic friction.shear_strength = 0.002, got 0.001"),
        "{below}"
    );
    let other = error_of(TRESCA, &["friction.static_coefficient=0.5"]);
    assert!(
        other.contains("friction.static_coefficient is not a key of friction.law = \"shear_strength\""),
        "{other}"
    );
    let glued_text = TRESCA.replace(
        "law = \"shear_strength\"\nshear_strength = 0.002",
        "law = \"no_slip\"\nstatic_shear_strength = 0.004",
    );
    let glued = error_of(&glued_text, &[]);
    assert!(glued.contains("friction.static_shear_strength"), "{glued}");
}

/// `friction.slip_weakening_distance` reaches the solver: over a D_c far below any step's
/// slip (1e-15) the run is the static law's bit for bit; over one five times the slip
/// distance τ0·a/G the broken elements keep most of τs, so the force is at least the static
/// law's at every step and above it at some, never above τs·A.
#[test]
fn slip_weakening_reaches_the_solver() {
    let static_key = "friction.static_shear_strength=0.004";
    let (_, static_records) = shear_run(&[static_key]);
    let (_, vanishing) = shear_run(&[static_key, "friction.slip_weakening_distance=1e-15"]);
    let forces = |records: &[adhesim::StepRecord]| records.iter().map(|r| r.force_tangential).collect::<Vec<_>>();
    assert_eq!(forces(&static_records), forces(&vanishing));
    let (weakened, weakened_records) = shear_run(&[static_key, "friction.slip_weakening_distance=1e-3"]);
    for (w, s) in weakened_records.iter().zip(&static_records) {
        assert!(
            w.force_tangential >= s.force_tangential * (1.0 - 1e-9),
            "step {}: {} below the static law's {}",
            w.step,
            w.force_tangential,
            s.force_tangential
        );
        assert!(w.force_tangential <= 0.004 * weakened.contact_area * (1.0 + 1e-9));
    }
    assert!(weakened_records
        .iter()
        .zip(&static_records)
        .any(|(w, s)| w.force_tangential > s.force_tangential * 1.01));
}

#[test]
fn slip_weakening_is_refused_without_a_static_law_or_a_positive_distance() {
    let alone = error_of(TRESCA, &["friction.slip_weakening_distance=1e-3"]);
    assert!(
        alone.contains("friction.slip_weakening_distance = 0.001 weakens a static bound")
            && alone.contains("friction.static_shear_strength"),
        "{alone}"
    );
    for bad in ["0", "-1e-3", "inf"] {
        let message = error_of(
            TRESCA,
            &[
                "friction.static_shear_strength=0.004",
                &format!("friction.slip_weakening_distance={bad}"),
            ],
        );
        assert!(
            message.contains("friction.slip_weakening_distance must be finite and > 0"),
            "{bad}: {message}"
        );
    }
}

/// `protocol.drive_stiffness`: the indenter lags the drive by the spring's stretch F/k at
/// every shift step (1e-9: the tractions' sum against the solver's stretch), and
/// `curve.csv` gains `drive_x`. With a static shear strength three times the kinetic one
/// the force saws: slip events in which the whole contact slides at τ0·A and the indenter
/// jumps ahead, each followed by a stick phase.
#[test]
fn a_compliant_drive_lets_the_contact_stick_and_slip() {
    let stiffness = 0.5;
    let settings = [
        "friction.static_shear_strength=0.006",
        "protocol.drive_stiffness=0.5",
        "protocol.distance=0.01",
        "protocol.steps=50",
    ];
    let (results, records) = shear_run(&settings);
    let shifts: Vec<_> = records
        .iter()
        .filter(|r| r.phase == Some(adhesim::Phase::Shear))
        .collect();
    let sliding = 0.002 * results.contact_area;
    let mut events = 0;
    for (k, r) in shifts.iter().enumerate() {
        let stretch = r.drive_offset - r.offset;
        assert!(
            (r.force_tangential - stiffness * stretch).abs() <= 1e-9 * r.force_tangential.abs().max(sliding),
            "step {}: F {} against k(X − δ) {}",
            r.step,
            r.force_tangential,
            stiffness * stretch
        );
        assert!(r.force_tangential <= 0.006 * r.area * (1.0 + 1e-9));
        if k > 0 && r.force_tangential < shifts[k - 1].force_tangential && r.stick_elements == 0 {
            events += 1;
            let ratio = r.force_tangential / (0.002 * r.area);
            assert!(ratio > 0.99 && ratio <= 1.0 + 1e-9, "step {}: F/τ0A {ratio}", r.step);
            assert!(
                r.offset - shifts[k - 1].offset > 0.01 / 50.0,
                "step {}: no jump",
                r.step
            );
        }
    }
    assert_eq!(results.slip_events, events);
    assert!(events >= 3, "{events} slip events: no sawtooth");
    let scenario = load(TRESCA, "tresca.toml", Path::new("."), &settings.map(String::from)).unwrap();
    let names: Vec<_> = CurveColumns::of(&scenario).names().collect();
    assert_eq!(names.last(), Some(&"drive_x"));
    let rigid = load(TRESCA, "tresca.toml", Path::new("."), &[]).unwrap();
    assert!(!CurveColumns::of(&rigid).names().any(|name| name == "drive_x"));
}

#[test]
fn a_drive_stiffness_must_be_positive_and_not_inclined() {
    for bad in ["0", "-1", "nan"] {
        let error = error_of(TRESCA, &[&format!("protocol.drive_stiffness={bad}")]);
        assert!(error.contains("protocol.drive_stiffness"), "{bad}: {error}");
    }
    let inclined = error_of(TRESCA, &["protocol.drive_stiffness=1", "protocol.incline=10"]);
    assert!(
        inclined.contains("protocol.drive_stiffness") && inclined.contains("protocol.incline"),
        "{inclined}"
    );
    let elsewhere = error_of(
        &TRESCA
            .replace("kind = \"shear\"", "kind = \"roll\"")
            .replace("[friction]\nlaw = \"shear_strength\"\nshear_strength = 0.002\n", ""),
        &["protocol.drive_stiffness=1"],
    );
    assert!(elsewhere.contains("drive_stiffness"), "{elsewhere}");
}

/// A smooth sphere (R = 1, E = 3, ν = 1/2) translated at d = 0.005 (a ≈ 0.07 = 9Δ) over 0.1
/// in 20 steps of 0.005: each step outruns the slip distance τ0·a/G ≈ 1.4e-4 seventy
/// times over, so every element in contact slips at every step.
const SLIDE: &str = r#"
[grid]
n = 64
size = 0.5
[material]
youngs_modulus = 3.0
poisson_ratio = 0.5
[adhesion]
work_of_adhesion = 0.0
[indenter]
shape = "sphere"
radius = 1.0
[friction]
law = "shear_strength"
shear_strength = 0.002
[protocol]
kind = "translate"
depth = 0.005
depth_unit = "length"
approach_steps = 5
distance = 0.1
steps = 20
"#;

fn translation_run(text: &str, overrides: &[&str]) -> (TranslationResults, Vec<adhesim::StepRecord>) {
    let (RunResults::Translation(results), records) = outcome_of(text, overrides) else {
        panic!("not a translation")
    };
    (results, records)
}

/// A slide with a shear strength τ0: every moving step slides the whole contact, so the
/// interface adds τ0·A to the boundary force (to 1e-3: the slip directions keep a small
/// sideways part, as in the shear protocol's gross slip), friction's dissipation per
/// distance is that force, and the energy balance closes with it.
#[test]
fn a_translation_under_a_shear_strength_slides_at_tau0_times_area() {
    let (results, records) = translation_run(SLIDE, &[]);
    let frictionless = translation_run(
        &SLIDE.replace("[friction]\nlaw = \"shear_strength\"\nshear_strength = 0.002\n", ""),
        &[],
    )
    .1;
    for (r, plain) in records
        .iter()
        .zip(&frictionless)
        .filter(|(r, _)| r.phase != Some(adhesim::Phase::Approach))
    {
        assert_eq!(
            (r.stick_elements, r.slip_elements),
            (0, r.contact_elements),
            "step {}",
            r.step
        );
        assert_eq!(
            r.contact_elements, plain.contact_elements,
            "step {}: the normal problem is Goodman's",
            r.step
        );
        let interface = r.force_tangential - plain.force_tangential;
        assert!(
            (interface / (0.002 * r.area) - 1.0).abs() < 1e-3,
            "step {}: interface force {interface} against τ0·A {}",
            r.step,
            0.002 * r.area
        );
    }
    // Friction's dissipation per distance against τ0·A: 2e-3, a first-order error of the
    // step (a backward step's slip, 1.4e-3 at ΔX = 0.64Δ here, 3e-4 at 0.16Δ, 1e-4 at
    // 0.04Δ); the energy balance closes to the same order (6e-4 here).
    let interface = results.interface_friction_force.expect("with [friction]");
    assert!(
        (interface / (0.002 * results.real_contact_area) - 1.0).abs() < 2e-3,
        "{interface}"
    );
    let ratio = results.energy_balance_ratio.unwrap();
    assert!((ratio - 1.0).abs() < 2e-3, "energy balance {ratio}");
    assert!(results.measured_q.is_none() && results.frictional_dissipation.unwrap() > 0.0);
}

/// A roll does not shift the indenter's material where it touches (free rolling): under
/// any law the interface carries no traction, and the forces are the frictionless run's.
#[test]
fn a_roll_with_friction_carries_no_interface_traction() {
    let roll = SLIDE.replace("kind = \"translate\"", "kind = \"roll\"");
    let coulomb = roll.replace(
        "law = \"shear_strength\"\nshear_strength = 0.002",
        "law = \"coulomb\"\ncoefficient = 0.5",
    );
    let (results, records) = translation_run(&coulomb, &[]);
    let plain = translation_run(
        &roll.replace("[friction]\nlaw = \"shear_strength\"\nshear_strength = 0.002\n", ""),
        &[],
    )
    .1;
    for (r, p) in records.iter().zip(&plain) {
        assert_eq!(r.force_tangential, p.force_tangential, "step {}", r.step);
        assert_eq!(r.slip_elements, 0, "step {}", r.step);
    }
    assert_eq!(results.frictional_dissipation, Some(0.0));
}

#[test]
fn friction_on_a_translation_refuses_what_only_the_shear_offers() {
    // A mode mixity goes with a translation's Goodman step and rigid drive, not with the
    // coupled operator's rounds or a spring's.
    let adhesive = ["adhesion.work_of_adhesion=1e-4", "friction.mode_mixity=1"];
    let coupled = error_of(SLIDE, &[&adhesive[..], &["friction.coupling=\"full\""]].concat());
    assert!(
        coupled.contains("friction.mode_mixity") && coupled.contains("friction.coupling"),
        "{coupled}"
    );
    let spring = error_of(SLIDE, &[&adhesive[..], &["protocol.drive_stiffness=0.5"]].concat());
    assert!(
        spring.contains("protocol.drive_stiffness") && spring.contains("friction.mode_mixity"),
        "{spring}"
    );
    let analysis = error_of(&format!("{SLIDE}\n[analysis]\ntau0 = 0.002\n"), &[]);
    assert!(analysis.contains("[friction] and [analysis]"), "{analysis}");
    let indentation = error_of(
        &SLIDE.replace("kind = \"translate\"", "kind = \"indent_pulloff\""),
        &["protocol.max_depth=0.005"],
    );
    assert!(indentation.contains("protocol.kind"), "{indentation}");
}

/// A sphere (R = 1, E = 3, ν = 1/2) on a periodic grid of 128² (a = 24Δ: the depth of a
/// periodic grid sets the mean gap, so the contact is wider than Hertz's √(Rd) = 20Δ),
/// shifted to gross slip under Coulomb's μ = 0.3.
const PERIODIC: &str = r#"
[grid]
n = 128
size = 1.0
boundary = "periodic"
[material]
youngs_modulus = 3.0
poisson_ratio = 0.5
[adhesion]
work_of_adhesion = 0.0
[indenter]
shape = "sphere"
radius = 1.0
[friction]
law = "coulomb"
coefficient = 0.3
[protocol]
kind = "shear"
depth = 0.0244140625
depth_unit = "length"
approach_steps = 5
distance = 0.022
steps = 40
"#;

/// On a periodic grid the shift is the indenter's relative to the surface's mean
/// displacement, so δ(Q) carries the images' share; the tractions do not: Cattaneo–
/// Mindlin's stick radius c/a = (1 − Q/μP)^{1/3} with the run's own Q and P, within 4 %
/// while c ≥ 8Δ (the staircase edges at a = 24Δ, ~1/(2·24) per radius; 1.3 % seen), and
/// gross slip at μP (1e-4).
#[test]
fn a_shear_on_a_periodic_grid_follows_cattaneo_mindlin() {
    let (results, records) = outcome_of(PERIODIC, &[]);
    let RunResults::Shear(results) = results else {
        panic!("not a shear run")
    };
    let shifts: Vec<_> = records
        .iter()
        .filter(|r| r.phase == Some(adhesim::Phase::Shear))
        .collect();
    let limit = 0.3 * results.normal_force;
    for r in &shifts {
        let ratio = r.force_tangential / limit;
        let stick = (r.stick_elements as f64 / r.contact_elements as f64).sqrt();
        let expected = (1.0 - ratio.min(1.0)).cbrt();
        let radius = (r.area / std::f64::consts::PI).sqrt();
        if expected * radius >= 8.0 / 128.0 {
            assert!(
                (stick / expected - 1.0).abs() < 0.04,
                "step {}: c/a {stick} vs {expected}",
                r.step
            );
        }
    }
    let last = shifts.last().unwrap();
    assert_eq!(last.stick_elements, 0);
    assert!(
        (last.force_tangential / limit - 1.0).abs() < 1e-4,
        "Q/μP {}",
        last.force_tangential / limit
    );
}

/// A shear pressed in one approach step: no warning without adhesion (Goodman: the held
/// normal problem does not depend on the approach), one naming `protocol.approach_steps`
/// with it (the edge's attachment follows the approach).
#[test]
fn a_one_step_approach_is_warned_about_only_with_adhesion() {
    let warnings = |text: &str| {
        load(
            text,
            "friction.toml",
            Path::new("."),
            &["protocol.approach_steps=1".to_string()],
        )
        .unwrap()
        .warnings
    };
    assert!(warnings(PERIODIC).iter().all(|w| !w.contains("approach step")));
    let adhesive = warnings(TRESCA);
    assert!(
        adhesive
            .iter()
            .any(|w| w.contains("protocol.approach_steps") && !w.contains("max_depth")),
        "{adhesive:?}"
    );
}

/// `protocol.drive_stiffness` on a translate: the spring balances the whole tangential
/// force at every stroke step, F_T = k(X − x), to the rounds' tolerance (the profile stands
/// within 1e-6Δ of the indenter: k·1e-6Δ, with 1e-9 of F for the solves). With a soft
/// spring and a static strength three times τ0 the slide sticks and slips: the force falls
/// in events where the indenter jumps ahead of the drive's step, to the kinetic τ0·A within
/// 2 % (the contact that comes to rest after the jump gains or loses elements at the edges,
/// a few of its ~265), and rises in the stick steps between, where the indenter lags.
#[test]
fn a_compliant_drive_lets_a_slide_stick_and_slip() {
    let stiffness = 0.002;
    let (_, records) = translation_run(
        SLIDE,
        &["friction.static_shear_strength=0.006", "protocol.drive_stiffness=0.002"],
    );
    let element = 0.5 / 64.0;
    let drive_step = 0.1 / 20.0;
    let strokes: Vec<_> = records
        .iter()
        .filter(|r| r.phase != Some(adhesim::Phase::Approach))
        .collect();
    let (mut events, mut sticks) = (0, 0);
    for (k, r) in strokes.iter().enumerate() {
        let spring = stiffness * (r.drive_offset - r.offset);
        assert!(
            (r.force_tangential - spring).abs() <= stiffness * 1e-6 * element + 1e-9 * r.force_tangential.abs(),
            "step {}: F_T {} against k(X − x) {spring}",
            r.step,
            r.force_tangential
        );
        let Some(before) = k.checked_sub(1).map(|j| strokes[j]) else {
            continue;
        };
        if r.force_tangential < before.force_tangential {
            events += 1;
            assert!(r.offset - before.offset > drive_step, "step {}: no jump", r.step);
            let ratio = r.force_tangential / (0.002 * r.area);
            assert!((ratio - 1.0).abs() < 0.02, "step {}: F/τ0A {ratio}", r.step);
        } else {
            sticks += 1;
            assert!(r.offset - before.offset < drive_step, "step {}: no lag", r.step);
        }
    }
    assert!(events >= 3 && sticks >= 3, "{events} events, {sticks} stick steps");
}

/// A stiff drive (k = 10⁴) is the rigid one in the limit of small steps: its step settles
/// the contact at the drive's position after the tangential move, so the elements the
/// contact gains at its front join stuck and unloaded, and its per-step force falls short
/// of the rigid slide's by a first-order error of the step (3.7, 2.0, 1.1 % at 20, 40, 80
/// steps: the shortfall at least 1.6 times smaller for each halving); friction's
/// dissipation per distance is the rigid slide's within 2e-3 at every step size (1.7e-3 at
/// 20 steps, 2e-4 at 40: the size of the rigid slide's own first-order error against τ0·A).
#[test]
fn a_stiff_drive_slides_as_the_rigid_one_as_the_step_shrinks() {
    let mut shortfalls = Vec::new();
    for steps in ["20", "40", "80"] {
        let steps = format!("protocol.steps={steps}");
        let (rigid, _) = translation_run(SLIDE, &[&steps]);
        let (stiff, _) = translation_run(SLIDE, &[&steps, "protocol.drive_stiffness=1e4"]);
        let force = |r: &TranslationResults| r.mean_tangential_force.expect("a mean force");
        shortfalls.push(1.0 - force(&stiff) / force(&rigid));
        let dissipation = |r: &TranslationResults| r.interface_friction_force.expect("with [friction]");
        assert!(
            (dissipation(&stiff) / dissipation(&rigid) - 1.0).abs() < 2e-3,
            "{steps}: {} against {}",
            dissipation(&stiff),
            dissipation(&rigid)
        );
    }
    assert!(shortfalls[0] > 0.0, "{shortfalls:?}");
    for pair in shortfalls.windows(2) {
        assert!(pair[1] > 0.0 && pair[0] / pair[1] > 1.6, "{shortfalls:?}");
    }
}

/// The drive's spring belongs to a slide or translate with `[friction]`: refused on a
/// roll and without `[friction]`, naming the key.
#[test]
fn a_translations_drive_stiffness_is_refused_where_it_cannot_pull() {
    let roll = error_of(
        &SLIDE.replace("kind = \"translate\"", "kind = \"roll\""),
        &["protocol.drive_stiffness=1"],
    );
    assert!(
        roll.contains("protocol.drive_stiffness") && roll.contains("roll"),
        "{roll}"
    );
    let frictionless = error_of(
        &SLIDE.replace("[friction]\nlaw = \"shear_strength\"\nshear_strength = 0.002\n", ""),
        &["protocol.drive_stiffness=1"],
    );
    assert!(
        frictionless.contains("protocol.drive_stiffness") && frictionless.contains("[friction]"),
        "{frictionless}"
    );
    let zero = error_of(SLIDE, &["protocol.drive_stiffness=0"]);
    assert!(zero.contains("protocol.drive_stiffness"), "{zero}");
}
