//! End-to-end tests of force control in a shear (`protocol.tangential_force`,
//! docs/tangential.md): Cattaneo–Mindlin and Mindlin–Deresiewicz under an imposed force
//! through `adhesim run`, and the refusals naming their keys. A module of the translation
//! tests.

use super::common::{adhesim, assert_fails_with, column_values, read_csv, read_json, repo, run_quiet, stderr, write};

#[test]
fn an_imposed_force_follows_cattaneo_mindlin_and_mindlin_deresiewicz() {
    // scenarios/friction/fretting_force.toml: the sphere of scenarios/shear.toml (a = 40Δ,
    // ν = 1/2, G = 1, μ = 0.3) under Q ramped to Q* = 0.75μP in 12 steps, then cycled twice
    // between ±Q*. The force of every step is the imposed one to 1e-8 relative (the search's
    // tolerance). With the run's P and a (from its area), the loading shift follows
    // Cattaneo–Mindlin, δ = δ*[1 − (1 − Q/μP)^{2/3}], and a cycle dissipates
    // Mindlin–Deresiewicz's W (Johnson 1985 §7.2, §7.4): tolerances 2 % and 3 %, as under
    // displacement control (the staircase edges at a/Δ ≥ 32). The loop closes: the shift at
    // +Q* after each cycle repeats to 1e-4 δ*, as the displacement-controlled loop is
    // symmetric to 1e-4 (the slip annulus's edge elements settle over the cycles; measured
    // 1.3e-5 δ*).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fretting_force");
    let output = run_quiet(&repo().join("scenarios/friction/fretting_force.toml"), &out, &[]);
    assert!(output.status.success(), "{}", stderr(&output));
    let (header, rows) = read_csv(&out.join("curve.csv"));
    let x = column_values(&header, &rows, "x");
    let force = column_values(&header, &rows, "force_tangential");
    let normal = column_values(&header, &rows, "force_normal");
    let area = column_values(&header, &rows, "area");
    let (approach, steps, cycles) = (20, 12, 2);
    assert_eq!(rows.len(), approach + steps * (1 + 4 * cycles));
    let steps = steps as i64;
    let (mu, g, nu, amplitude) = (0.3, 1.0, 0.5, 0.75);
    let last = rows.len() - 1;
    let limit = mu * normal[last];
    let radius = (area[last] / std::f64::consts::PI).sqrt();
    let full_slip = 3.0 * limit * (2.0 - nu) / (16.0 * g * radius);
    for k in approach..rows.len() {
        let travelled = (k + 1 - approach) as i64;
        // The path of the imposed force: up to Q*, then each cycle down to −Q* and back.
        let imposed = if travelled <= steps {
            travelled
        } else {
            let within = (travelled - steps - 1) % (4 * steps) + 1;
            if within <= 2 * steps {
                steps - within
            } else {
                within - 3 * steps
            }
        };
        let expected = amplitude * limit * imposed as f64 / steps as f64;
        assert!(
            (force[k] - expected).abs() <= 1e-8 * limit,
            "row {k}: force {} vs imposed {expected}",
            force[k]
        );
        if travelled <= steps {
            let ratio = force[k] / limit;
            let shift = full_slip * (1.0 - (1.0 - ratio).powf(2.0 / 3.0));
            assert!(
                (x[k] / shift - 1.0).abs() < 0.02,
                "row {k}: δ {} vs Cattaneo–Mindlin {shift}",
                x[k]
            );
        }
    }
    let (first_cycle, second_cycle) = (approach + 5 * steps as usize - 1, last);
    assert!(
        (x[first_cycle] - x[second_cycle]).abs() < 1e-4 * full_slip,
        "the loop closes: {} vs {}",
        x[first_cycle],
        x[second_cycle]
    );
    let x_star = force[last] / limit;
    let expected = 9.0 * limit * limit * (2.0 - nu) / (10.0 * g * radius)
        * (1.0 - (1.0 - x_star).powf(5.0 / 3.0) - 5.0 * x_star / 6.0 * (1.0 + (1.0 - x_star).powf(2.0 / 3.0)));
    let results = read_json(&out.join("summary.json"))["results"].clone();
    let dissipated = results["fretting_dissipation_per_cycle"].as_f64().unwrap();
    assert!(
        (dissipated / expected - 1.0).abs() < 0.03,
        "loop energy {dissipated} vs Mindlin–Deresiewicz {expected}"
    );
}

#[test]
fn force_control_errors_name_their_keys() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(repo().join("scenarios/friction/fretting_force.toml")).unwrap();
    let with = |from: &str, to: &str| text.replace(from, to);
    let unit = "tangential_force_unit = \"friction_limit\"";
    let cases: [(&str, String, &[&str]); 8] = [
        (
            "both.toml",
            with("steps = 12", "steps = 12\ndistance = 0.01"),
            &["protocol.tangential_force", "protocol.distance"],
        ),
        (
            "neither.toml",
            with("tangential_force = 0.75", "").replace(unit, ""),
            &["protocol.distance", "protocol.tangential_force"],
        ),
        (
            "limit.toml",
            with("tangential_force = 0.75", "tangential_force = 1.0"),
            &["protocol.tangential_force", "1", "gross slip"],
        ),
        (
            "negative.toml",
            with("tangential_force = 0.75", "tangential_force = -0.5"),
            &["protocol.tangential_force", "-0.5"],
        ),
        (
            "static.toml",
            with("coefficient = 0.3", "coefficient = 0.3\nstatic_coefficient = 0.4"),
            &["protocol.tangential_force", "friction.static_*"],
        ),
        (
            "spring.toml",
            with("steps = 12", "steps = 12\ndrive_stiffness = 1.0"),
            &["protocol.tangential_force", "protocol.drive_stiffness"],
        ),
        (
            "incline.toml",
            with("steps = 12", "steps = 12\nincline = 10.0"),
            &["protocol.tangential_force", "protocol.incline"],
        ),
        (
            "unit.toml",
            with("tangential_force = 0.75", "distance = 0.01"),
            &["protocol.tangential_force_unit", "protocol.tangential_force"],
        ),
    ];
    for (name, text, fragments) in cases {
        let path = write(dir.path(), name, &text);
        let out = dir.path().join(name.trim_end_matches(".toml"));
        assert_fails_with(
            &adhesim(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap()]),
            fragments,
        );
    }
    // An absolute force beyond μP is known only once the approach has set P: the run stops
    // at the first step that cannot hold it, naming the force and the limit.
    let beyond = with(unit, "").replace("tangential_force = 0.75", "tangential_force = 1.0");
    let path = write(dir.path(), "beyond.toml", &beyond);
    let out = dir.path().join("beyond");
    assert_fails_with(
        &adhesim(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap()]),
        &["imposed tangential force", "what the interface holds"],
    );
}
