//! Values at the edges of the numbers: non-finite and subnormal results, scaled lengths,
//! unresolved contacts, degenerate laws, and type errors named in words.

use super::*;

/// `adhesim reference` printed inf and NaN rows where the closed forms overflow.
#[test]
fn reference_prints_no_non_finite_rows() {
    let output = adhesim(&["reference", "hertz", "--radius", "1e300", "--max-radius", "1e300"]);
    assert_fails_with(&output, &["leaves double precision", "d = inf", "--radius 1e300"]);
    assert!(output.stdout.is_empty(), "nothing printed before the error");
    let output = adhesim(&["reference", "jkr", "--radius", "1e-300", "--work-of-adhesion", "1e300"]);
    assert_fails_with(
        &output,
        &["is not a usable number", "--radius 1e-300", "--work-of-adhesion 1e300"],
    );
}

/// Type errors were blamed on another key whose value the message happened to quote.
#[test]
fn type_errors_name_the_key_the_user_wrote() {
    let rough = scenarios_dir().join("rough_sphere.toml");
    let punch = scenarios_dir().join("fig12_homogeneous.toml");
    let ratio = scenarios_dir().join("fig12_ratio13.toml");
    let hertz = hertz();
    let cases: [(&Path, &str, &str); 7] = [
        (
            Path::new(&hertz),
            "protocol.steps=0.01",
            "protocol.steps = 0.01: invalid type",
        ),
        (
            Path::new(&hertz),
            "indenter.shape=nan",
            "indenter.shape = nan: invalid type",
        ),
        (&rough, "roughness.seed=nan", "roughness.seed = nan: invalid type"),
        (
            &punch,
            "indenter.semi_axes=[\"a\",\"b\"]",
            "indenter.semi_axes = [\"a\", \"b\"]: invalid type",
        ),
        (
            &punch,
            "indenter.semi_axes=[1,\"a\"]",
            "indenter.semi_axes = [1, \"a\"]: invalid type",
        ),
        (
            &ratio,
            "adhesion.work_of_adhesion=\"x\"",
            "adhesion.work_of_adhesion = \"x\": invalid type",
        ),
        (
            Path::new(&hertz),
            "protocol.max_depth={a = 1}",
            "protocol.max_depth = { a = 1 }: invalid type: map",
        ),
    ];
    for (scenario, set, expected) in cases {
        let output = adhesim(&["run", scenario.to_str().unwrap(), "--set", set]);
        assert_fails_with(&output, &[expected]);
    }
}

/// `topography any.npy --spacing 1e300` made the PSD plot's tick generation allocate without
/// bound; heights near 1e300 gave an rms height of inf with exit 0.
#[test]
fn absurd_topography_spacings_and_heights_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let heights: Vec<f64> = (0..256).map(|k| ((k * 37 % 101) as f64 - 50.0) * 1e-3).collect();
    let plain = dir.path().join("plain.npy");
    std::fs::write(&plain, npy_bytes((16, 16), &heights)).unwrap();
    let out = dir.path().join("out");
    let limit = Duration::from_secs(60);
    for spacing in ["1e300", "1e-300"] {
        let args = [
            "topography",
            plain.to_str().unwrap(),
            "--spacing",
            spacing,
            "--height-unit",
            "m",
            "--out",
            out.to_str().unwrap(),
        ];
        let output = adhesim_within(&args, limit);
        assert_fails_with(&output, &["plain.npy: spacing", "outside the floating-point range"]);
    }
    let huge: Vec<f64> = heights.iter().map(|h| h * 1e303).collect();
    let path = dir.path().join("huge.npy");
    std::fs::write(&path, npy_bytes((16, 16), &huge)).unwrap();
    let args = [
        "topography",
        path.to_str().unwrap(),
        "--spacing",
        "1",
        "--height-unit",
        "m",
        "--out",
        out.to_str().unwrap(),
    ];
    assert_fails_with(
        &adhesim_within(&args, limit),
        &["huge.npy: a height of", "beyond 1e150"],
    );
}

/// A sphere whose contact radius stays under an element gave 63× to 1981× the Hertz force
/// without a word; now a warning on stderr and in summary.json (Hertz and JKR).
#[test]
fn an_unresolved_contact_radius_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [
        ("hertz", "adhesion.work_of_adhesion=0"),
        ("jkr", "adhesion.work_of_adhesion=1e-6"),
    ] {
        let out = dir.path().join(name);
        let args = [
            "run",
            &hertz(),
            "--set",
            "protocol.max_depth=1e-5",
            "--set",
            "grid.n=16",
            "--set",
            extra,
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        let output = adhesim(&args);
        assert!(output.status.success(), "{}", stderr(&output));
        assert!(
            stderr(&output).contains("contact radius at the largest depth"),
            "{}",
            stderr(&output)
        );
        let summary = read_json(&out.join("summary.json"));
        let warnings = summary["warnings"].as_array().unwrap();
        let expected = if name == "hertz" {
            "the Hertz contact radius"
        } else {
            "the JKR contact radius"
        };
        assert!(
            warnings.iter().any(|w| w.as_str().unwrap().contains(expected)),
            "{warnings:?}"
        );
    }
    // The shipped Hertz scenario resolves its contact (a = 21 elements): no such warning.
    let output = adhesim(&[
        "run",
        &hertz(),
        "--out",
        dir.path().join("ok").to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        !stderr(&output).contains("contact radius at the largest depth"),
        "{}",
        stderr(&output)
    );
}

/// A sphere of radius 1e-300 and an rms height of 1e300 failed mid-run or with a message
/// about another key; now refused before the run, naming theirs.
#[test]
fn heights_beyond_the_solver_range_are_refused_naming_the_keys() {
    let output = adhesim(&["run", &hertz(), "--set", "indenter.radius=1e-300"]);
    assert_fails_with(&output, &["the indenter's heights span", "indenter.radius = 1e-300"]);
    let rough = scenarios_dir().join("rough_sphere.toml");
    for value in ["1e300", "1e-300"] {
        let output = adhesim(&[
            "run",
            rough.to_str().unwrap(),
            "--set",
            &format!("roughness.rms_height={value}"),
        ]);
        let expected = format!("roughness.rms_height = {value} lies outside the magnitudes 1e-150..1e150");
        assert_fails_with(&output, &[&expected]);
    }
}

/// Second robustness audit (docs/reliability.md): all lengths scaled by 1e-20 (inside the
/// documented window; γ scaled with them, E* kept). The normalised results must equal the
/// unscaled file's, and forces scale by 1e-40 (F ∝ γR), to the CG tolerance (relative residual
/// 1e-6: the two runs stop their solves at different roundings; measured 3e-9).
#[test]
fn lengths_scaled_by_1e_minus_20_give_the_same_normalised_results() {
    let temp = tempfile::tempdir().unwrap();
    let scenario = scenarios_dir().join("jkr.toml");
    let scenario = scenario.to_str().unwrap();
    let plain = temp.path().join("plain");
    let scaled = temp.path().join("scaled");
    let base = ["run", scenario, "--set", "grid.n=64", "--quiet", "--out"];
    let output = adhesim(&[&base[..], &[plain.to_str().unwrap()]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
    let tiny = [
        "--set",
        "grid.size=0.25e-20",
        "--set",
        "indenter.radius=1e-20",
        "--set",
        "adhesion.work_of_adhesion=3.5367765131532306e-25",
    ];
    let output = adhesim(&[&base[..], &[scaled.to_str().unwrap()], &tiny[..]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
    let plain = read_json(&plain.join("summary.json"))["results"].clone();
    let scaled = read_json(&scaled.join("summary.json"))["results"].clone();
    let value = |results: &serde_json::Value, key: &str| results[key].as_f64().unwrap();
    for (key, scale) in [
        ("gamma_approach_norm", 1.0),
        ("gamma_pulloff_norm", 1.0),
        ("adhesive_force_ratio", 1.0),
        ("max_adhesive_force", 1e-40),
        ("pull_off_depth", 1e-20),
    ] {
        let ratio = value(&scaled, key) / (scale * value(&plain, key));
        assert!((ratio - 1.0).abs() < 1e-6, "{key}: scaled/plain = {ratio}");
    }
}

/// A grid size of 1e-310 was refused as "[grid]: grid element size size/n … Δ² = 0e0",
/// where every other message names `grid.size` and prints numbers as a person writes them.
#[test]
fn a_grid_of_subnormal_elements_is_named_as_grid_size_in_plain_numbers() {
    let output = adhesim(&["run", &hertz(), "--set", "grid.size=1e-310"]);
    assert_fails_with(
        &output,
        &[
            "grid.size = 1e-310 with grid.n = 64 makes elements of side 1.5625e-312 and area 0",
            "choose a grid.size commensurate with grid.n",
        ],
    );
    assert!(!stderr(&output).contains("0e0"), "{}", stderr(&output));
}

/// Degenerate law parameters: `cohesive_stress = 5e-324` gave F_ad = 0 (Dugdale) and
/// `range = 5e-324` NaN rows (exponential); refused before the run, naming the key.
#[test]
fn degenerate_law_parameters_are_refused_naming_the_key() {
    let dugdale = scenarios_dir().join("cohesive").join("maugis_lambda1.toml");
    let output = adhesim(&[
        "run",
        dugdale.to_str().unwrap(),
        "--set",
        "adhesion.cohesive_stress=5e-324",
    ]);
    assert_fails_with(&output, &["adhesion.cohesive_stress = 5e-324", "1e-150..1e150"]);
}

/// A sphere with `protocol.step = 1e6` |d_JKR| "ran" one step each way and reported a
/// dissipated energy of 57,198 without a word: warned on stderr and in summary.json.
#[test]
fn a_single_approach_step_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let jkr = scenarios_dir().join("jkr.toml");
    let output = run_quiet(&jkr, &out, &["--set", "grid.n=32", "--set", "protocol.steps=1"]);
    let expected = "in 1 approach step of";
    assert!(stderr(&output).contains(expected), "{}", stderr(&output));
    if output.status.success() {
        let summary = read_json(&out.join("summary.json"));
        let warnings = summary["warnings"].as_array().unwrap();
        assert!(
            warnings.iter().any(|w| w.as_str().unwrap().contains(expected)),
            "{warnings:?}"
        );
    }
}

/// `plot master` drew NaN, inf, text and α ≤ 0 rows, and exited 0 with no figure when
/// every α was 0: each such row is an error naming the table, its line, the case and the
/// column; a table of good rows is drawn.
#[test]
fn plot_master_rejects_rows_it_cannot_draw() {
    let dir = tempfile::tempdir().unwrap();
    let header = "case,johnson_parameter,gamma_approach_norm,gamma_pulloff_norm,adhesive_force_ratio,status,series\n";
    let good = "0000-a,0.5,0.9,1.2,1.1,ok,s\n0001-b,1.0,0.8,1.4,1.2,ok,s\n";
    let out = dir.path().join("plots");
    let plot = |name: &str, rows: &str| {
        let table = write(dir.path(), name, &format!("{header}{good}{rows}"));
        adhesim(&[
            "plot",
            "master",
            table.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
    };
    for (row, column, value) in [
        ("0002-c,nan,0.8,1.4,1.2,ok,s\n", "johnson_parameter", "\"nan\""),
        ("0002-c,0,0.8,1.4,1.2,ok,s\n", "johnson_parameter", "\"0\""),
        ("0002-c,-1,0.8,1.4,1.2,ok,s\n", "johnson_parameter", "\"-1\""),
        ("0002-c,2.0,inf,1.4,1.2,ok,s\n", "gamma_approach_norm", "\"inf\""),
        ("0002-c,2.0,0.8,abc,1.2,ok,s\n", "gamma_pulloff_norm", "\"abc\""),
    ] {
        let output = plot("t.csv", row);
        let expected = format!("t.csv line 4 (case 0002-c): {column} = {value} cannot be drawn");
        assert_fails_with(&output, &[&expected]);
    }
    // A failed case's row is not drawn and not checked; an empty value is no value.
    let output = plot("t.csv", "0002-c,nan,,,,error,s\n0003-d,2.0,,1.3,,ok,s\n");
    assert!(output.status.success(), "{}", stderr(&output));
    // Every α 0: nothing to draw is an error, not exit 0 without a figure.
    let table = write(
        dir.path(),
        "zero.csv",
        &format!("{header}0000-a,0,0.9,1.2,1.1,error,s\n"),
    );
    let output = adhesim(&[
        "plot",
        "master",
        table.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_fails_with(&output, &["nothing to draw"]);
}

/// A topography indenter whose contact is below one element (a single low point of a
/// measured map) ran without a word: a warning on stderr and in summary.json.
#[test]
fn a_contact_of_one_element_on_a_map_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let n = 16;
    let mut values = vec![1e-3; n * n];
    // Four points at 0: the element whose centre lies among them is the one lowest.
    for (row, column) in [
        (n / 2, n / 2),
        (n / 2, n / 2 - 1),
        (n / 2 - 1, n / 2),
        (n / 2 - 1, n / 2 - 1),
    ] {
        values[row * n + column] = 0.0;
    }
    std::fs::write(dir.path().join("spike.npy"), npy_bytes((n, n), &values)).unwrap();
    let scenario = format!(
        "[grid]\nn = {n}\nsize = 1.0\n[material]\ncontact_modulus = 1.0\n[adhesion]\nwork_of_adhesion = 0.0\n\
         [indenter]\nshape = \"topography\"\nfile = \"spike.npy\"\nspacing = {}\n\
         [protocol]\nkind = \"indent_pulloff\"\nmax_depth = 1e-5\ndepth_unit = \"length\"\nsteps = 4\n",
        1.0 / n as f64
    );
    let path = write(dir.path(), "spike.toml", &scenario);
    let out = dir.path().join("run");
    let output = adhesim(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let expected = "the contact never spanned more than 1 element";
    assert!(stderr(&output).contains(expected), "{}", stderr(&output));
    let summary = read_json(&out.join("summary.json"));
    assert!(
        summary["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|w| w.as_str().unwrap().contains(expected)),
        "{summary}"
    );
}

/// Type errors spoke Rust (`expected i64`, `floating point`): now in words.
#[test]
fn type_errors_name_types_in_words() {
    let output = adhesim(&["run", &hertz(), "--set", "protocol.steps=0.01"]);
    assert_fails_with(
        &output,
        &["protocol.steps = 0.01: invalid type: number `0.01`, expected an integer"],
    );
    let message = stderr(&output);
    assert!(
        !message.contains("i64") && !message.contains("floating point"),
        "{message}"
    );
    let output = adhesim(&["run", &hertz(), "--set", "indenter.radius=\"x\""]);
    assert_fails_with(&output, &["indenter.radius = \"x\": invalid type", "expected a number"]);
}
