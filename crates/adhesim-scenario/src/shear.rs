//! Friction at the interface: `[friction]` and `[protocol] kind = "shear"` validated into
//! a [`ShearSetup`], and the `results` of a shear run.

use crate::checks::{finite, positive};
use crate::error::ScenarioError;
use crate::guards::{step_count, MAX_STEPS};
use crate::model::*;
use crate::validated::ValidatedSections;
use adhesim::{Complementarity, FrictionLaw, Shear, ShearMaterial, ShearSummary, StepRecord};
use anyhow::{bail, Result};
use serde::Serialize;

mod force_control;
mod protocol_keys;

use force_control::shift_or_force;
use protocol_keys::{approach_depths, approach_steps, coupled, incline, mode_mixity, normal_control};
pub(crate) use protocol_keys::{layer_shear, mixity_keys};

impl ValidScenario {
    /// The interface carries friction: a shear, or a roll, slide or translate with
    /// `[friction]` (the friction columns and fields are written).
    pub fn has_interface_friction(&self) -> bool {
        self.shear.is_some() || self.translation.as_ref().is_some_and(|t| t.friction.is_some())
    }
}

impl ScenarioFile {
    /// `kind = "shear"` only with `[friction]`; `[friction]` with a shear, roll, slide or
    /// translate, not with an indentation.
    pub(crate) fn check_friction_pairing(&self) -> Result<()> {
        let kind = self.protocol.kind();
        match (&self.friction, kind) {
            (Some(_), ProtocolKind::IndentPulloff) => bail!(ScenarioError::invalid_as(
                "protocol.kind",
                "\"indent_pulloff\"",
                "\"shear\", \"roll\", \"slide\" or \"translate\" with [friction]",
                "[friction] acts where the indenter moves along the surface (protocol.kind = \"shear\", \"roll\", \"slide\" or \"translate\"), got \"indent_pulloff\""
            )),
            (Some(_), _) | (None, ProtocolKind::IndentPulloff) => Ok(()),
            (None, ProtocolKind::Shear) => bail!(ScenarioError::missing(
                "friction",
                "a [friction] section with protocol.kind = \"shear\"",
                "protocol.kind = \"shear\" needs a [friction] section (friction.law = \"coulomb\", \"shear_strength\" or \"coulomb_shear\")"
            )),
            (None, _) => Ok(()),
        }
    }

    /// `[protocol]` of kind shear with its `[friction]` (and `[output]`).
    pub(crate) fn validate_shear(
        self,
        inputs: ValidatedSections,
        heights: Vec<f64>,
        start_depth: f64,
    ) -> Result<ValidScenario> {
        let ValidatedSections {
            grid,
            material,
            layer,
            gamma,
            gamma0,
            law: adhesion_law,
            indenter,
            unit,
            jkr,
            derived,
            ..
        } = inputs;
        let ProtocolSection::Shear(p) = &self.protocol else {
            bail!("[protocol]: validate_shear needs protocol.kind = \"shear\"");
        };
        let Some(friction) = &self.friction else {
            bail!("[friction]: validate_shear needs a [friction] section");
        };
        let InterfaceFriction {
            law,
            static_law,
            slip_weakening_distance,
            material: shear_material,
            mode_mixity,
            ..
        } = self.interface_laws(friction, material.contact_modulus(), gamma0)?;
        let (depth, press_depth) = approach_depths(p, unit, start_depth)?;
        let deepest = press_depth.unwrap_or(depth);
        let (distance, force_control) = shift_or_force(p, friction, law, static_law)?;
        let steps = step_count("protocol.steps", p.steps)?;
        let approach_steps = approach_steps(p, press_depth.is_some())?;
        // The depth travelled per approach step: down to the deepest depth, and up again to
        // the held one after a press.
        let depth_step = (deepest - start_depth + (deepest - depth)) / approach_steps as f64;
        self.check_step(
            start_depth,
            deepest,
            depth_step,
            "protocol.approach_steps, protocol.depth",
        )?;
        let direction = finite("protocol.direction", p.direction.unwrap_or(0.0))?.to_radians();
        let jump_force_threshold = self.output_checks(gamma0, &jkr, &indenter, material.contact_modulus())?;
        let coupled = coupled(friction);
        if let Some(layer) = &layer {
            layer_shear(layer)?;
        }
        let drive_stiffness = drive_stiffness(p)?;
        let protocol = Shear {
            start_depth,
            depth,
            press_depth,
            approach_steps,
            distance,
            steps,
            direction,
            return_stroke: p.return_stroke.unwrap_or(false),
            cycles: match p.cycles {
                None => 0,
                Some(cycles) => step_count("protocol.cycles", cycles)?,
            },
            jump_force_threshold,
            incline: incline(p.incline)?,
            mode_mixity,
            force_control,
            coupled,
            hold_normal_force: normal_control(p)?,
        };
        if protocol.shift_steps() > MAX_STEPS {
            bail!(ScenarioError::invalid_as(
                "protocol.cycles",
                protocol.cycles,
                format!("at most {MAX_STEPS} shift steps in all"),
                format!(
                    "protocol.steps = {steps} with protocol.cycles = {} makes {} shift steps, more than {MAX_STEPS}",
                    protocol.cycles,
                    protocol.shift_steps()
                )
            ));
        }
        Ok(ValidScenario {
            file: self,
            grid,
            material,
            layer,
            gamma,
            gamma0,
            first_contact_factor: None,
            law: adhesion_law,
            indenter,
            heights,
            start_depth,
            max_depth: deepest,
            depth_step,
            approach_steps,
            max_retract_steps: 0,
            jkr,
            derived,
            jump_force_threshold,
            translation: None,
            shear: Some(ShearSetup {
                protocol,
                law,
                static_law,
                slip_weakening_distance,
                drive_stiffness,
                material: shear_material,
            }),
            roughness: None,
            hold: None,
            warnings: Vec::new(),
        })
    }

    /// `[friction]` of a roll, slide or translate (None without one): the laws and the
    /// tangential constants, with what shear alone offers refused by name (a mode mixity
    /// goes with Goodman's approximation only there).
    pub(crate) fn interface_friction(
        &self,
        contact_modulus: f64,
        work_of_adhesion: f64,
    ) -> Result<Option<InterfaceFriction>> {
        let Some(friction) = &self.friction else {
            return Ok(None);
        };
        let interface = self.interface_laws(friction, contact_modulus, work_of_adhesion)?;
        if interface.coupled {
            if let Some((key, mixity)) = mixity_keys(friction).find(|&(_, m)| m != 0.0) {
                bail!(ScenarioError::invalid_as(
                    key,
                    mixity,
                    "0 with friction.coupling = \"full\" under a roll, slide or translate",
                    format!(
                        "{key} = {mixity} weakens the edge in rounds that are not built around the coupled operator's under protocol.kind = \"{}\": use friction.coupling = \"none\" with it, or protocol.kind = \"shear\"",
                        self.protocol.kind().name()
                    )
                ));
            }
        }
        Ok(Some(interface))
    }

    /// The laws of `friction` and the tangential constants, with what no protocol combines
    /// with `[friction]` yet refused (the checks a shear and a translation share).
    fn interface_laws(
        &self,
        friction: &FrictionSection,
        contact_modulus: f64,
        work_of_adhesion: f64,
    ) -> Result<InterfaceFriction> {
        let law = friction_law(friction)?;
        let static_law = static_friction_law(friction)?;
        let slip_weakening_distance = slip_weakening(friction, static_law)?;
        let material = self.shear_material(contact_modulus)?;
        self.check_shear_combinations()?;
        Ok(InterfaceFriction {
            law,
            static_law,
            slip_weakening_distance,
            material,
            drive_stiffness: None,
            coupled: coupled(friction),
            mode_mixity: mode_mixity(friction, work_of_adhesion)?,
        })
    }

    /// What `[friction]` does not combine with yet: a cohesive law, `[analysis]`; each
    /// refused naming its key.
    fn check_shear_combinations(&self) -> Result<()> {
        let law_name = self.adhesion.law.unwrap_or_default();
        if law_name != LawName::Jkr {
            bail!(ScenarioError::invalid_as(
                "adhesion.law",
                format!("{law_name:?}").to_lowercase(),
                "\"jkr\" with [friction]",
                "[friction] works with the JKR-type adhesion (adhesion.law = \"jkr\", or work_of_adhesion = 0); a cohesive law's tractions across gaps have no friction law yet"
            ));
        }
        let kind = self.protocol.kind();
        if !self.analysis.is_empty() && kind != ProtocolKind::Shear {
            bail!(ScenarioError::invalid_as(
                "friction",
                "[friction]",
                "absent with [analysis]",
                format!(
                    "[friction] and [analysis] do not go together: [analysis] reads the forces of a frictionless interface (its tau0 adds the paper's area friction after the run), while [friction] puts the friction into the interface of this \"{}\"",
                    kind.name()
                )
            ));
        }
        if !self.analysis.is_empty() {
            bail!(ScenarioError::invalid_as(
                "protocol.kind",
                "\"shear\"",
                "\"roll\" or \"slide\" with [analysis]",
                "[analysis] (gamma_approach, gamma_pulloff, tau0) is used by protocol.kind = \"roll\" / \"slide\" only, got \"shear\" (its friction is [friction])"
            ));
        }
        Ok(())
    }

    /// G and ν: tangential contact needs Poisson's ratio, so `[material]` must give
    /// youngs_modulus and poisson_ratio.
    fn shear_material(&self, contact_modulus: f64) -> Result<ShearMaterial> {
        let Some(poisson_ratio) = self.material.poisson_ratio else {
            bail!(ScenarioError::missing(
                "material.poisson_ratio",
                "material.youngs_modulus and material.poisson_ratio with [friction]",
                "material.poisson_ratio is required with [friction] (tangential contact needs Poisson's ratio): give [material] youngs_modulus and poisson_ratio instead of contact_modulus"
            ));
        };
        Ok(ShearMaterial::from_contact_modulus(contact_modulus, poisson_ratio))
    }
}

/// The interface law of `[friction]`, each law taking exactly its own keys.
fn friction_law(section: &FrictionSection) -> Result<FrictionLaw> {
    let law = section.law;
    let needed = |key: &str, value: Option<f64>| -> Result<f64> {
        value.ok_or_else(|| {
            ScenarioError::missing(
                &format!("friction.{key}"),
                format!("with friction.law = \"{}\"", law.name()),
                format!("friction.law = \"{}\" needs friction.{key}", law.name()),
            )
            .into()
        })
    };
    let unused = |key: &str, value: Option<f64>| -> Result<()> {
        match value {
            Some(v) => bail!(ScenarioError::invalid_as(
                &format!("friction.{key}"),
                v,
                format!("absent with friction.law = \"{}\"", law.name()),
                format!(
                    "friction.{key} is not a key of friction.law = \"{}\", got {v}",
                    law.name()
                )
            )),
            None => Ok(()),
        }
    };
    let non_negative = |key: &str, value: f64| -> Result<f64> {
        if value.is_finite() && value >= 0.0 {
            Ok(value)
        } else {
            Err(ScenarioError::invalid(&format!("friction.{key}"), value, "finite and >= 0").into())
        }
    };
    let (coefficient, shear_strength) = (section.coefficient, section.shear_strength);
    let built = match law {
        FrictionLawName::Coulomb => {
            unused("shear_strength", shear_strength)?;
            FrictionLaw::coulomb(non_negative("coefficient", needed("coefficient", coefficient)?)?)
        }
        FrictionLawName::ShearStrength => {
            unused("coefficient", coefficient)?;
            FrictionLaw::shear_strength(non_negative(
                "shear_strength",
                needed("shear_strength", shear_strength)?,
            )?)
        }
        FrictionLawName::NoSlip => {
            unused("coefficient", coefficient)?;
            unused("shear_strength", shear_strength)?;
            Ok(FrictionLaw::NoSlip)
        }
        FrictionLawName::CoulombShear => FrictionLaw::coulomb_shear(
            non_negative("coefficient", needed("coefficient", coefficient)?)?,
            non_negative("shear_strength", needed("shear_strength", shear_strength)?)?,
        ),
    };
    Ok(built?)
}

/// `protocol.drive_stiffness`: finite and > 0, and not with an inclined path (the drive
/// pulls along the surface).
fn drive_stiffness(protocol: &ShearProtocol) -> Result<Option<f64>> {
    let Some(stiffness) = protocol.drive_stiffness else {
        return Ok(None);
    };
    let stiffness = positive("protocol.drive_stiffness", stiffness)?;
    if protocol.incline.is_some_and(|incline| incline != 0.0) {
        bail!(ScenarioError::invalid_as(
            "protocol.drive_stiffness",
            stiffness,
            "absent with protocol.incline",
            "protocol.drive_stiffness pulls the indenter along the surface; an inclined path (protocol.incline) takes a rigid drive"
        ));
    }
    Ok(Some(stiffness))
}

/// The static law of `[friction]` (`static_coefficient`, `static_shear_strength`; each at
/// least its kinetic key, and only with a law that has that key), None without them.
fn static_friction_law(section: &FrictionSection) -> Result<Option<FrictionLaw>> {
    let law = section.law;
    let checked = |key: &str, value: Option<f64>, kinetic_key: &str, kinetic: Option<f64>| -> Result<Option<f64>> {
        let Some(value) = value else { return Ok(None) };
        let Some(kinetic) = kinetic else {
            bail!(ScenarioError::invalid_as(
                &format!("friction.{key}"),
                value,
                format!("absent with friction.law = \"{}\"", law.name()),
                format!(
                    "friction.{key} is not a key of friction.law = \"{}\" (it goes with friction.{kinetic_key}), got {value}",
                    law.name()
                )
            ));
        };
        if !(value.is_finite() && value >= kinetic) {
            bail!(ScenarioError::invalid_as(
                &format!("friction.{key}"),
                value,
                format!("finite and >= friction.{kinetic_key} = {kinetic}"),
                format!("friction.{key} must be finite and at least the kinetic friction.{kinetic_key} = {kinetic}, got {value}")
            ));
        }
        Ok(Some(value))
    };
    let coefficient = checked(
        "static_coefficient",
        section.static_coefficient,
        "coefficient",
        section.coefficient,
    )?;
    let strength = checked(
        "static_shear_strength",
        section.static_shear_strength,
        "shear_strength",
        section.shear_strength,
    )?;
    let built = match (law, coefficient, strength) {
        (_, None, None) => return Ok(None),
        (FrictionLawName::Coulomb, Some(coefficient), _) => FrictionLaw::coulomb(coefficient),
        (FrictionLawName::ShearStrength, _, Some(strength)) => FrictionLaw::shear_strength(strength),
        (FrictionLawName::CoulombShear, coefficient, strength) => FrictionLaw::coulomb_shear(
            coefficient.or(section.coefficient).unwrap_or(0.0),
            strength.or(section.shear_strength).unwrap_or(0.0),
        ),
        // A static key without its kinetic key was refused above.
        _ => return Ok(None),
    };
    Ok(Some(built?))
}

/// `friction.slip_weakening_distance` D_c: finite and > 0, and only with a static law to
/// weaken from (None without the key).
fn slip_weakening(section: &FrictionSection, static_law: Option<FrictionLaw>) -> Result<Option<f64>> {
    let Some(distance) = section.slip_weakening_distance else {
        return Ok(None);
    };
    if static_law.is_none() {
        bail!(ScenarioError::invalid_as(
            "friction.slip_weakening_distance",
            distance,
            "with friction.static_shear_strength or friction.static_coefficient",
            format!(
                "friction.slip_weakening_distance = {distance} weakens a static bound to the kinetic one; give friction.static_shear_strength or friction.static_coefficient above the kinetic value, or drop the key"
            )
        ));
    }
    if !(distance.is_finite() && distance > 0.0) {
        bail!(ScenarioError::invalid_as(
            "friction.slip_weakening_distance",
            distance,
            "finite and > 0",
            format!("friction.slip_weakening_distance must be finite and > 0, got {distance}")
        ));
    }
    Ok(Some(distance))
}

/// The `results` of a shear run in `summary.json`.
///
/// # Example
/// An adhesive contact whose interface is bounded by a shear strength τ0 slides at
/// F_T = τ0·A, its tensile edge included (the paper's area friction, Eq. 16).
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
/// work_of_adhesion = 2e-3
/// [indenter]
/// shape = "sphere"
/// radius = 1.0
/// [friction]
/// law = "shear_strength"
/// shear_strength = 0.002
/// [protocol]
/// kind = "shear"
/// depth = 0.01
/// depth_unit = "length"
/// approach_steps = 5
/// distance = 0.02
/// steps = 5
/// "#;
/// let valid = Scenario::from_toml_str(text, "tresca.toml")?.validate(std::path::Path::new("."))?;
/// let RunResults::Shear(results) = run(&valid, &mut ())?.results else { unreachable!() };
/// let sliding = results.sliding_friction_force.expect("gross slip");
/// assert!((sliding / (0.002 * results.contact_area) - 1.0).abs() < 1e-9);
/// assert!((results.mean_shear_stress.unwrap() / 0.002 - 1.0).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Serialize)]
pub struct ShearResults {
    /// Peak tangential force before gross slip (null when the stroke ends in partial slip).
    pub static_friction_force: Option<f64>,
    /// Tangential force at the end of the forward stroke when every contact element slips
    /// (null otherwise).
    pub sliding_friction_force: Option<f64>,
    /// F_T/A in gross slip: the paper's τ (null otherwise).
    pub mean_shear_stress: Option<f64>,
    /// Largest tangential force of the forward stroke.
    pub peak_tangential_force: f64,
    /// Normal force at the end of the forward stroke.
    pub normal_force: f64,
    /// Contact area at the end of the forward stroke.
    pub contact_area: f64,
    /// A at the peak of the forward stroke over A at rest (the end of the approach): 1
    /// unless the shear weakens the adhesive edge (`friction.mode_mixity` > 0); with
    /// Goodman's approximation the normal problem does not see the shear otherwise.
    pub contact_area_reduction: f64,
    /// Energy dissipated by friction over the run.
    pub frictional_dissipation: f64,
    /// Energy dissipated by friction in the last fretting cycle (null without
    /// `protocol.cycles`): Mindlin–Deresiewicz's loop energy.
    pub fretting_dissipation_per_cycle: Option<f64>,
    /// The most tensile normal force during the shift (the pull-off force of an inclined
    /// path out of the body).
    pub min_normal_force: f64,
    /// The shift at which an inclined path lost the contact (null while in contact).
    pub contact_lost_at_shift: Option<f64>,
    /// Energy released by normal jumps on the approach.
    pub dissipated_energy: f64,
    /// The worst optimality conditions of any tangential step.
    pub complementarity: Complementarity,
    /// Slip events: steps in which elements broke loose from a static bound and the
    /// tangential force fell (0 without a static law).
    pub slip_events: usize,
    pub border_contact: bool,
}

impl ShearResults {
    /// The results of a run from its summary and records.
    pub fn new(summary: &ShearSummary, records: &[StepRecord], protocol: &Shear) -> Self {
        let forward_end = records
            .iter()
            .filter(|r| r.phase == Some(adhesim::Phase::Shear))
            .nth(protocol.steps - 1);
        let gross_slip = forward_end.is_some_and(|r| r.stick_elements == 0 && r.slip_elements > 0);
        // A at the peak of the forward stroke over A at rest (the last approach step).
        let at_rest = records
            .iter()
            .rfind(|r| r.phase == Some(adhesim::Phase::Approach))
            .map(|r| r.area);
        let at_peak = records
            .iter()
            .filter(|r| r.phase == Some(adhesim::Phase::Shear))
            .take(protocol.steps)
            .max_by(|a, b| a.force_tangential.total_cmp(&b.force_tangential))
            .map(|r| r.area);
        let area_reduction = match (at_peak, at_rest) {
            (Some(peak), Some(rest)) if rest > 0.0 => peak / rest,
            _ => 1.0,
        };
        let sliding = gross_slip.then_some(summary.final_tangential_force);
        Self {
            static_friction_force: gross_slip.then_some(summary.peak_tangential_force),
            sliding_friction_force: sliding,
            mean_shear_stress: sliding.filter(|_| summary.area > 0.0).map(|f| f / summary.area),
            peak_tangential_force: summary.peak_tangential_force,
            normal_force: summary.normal_force,
            contact_area: summary.area,
            contact_area_reduction: area_reduction,
            frictional_dissipation: summary.frictional_dissipation,
            fretting_dissipation_per_cycle: (protocol.cycles > 0).then_some(summary.last_cycle_dissipation),
            min_normal_force: summary.min_normal_force,
            contact_lost_at_shift: summary.contact_lost_at,
            dissipated_energy: summary.dissipated_energy,
            complementarity: summary.complementarity,
            slip_events: summary.slip_events,
            border_contact: summary.touches_border,
        }
    }
}
