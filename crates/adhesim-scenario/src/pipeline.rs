//! The run pipeline, one for every protocol: a validated scenario → elastic operator,
//! normal solver and protocol → the caller's observer sees every step → results.

use crate::cohesive::cohesive_solver;
use crate::model::{ShearSetup, TranslationSetup, ValidScenario};
use crate::results::{fit_results, Results, RunResults};
use crate::shear::ShearResults;
use adhesim::analysis::friction::{TranslationInputs, TranslationResults};
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Backend, Ccg, CcgParams, FrictionLaw, IndentPulloff, NormalSolver, Observer,
    Problem, Profile, ProtocolCheckpoint, ProtocolError, RunSummary, ShearBody, StepRecord, TangentialParams,
    TangentialSolver, TranslationFriction, TranslationSummary,
};

/// The protocol of a scenario, built in one place ([`ValidScenario::protocol_setup`]).
#[derive(Debug, Clone, Copy)]
pub enum ProtocolSetup<'a> {
    /// indent_pulloff: approach to the maximum depth, then retraction to pull-off.
    Indentation(IndentPulloff),
    /// roll / slide / translate at fixed depth.
    Translation(&'a TranslationSetup),
    /// shear at fixed depth with friction at the interface.
    Shear(&'a ShearSetup),
}

impl ValidScenario {
    /// The scenario's protocol.
    pub fn protocol_setup(&self) -> ProtocolSetup<'_> {
        if let Some(setup) = &self.shear {
            return ProtocolSetup::Shear(setup);
        }
        match &self.translation {
            Some(setup) => ProtocolSetup::Translation(setup),
            None => ProtocolSetup::Indentation(IndentPulloff {
                start_depth: self.start_depth,
                max_depth: self.max_depth,
                depth_step: self.depth_step,
                max_retract_steps: self.max_retract_steps,
                jump_force_threshold: self.jump_force_threshold,
            }),
        }
    }

    /// The normal solver: the cohesive solver of `adhesion.law` = "dugdale" or
    /// "exponential", the adhesive active set where γ0 > 0, the library's non-adhesive
    /// default otherwise.
    pub fn normal_solver(&self) -> NormalSolver {
        self.solver_with(&self.gamma)
    }

    /// The normal solver with the work of adhesion `work_of_adhesion` per element.
    fn solver_with(&self, work_of_adhesion: &[f64]) -> NormalSolver {
        if let Some(solver) = cohesive_solver(&self.law, self.grid, self.material, work_of_adhesion) {
            NormalSolver::Cohesive(Box::new(solver))
        } else if self.gamma0 > 0.0 {
            // On a layer the reference rule: the certified stops and local replays are
            // derived for the half-space's kernel.
            let params = match self.layer {
                Some(_) => AdhesiveParams {
                    reference_rule: true,
                    predicted_growth: adhesim::solver::PredictedGrowth::Off,
                    ..AdhesiveParams::default()
                },
                None => AdhesiveParams {
                    predicted_growth: self.predicted_growth(),
                    contact_window: self
                        .file
                        .solver
                        .as_ref()
                        .and_then(|solver| solver.contact_window)
                        .unwrap_or(AdhesiveParams::default().contact_window),
                    ..AdhesiveParams::default()
                },
            };
            NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
                self.grid,
                self.material.contact_modulus(),
                work_of_adhesion.to_vec(),
                params,
            )))
        } else if self.layer.is_some() {
            // The nested active set's coarse levels and windows are half-space operators:
            // on a layer, CCG on the layer's own operator.
            NormalSolver::NonAdhesive(Ccg::new(CcgParams::default()))
        } else {
            adhesim::protocol::non_adhesive_solver(self.grid, self.material)
        }
    }

    /// `solver.predicted_growth`, the library's default where absent.
    fn predicted_growth(&self) -> adhesim::solver::PredictedGrowth {
        let name = self.file.solver.as_ref().and_then(|solver| solver.predicted_growth);
        name.map_or(AdhesiveParams::default().predicted_growth, |name| name.rule())
    }

    /// The problem this scenario solves: the body's operator (half-space, periodic or
    /// layer), the indenter's heights (for a roll, slide or translate, its moving contact)
    /// and the work of adhesion per element, checked by [`Problem`].
    pub fn problem(&self) -> Result<Problem, ProtocolError> {
        let operator = Backend::default()
            .normal_operator(self.grid, self.material, self.layer)
            .map_err(|error| ProtocolError::InvalidParameter(format!("material.thickness: {error}")))?;
        let problem = match self.protocol_setup() {
            ProtocolSetup::Translation(setup) => Problem::translating(operator, setup.contact.clone())?,
            _ => Problem::new(operator, self.heights.clone())?,
        };
        Ok(problem.with_work_of_adhesion(self.gamma.clone())?)
    }

    /// Steps the protocol will report (for progress bars): approach + retraction of an
    /// indentation (an estimate), approach + stroke(s) of a translation.
    pub fn expected_steps(&self) -> usize {
        match self.protocol_setup() {
            ProtocolSetup::Indentation(_) => 2 * self.approach_steps + self.hold.map_or(0, |hold| hold.steps()),
            ProtocolSetup::Translation(setup) => {
                let p = &setup.protocol;
                p.approach_steps + p.steps + if p.return_stroke { p.steps } else { 0 }
            }
            ProtocolSetup::Shear(setup) => setup.protocol.approach_steps + setup.protocol.shift_steps(),
        }
    }
}

/// What [`run`] gives back.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// The `results` section of `summary.json`.
    pub results: RunResults,
    /// The library's summary of the protocol.
    pub report: RunSummary,
    /// Every step's record.
    pub records: Vec<StepRecord>,
}

/// Keeps every record and passes each step on to the caller's observer.
type Recording<'a> = (Vec<StepRecord>, &'a mut dyn Observer);

/// Where a run goes on from: the protocol's checkpoint and the records of the steps
/// before it.
#[derive(Debug, Clone)]
pub struct Resume {
    /// The protocol's state after its last step.
    pub protocol: ProtocolCheckpoint,
    /// The records of the steps done.
    pub records: Vec<StepRecord>,
}

/// Runs a validated scenario: builds the elastic operator and the normal solver, runs the
/// protocol with `observer` seeing every step (pass `&mut ()` for none), and analyses the
/// records into the results `summary.json` reports. Writes nothing itself.
///
/// # Examples
/// A sphere pressed into rubber and shifted with Coulomb friction at the interface
/// (Cattaneo–Mindlin): every contact element sticks or slips, and the slip zone grows from
/// the edge.
/// ```
/// use adhesim_scenario::{run, RunResults, Scenario};
///
/// let text = r#"
/// [grid]
/// n = 48
/// size = 0.5
/// [material]
/// youngs_modulus = 3.0
/// poisson_ratio = 0.5
/// [adhesion]
/// work_of_adhesion = 0.0
/// [indenter]
/// shape = "sphere"
/// radius = 1.0
/// [friction]
/// law = "coulomb"
/// coefficient = 0.3
/// [protocol]
/// kind = "shear"
/// depth = 0.01
/// depth_unit = "length"
/// approach_steps = 5
/// distance = 0.004
/// steps = 4
/// "#;
/// let valid = Scenario::from_toml_str(text, "shear.toml")?.validate(std::path::Path::new("."))?;
/// let outcome = run(&valid, &mut ())?;
/// let RunResults::Shear(results) = &outcome.results else { unreachable!() };
/// let last = outcome.records.last().unwrap();
/// assert_eq!(last.stick_elements + last.slip_elements, last.contact_elements);
/// assert!(last.slip_elements > 0 && last.stick_elements > 0, "partial slip");
/// assert!(results.peak_tangential_force < 0.3 * results.normal_force);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
/// A layer much thicker than the contact is a half-space:
/// ```
/// use adhesim_scenario::{run, Scenario};
///
/// let text = |layer: &str| format!(r#"
/// [grid]
/// n = 32
/// size = 0.4
/// [material]
/// youngs_modulus = 3.0
/// poisson_ratio = 0.5
/// {layer}
/// [adhesion]
/// work_of_adhesion = 0.0
/// [indenter]
/// shape = "sphere"
/// radius = 1.0
/// [protocol]
/// kind = "indent_pulloff"
/// max_depth = 0.005
/// steps = 4
/// "#);
/// let force = |layer: &str| -> Result<f64, Box<dyn std::error::Error>> {
///     let valid = Scenario::from_toml_str(&text(layer), "layer.toml")?.validate(std::path::Path::new("."))?;
///     let outcome = run(&valid, &mut ())?;
///     Ok(outcome.records.iter().map(|r| r.force_normal).fold(0.0, f64::max))
/// };
/// let (half_space, thick) = (force("")?, force("thickness = 1000.0")?);
/// assert!((thick / half_space - 1.0).abs() < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run(scenario: &ValidScenario, observer: &mut dyn Observer) -> Result<RunOutcome, ProtocolError> {
    run_from(scenario, observer, None)
}

/// As [`run`], continued from `resume` when given: the outcome is that of the
/// uninterrupted run, bit for bit. A checkpoint of the other kind of protocol is an error.
pub fn run_from(
    scenario: &ValidScenario,
    observer: &mut dyn Observer,
    resume: Option<Resume>,
) -> Result<RunOutcome, ProtocolError> {
    let mut problem = scenario.problem()?;
    // The solver from the problem's work of adhesion, checked when the problem was built.
    let mut solver = scenario.solver_with(problem.work_of_adhesion());
    let (start, records) = match resume {
        Some(Resume { protocol, records }) => (Some(protocol), records),
        None => (None, Vec::new()),
    };
    let (indentation_start, translation_start) = match start {
        Some(ProtocolCheckpoint::Indentation(c)) => (Some(c), None),
        Some(ProtocolCheckpoint::Translation(c)) => (None, Some(c)),
        None => (None, None),
    };
    let wrong_kind = match scenario.protocol_setup() {
        ProtocolSetup::Indentation(_) => translation_start.is_some(),
        ProtocolSetup::Translation(_) => indentation_start.is_some(),
        // A shear run takes no checkpoints: any is another protocol's.
        ProtocolSetup::Shear(_) => indentation_start.is_some() || translation_start.is_some(),
    };
    if wrong_kind {
        return Err(ProtocolError::InvalidParameter(
            "the checkpoint is of another protocol than this run's".into(),
        ));
    }
    let mut recording: Recording<'_> = (records, observer);
    match scenario.protocol_setup() {
        ProtocolSetup::Indentation(protocol) => {
            let start = indentation_start.as_deref();
            let summary = match &scenario.hold {
                Some(hold) => protocol.run_holding(&mut problem, &mut solver, &mut recording, start, hold)?,
                None => protocol.run_from(&mut problem, &mut solver, &mut recording, start)?,
            };
            let records = recording.0;
            let (fits, _) = fit_results(scenario, &records);
            Ok(RunOutcome {
                results: RunResults::Indentation(Results {
                    fits,
                    ..Results::from_protocol(&summary)
                }),
                report: RunSummary::Indentation(summary),
                records,
            })
        }
        ProtocolSetup::Shear(setup) => run_shear(scenario, setup, &mut problem, &mut solver, recording),
        ProtocolSetup::Translation(setup) => {
            let summary = match &setup.friction {
                Some(friction) => setup.protocol.run_with_friction(
                    &mut problem,
                    &mut solver,
                    TranslationFriction {
                        body: ShearBody {
                            material: friction.material,
                            layer: scenario.layer,
                        },
                        solver: &mut tangential_solver(
                            friction.law,
                            friction.static_law,
                            friction.slip_weakening_distance,
                            friction.drive_stiffness,
                        )?,
                        coupled: friction.coupled,
                        mode_mixity: friction.mode_mixity,
                    },
                    &mut recording,
                )?,
                None => {
                    setup
                        .protocol
                        .run_from(&mut problem, &mut solver, &mut recording, translation_start.as_deref())?
                }
            };
            let records = recording.0;
            let mut results = analyse_translation(scenario, setup, &summary, &records);
            if setup.friction.is_some() {
                results = results.with_interface_friction(&summary);
            }
            Ok(RunOutcome {
                results: RunResults::Translation(results),
                report: RunSummary::Translation(summary),
                records,
            })
        }
    }
}

/// A shear run: the tangential operator and solver beside the normal ones.
fn run_shear(
    scenario: &ValidScenario,
    setup: &ShearSetup,
    problem: &mut Problem,
    solver: &mut NormalSolver,
    mut recording: Recording<'_>,
) -> Result<RunOutcome, ProtocolError> {
    let mut friction = tangential_solver(
        setup.law,
        setup.static_law,
        setup.slip_weakening_distance,
        setup.drive_stiffness,
    )?;
    let summary = setup.protocol.run(
        problem,
        solver,
        ShearBody {
            material: setup.material,
            layer: scenario.layer,
        },
        &mut friction,
        &mut recording,
    )?;
    let records = recording.0;
    Ok(RunOutcome {
        results: RunResults::Shear(ShearResults::new(&summary, &records, &setup.protocol)),
        report: RunSummary::Shear(summary),
        records,
    })
}

/// The round limit of a run's tangential steps (the library's default is 200): a slip
/// event's avalanche under a static law, or the falling bounds of slip weakening, crosses a
/// contact of a hundred elements and more a few elements a round (the paper's slide at
/// Δ = 0.05 mm took more than 200). Only steps that would have failed take more.
const TANGENTIAL_ROUNDS: usize = 2000;

/// The tangential solver of a law, its static law and its slip weakening, and a compliant
/// drive.
fn tangential_solver(
    law: FrictionLaw,
    static_law: Option<FrictionLaw>,
    slip_weakening_distance: Option<f64>,
    drive_stiffness: Option<f64>,
) -> Result<TangentialSolver, ProtocolError> {
    let invalid = |e: adhesim::FrictionLawError| ProtocolError::InvalidParameter(e.to_string());
    let params = TangentialParams {
        max_rounds: TANGENTIAL_ROUNDS,
        ..TangentialParams::default()
    };
    let mut solver = TangentialSolver::new(law, params);
    if let Some(static_law) = static_law {
        solver = solver.with_static_law(static_law).map_err(invalid)?;
    }
    if let Some(distance) = slip_weakening_distance {
        solver = solver.with_slip_weakening(distance).map_err(invalid)?;
    }
    if let Some(stiffness) = drive_stiffness {
        solver = solver.with_drive_stiffness(stiffness).map_err(invalid)?;
    }
    Ok(solver)
}

/// The library's friction analysis with the scenario's inputs.
fn analyse_translation(
    scenario: &ValidScenario,
    setup: &TranslationSetup,
    summary: &TranslationSummary,
    records: &[StepRecord],
) -> TranslationResults {
    TranslationResults::new(
        summary,
        &TranslationInputs {
            kinematics: setup.contact.kinematics(),
            records,
            stationary_from: setup.protocol.stationary_from,
            distance: setup.protocol.distance,
            jkr: scenario.jkr,
            work_of_adhesion: scenario.gamma0,
            radius: scenario.indenter.radius_of_curvature().unwrap_or(f64::NAN),
            contact_modulus: scenario.material.contact_modulus(),
            gammas: setup.gammas,
            tau0: setup.tau0,
        },
    )
}
