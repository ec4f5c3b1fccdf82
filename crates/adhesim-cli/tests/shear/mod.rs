//! End-to-end tests of friction at the interface (`[friction]`, `[protocol] kind =
//! "shear"`; docs/tangential.md): Cattaneo–Mindlin through `adhesim run`, gross sliding at
//! τ0·A, and the errors naming the keys at fault. Part of the translation test binary.

use super::common::{adhesim, assert_fails_with, column_values, read_csv, read_json, repo, stderr, write};

/// The shear scenario's text with `[friction]` and `[adhesion]` replaced.
fn shear_text(friction: &str, work_of_adhesion: f64) -> String {
    let text = std::fs::read_to_string(repo().join("scenarios/shear.toml")).unwrap();
    let start = text.find("[friction]").unwrap();
    let end = text.find("[protocol]").unwrap();
    let text = format!("{}[friction]\n{friction}\n\n{}", &text[..start], &text[end..]);
    text.replace(
        "work_of_adhesion = 0.0",
        &format!("work_of_adhesion = {work_of_adhesion:e}"),
    )
}

#[test]
fn shear_run_follows_cattaneo_mindlin() {
    // scenarios/shear.toml: a = 40Δ, ν = 1/2, G = 1, μ = 0.3, shifted to 1.2δ*.
    // Cattaneo–Mindlin (Johnson 1985 §7.2) with the run's own P and a (from its area):
    // δ(Q) = δ*[1 − (1 − Q/μP)^{2/3}], δ* = 3μP(2 − ν)/(16Ga), and c/a = (1 − Q/μP)^{1/3}
    // with c from the stick area. Tolerance 2 % (the goal at a/Δ ≥ 32: the staircase edges
    // of contact and stick zone); c/a is checked while the stick zone's radius spans ≥ 12
    // elements (below, its staircase error grows as Δ/c: 4.6 % at c = 8.6Δ, docs/validation.md).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shear");
    let scenario = repo().join("scenarios/shear.toml");
    let output = adhesim(&[
        "run",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let (header, rows) = read_csv(&out.join("curve.csv"));
    for name in [
        "x",
        "force_normal",
        "force_tangential",
        "n_contact",
        "n_stick",
        "n_slip",
    ] {
        assert!(header.iter().any(|h| h == name), "curve.csv lacks {name}");
    }
    let x = column_values(&header, &rows, "x");
    let normal = column_values(&header, &rows, "force_normal");
    let tangential = column_values(&header, &rows, "force_tangential");
    let contact = column_values(&header, &rows, "n_contact");
    let stick = column_values(&header, &rows, "n_stick");
    let slip = column_values(&header, &rows, "n_slip");
    let area = column_values(&header, &rows, "area");
    let (mu, g, nu, element) = (0.3, 1.0, 0.5, 0.5 / 128.0);
    let last = rows.len() - 1;
    let radius = (area[last] / std::f64::consts::PI).sqrt();
    let full_slip = 3.0 * mu * normal[last] * (2.0 - nu) / (16.0 * g * radius);
    let mut checked = 0;
    for k in 20..rows.len() {
        assert_eq!(
            stick[k] + slip[k],
            contact[k],
            "row {k}: every contact element sticks or slips"
        );
        let ratio = tangential[k] / (mu * normal[k]);
        if x[k] < full_slip {
            let expected = full_slip * (1.0 - (1.0 - ratio).powf(2.0 / 3.0));
            assert!(
                (x[k] / expected - 1.0).abs() < 0.02,
                "row {k}: δ {} vs {expected}",
                x[k]
            );
            let expected_stick = (1.0 - ratio).cbrt();
            if expected_stick * radius >= 12.0 * element {
                let stick_ratio = (stick[k] / contact[k]).sqrt();
                assert!(
                    (stick_ratio / expected_stick - 1.0).abs() < 0.02,
                    "row {k}: c/a {stick_ratio} vs {expected_stick}"
                );
                checked += 1;
            }
        } else {
            assert_eq!(stick[k], 0.0, "row {k}: gross slip beyond δ*");
        }
    }
    assert!(checked >= 12, "only {checked} rows in partial slip");
    // In gross slip the tractions keep a little of the last stick zone's sideways
    // relaxation, which the further shift wears off (docs/tangential.md): at 1.2δ* Q/μP is
    // 1 to 1e-3 (0.99977 measured).
    let ratio = tangential[last] / (mu * normal[last]);
    assert!((ratio - 1.0).abs() < 1e-3, "Q/μP = {ratio} at 1.2δ*");
    let summary = read_json(&out.join("summary.json"));
    let results = &summary["results"];
    let sliding = results["sliding_friction_force"].as_f64().unwrap();
    assert!((sliding / tangential[last] - 1.0).abs() < 1e-12);
    assert!(results["complementarity"]["stick_residual"].as_f64().unwrap() < 1e-8);
    // Goodman's approximation: the shear leaves the normal contact as it is.
    assert_eq!(results["contact_area_reduction"].as_f64(), Some(1.0));
}

#[test]
fn shear_strength_slides_at_tau0_times_area_with_tensile_elements() {
    // A JKR contact (γ0 > 0) has a tensile ring at its edge; the constant shear strength
    // bounds the traction there too, so in gross slip F_T = τ0·A exactly (to the solver's
    // tolerance, 1e-9 relative).
    let dir = tempfile::tempdir().unwrap();
    let text = shear_text("law = \"shear_strength\"\nshear_strength = 0.002", 2e-3);
    let scenario = write(dir.path(), "tresca.toml", &text);
    let out = dir.path().join("tresca");
    let output = adhesim(&[
        "run",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--set",
        "grid.n=64",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let results = read_json(&out.join("summary.json"))["results"].clone();
    let area = results["contact_area"].as_f64().unwrap();
    let sliding = results["sliding_friction_force"].as_f64().expect("gross slip reached");
    assert!(
        (sliding / (0.002 * area) - 1.0).abs() < 1e-9,
        "F_T {sliding} vs τ0·A {}",
        0.002 * area
    );
    assert!((results["mean_shear_stress"].as_f64().unwrap() / 0.002 - 1.0).abs() < 1e-9);
}

#[test]
fn friction_errors_name_their_keys() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, String, &[&str]); 5] = [
        (
            "full.toml",
            shear_text("law = \"coulomb\"\ncoefficient = 0.3\ncoupling = \"full\"", 0.0),
            &["friction.coupling", "not implemented"],
        ),
        (
            "missing.toml",
            shear_text("law = \"coulomb\"", 0.0),
            &["friction.coefficient"],
        ),
        (
            "extra.toml",
            shear_text("law = \"coulomb\"\ncoefficient = 0.3\nshear_strength = 1.0", 0.0),
            &["friction.shear_strength"],
        ),
        (
            "negative.toml",
            shear_text("law = \"coulomb\"\ncoefficient = -0.3", 0.0),
            &["friction.coefficient", "-0.3"],
        ),
        (
            "modulus.toml",
            shear_text("law = \"coulomb\"\ncoefficient = 0.3", 0.0)
                .replace("youngs_modulus = 3.0", "contact_modulus = 4.0")
                .replace("poisson_ratio = 0.5 ", "# "),
            &["material.poisson_ratio"],
        ),
    ];
    for (name, text, fragments) in cases {
        let path = write(dir.path(), name, &text);
        assert_fails_with(
            &adhesim(&[
                "run",
                path.to_str().unwrap(),
                "--out",
                dir.path().join(name).to_str().unwrap(),
            ]),
            fragments,
        );
    }
    let shear = repo().join("scenarios/shear.toml");
    let out = dir.path().join("p");
    assert_fails_with(
        &adhesim(&[
            "run",
            shear.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--set",
            "grid.boundary=\"periodic\"",
        ]),
        &["grid.boundary"],
    );
    let roll = repo().join("scenarios/fig6.toml");
    let text = std::fs::read_to_string(roll).unwrap() + "\n[friction]\nlaw = \"coulomb\"\ncoefficient = 0.3\n";
    let path = write(dir.path(), "roll.toml", &text);
    assert_fails_with(
        &adhesim(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap()]),
        &["protocol.kind", "[friction]"],
    );
}
