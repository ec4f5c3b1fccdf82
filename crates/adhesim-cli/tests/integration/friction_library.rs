//! A library user reproduces `summary.json` without the command line: the friction
//! analysis of `adhesim::analysis::friction` on the rolling case of paper Fig. 6
//! (`scenarios/fig6.toml`), built here from library objects only and reduced to a 32×32
//! grid, 20 approach and 40 rolling steps so that it runs in about a second, against the
//! `summary.json` that `adhesim run scenarios/fig6.toml --set grid.n=32
//! --set protocol.approach_steps=20 --set protocol.steps=40` writes in the same test.

use std::path::Path;
use std::process::Command;

use adhesim::analysis::friction::{TranslationInputs, TranslationResults};
use adhesim::analysis::reference::Jkr;
use adhesim::geometry::WavySphere;
use adhesim::{
    AdhesiveParams, Boundary, ElasticMaterial, Grid, HalfSpace, Kinematics, NormalSolver, Problem, StepRecord,
    TranslatingContact, Translation,
};

use crate::common;
use common::{read_json, scenarios_dir};

fn reduced_fig6() -> TranslationResults {
    let grid = Grid::new(32, 0.4, Boundary::Free).unwrap();
    let material = ElasticMaterial::new(1.0).unwrap();
    let work_of_adhesion = 2e-5;
    let radius = 1.0;
    let jkr = Jkr {
        radius,
        contact_modulus: 1.0,
        work_of_adhesion,
    };
    let wavelength = 0.05;
    let contact = TranslatingContact::new(
        WavySphere::new(radius, 5.627e-4, wavelength, 0.0).unwrap(),
        Kinematics::Roll,
    );
    let mut problem = Problem::translating(Box::new(HalfSpace::new(grid, material)), contact)
        .unwrap()
        .with_work_of_adhesion(vec![work_of_adhesion; grid.len()])
        .unwrap();
    let start_depth = problem.heights().iter().copied().fold(f64::INFINITY, f64::min);
    let protocol = Translation {
        start_depth,
        depth: 5.0 * jkr.critical_depth().abs(),
        approach_steps: 20,
        distance: 2.0 * wavelength,
        steps: 40,
        return_stroke: false,
        stationary_from: 0.5,
        jump_force_threshold: 0.01 * jkr.critical_force().abs(),
    };
    let mut solver = NormalSolver::Adhesive(Box::new(problem.adhesive_solver(AdhesiveParams::default())));
    let mut records: Vec<StepRecord> = Vec::new();
    let summary = protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    TranslationResults::new(
        &summary,
        &TranslationInputs {
            kinematics: Kinematics::Roll,
            records: &records,
            stationary_from: protocol.stationary_from,
            distance: protocol.distance,
            jkr: Some(jkr),
            work_of_adhesion,
            radius,
            contact_modulus: 1.0,
            gammas: None,
            tau0: None,
        },
    )
}

/// `results` of the reduced fig6 run of the command line.
fn cli_results(dir: &Path) -> serde_json::Value {
    let scenario = scenarios_dir().join("fig6.toml");
    let out = dir.join("fig6");
    let output = Command::new(env!("CARGO_BIN_EXE_adhesim"))
        .args([
            "run",
            scenario.to_str().unwrap(),
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ])
        .args([
            "--set",
            "grid.n=32",
            "--set",
            "protocol.approach_steps=20",
            "--set",
            "protocol.steps=40",
        ])
        .output()
        .expect("binary runs");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let summary: serde_json::Value = read_json(&out.join("summary.json"));
    summary["results"].clone()
}

#[test]
fn library_reproduces_the_cli_friction_numbers_of_fig6() {
    let dir = tempfile::tempdir().unwrap();
    let cli = cli_results(dir.path());
    let results = reduced_fig6();
    // The same computation in the same order as the command line: equal to the last
    // digits but for summation order across threads, hence 1e-12 relative.
    let expect = |name: &str, got: Option<f64>| {
        let got = got.unwrap_or_else(|| panic!("{name} is None in the library results"));
        let want = cli[name]
            .as_f64()
            .unwrap_or_else(|| panic!("{name} missing from summary.json: {cli}"));
        assert!(
            (got - want).abs() <= 1e-12 * want.abs(),
            "{name}: library {got:e}, summary.json {want:e}"
        );
    };
    assert_eq!(results.kind, "roll");
    assert_eq!(Some(results.jumps as u64), cli["jumps"].as_u64(), "jumps");
    expect("mean_tangential_force", results.mean_tangential_force);
    expect("mean_tangential_force_work", Some(results.mean_tangential_force_work));
    expect("mean_normal_force", Some(results.mean_normal_force));
    expect("contact_half_width", Some(results.contact_half_width));
    expect("contact_radius", Some(results.contact_radius));
    expect("compactness", Some(results.compactness));
    expect("energy_balance_ratio", results.energy_balance_ratio);
    expect("mean_normal_force_norm", results.mean_normal_force_norm);
    expect("gamma3", results.gamma3);
    expect("gamma3_half_width", results.gamma3_half_width);
    expect("gamma3_depth", results.gamma3_depth);
    // No [analysis] section: Eq. 12 and the sliding law do not apply.
    assert_eq!(results.eq12_prediction, None);
    assert!(
        cli["eq12_prediction"].is_null(),
        "eq12_prediction: {}",
        cli["eq12_prediction"]
    );
    assert_eq!(results.friction_eq16, None);
    assert!(!results.border_contact);
    assert_eq!(cli["border_contact"].as_bool(), Some(false), "border_contact");
}
