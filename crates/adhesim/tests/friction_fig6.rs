//! The friction analysis of `adhesim::analysis::friction` on the rolling case of paper
//! Fig. 6 (`scenarios/fig6.toml`), built here from library objects only, reduced to a
//! 32×32 grid, 20 approach and 40 rolling steps so that it runs in about a second:
//! `adhesim run scenarios/fig6.toml --threads 1 --set grid.n=32
//!  --set protocol.approach_steps=20 --set protocol.steps=40` (the reduced run of
//! `scripts/compare_outputs.sh`) reports the numbers below in `summary.json`. A library
//! user must get them without the command line.

use adhesim::analysis::friction::{TranslationInputs, TranslationResults};
use adhesim::analysis::reference::Jkr;
use adhesim::geometry::WavySphere;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ElasticMaterial, Grid, HalfSpace, Kinematics, NormalSolver, StepRecord,
    TranslatingContact, Translation,
};

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
    let mut heights = vec![0.0; grid.len()];
    contact.fill_heights(&grid, 0.0, &mut heights);
    let start_depth = heights.iter().copied().fold(f64::INFINITY, f64::min);
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
    let mut operator = HalfSpace::new(grid, material);
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        1.0,
        vec![work_of_adhesion; grid.len()],
        AdhesiveParams::default(),
    )));
    let mut records: Vec<StepRecord> = Vec::new();
    let summary = protocol
        .run(&mut operator, &contact, &mut solver, &mut records)
        .unwrap();
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

#[test]
fn library_reproduces_the_cli_friction_numbers_of_fig6() {
    let results = reduced_fig6();
    // The same computation in the same order as the command line: equal to the last
    // digits but for summation order across threads, hence 1e-12 relative.
    let expect = |name: &str, got: Option<f64>, want: f64| {
        let got = got.unwrap_or_else(|| panic!("{name} is None"));
        assert!(
            (got - want).abs() <= 1e-12 * want.abs(),
            "{name}: library {got:e}, summary.json {want:e}"
        );
    };
    assert_eq!(results.kind, "roll");
    assert_eq!(results.jumps, 46);
    expect(
        "mean_tangential_force",
        results.mean_tangential_force,
        3.227807112493166e-07,
    );
    expect(
        "mean_tangential_force_work",
        Some(results.mean_tangential_force_work),
        8.767319546675932e-07,
    );
    expect(
        "mean_normal_force",
        Some(results.mean_normal_force),
        0.0001393948170327632,
    );
    expect(
        "contact_half_width",
        Some(results.contact_half_width),
        0.07499999999999998,
    );
    expect("contact_radius", Some(results.contact_radius), 0.08533466045928989);
    expect("compactness", Some(results.compactness), 0.8447873977535257);
    expect("energy_balance_ratio", results.energy_balance_ratio, 0.9175369560312523);
    expect(
        "mean_normal_force_norm",
        results.mean_normal_force_norm,
        1.479024944810306,
    );
    expect("gamma3", results.gamma3, 3.053094819879557e-05);
    expect("gamma3_half_width", results.gamma3_half_width, 1.6883910484460427e-05);
    expect("gamma3_depth", results.gamma3_depth, 1.634956931571274e-05);
    // No [analysis] section: Eq. 12 and the sliding law do not apply.
    assert_eq!(results.eq12_prediction, None);
    assert_eq!(results.friction_eq16, None);
    assert!(!results.border_contact);
}
