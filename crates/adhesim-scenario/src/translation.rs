//! Validation of the roll / slide / translate protocols (`[protocol]` kind roll, slide,
//! translate, and `[analysis]`).

use crate::checks::{check_periodic_depth, finite, held_depth, non_negative, positive};
use crate::error::{ErrorKind, ScenarioError};
use crate::guards::step_count;
use crate::model::*;
use crate::validated::{ValidatedSections, DEFAULT_APPROACH_STEPS};
use adhesim::analysis::reference::Jkr;
use adhesim::geometry::WavySphere;
use adhesim::{Grid, Indenter, Kinematics, TranslatingContact, Translation};
use anyhow::{bail, Result};

/// Default stationary fraction.
pub const DEFAULT_STATIONARY_FROM: f64 = 0.5;
/// Default substrate angle of a slide, degrees.
pub const DEFAULT_SUBSTRATE_ANGLE: f64 = 30.0;

impl ScenarioFile {
    /// `[protocol]` of kind roll / slide / translate (and `[analysis]`).
    pub(crate) fn validate_translation(self, inputs: ValidatedSections) -> Result<ValidScenario> {
        let ValidatedSections {
            grid,
            material,
            layer,
            gamma,
            gamma0,
            law,
            indenter,
            unit,
            jkr,
            derived,
            substrate_roughness,
        } = inputs;
        let kind = self.protocol.kind();
        let Some((p, substrate_angle)) = self.protocol.motion() else {
            bail!("[protocol]: validate_translation needs protocol.kind = \"roll\", \"slide\" or \"translate\"");
        };
        let (wavy, wavelength, contact) =
            self.translating_contact(&indenter, &grid, kind, substrate_angle, substrate_roughness)?;
        let mut heights = vec![0.0; grid.len()];
        contact.fill_heights(&grid, 0.0, &mut heights);
        let start_depth = heights.iter().copied().fold(f64::INFINITY, f64::min);
        let raw_depth = p.depth;
        let depth = held_depth(raw_depth, unit, start_depth)?;
        check_periodic_depth(&grid, &heights, "protocol.depth", raw_depth, unit)?;
        let raw_distance = p.distance;
        let distance_scale = match p.distance_unit.unwrap_or_default() {
            DistanceUnit::Length => 1.0,
            DistanceUnit::Wavelength => wavelength.ok_or_else(|| {
                ScenarioError::invalid_as(
                    "protocol.distance_unit",
                    "\"wavelength\"",
                    "indenter.shape = \"wavy_sphere\"",
                    format!(
                        "protocol.distance_unit = \"wavelength\" needs indenter.shape = \"wavy_sphere\" (its indenter.wavelength), got \"{}\"",
                        self.indenter.shape().name()
                    ),
                )
            })?,
        };
        let distance = positive("protocol.distance", raw_distance)? * distance_scale;
        check_travel_inside(&grid, &wavy, jkr.as_ref(), depth, (raw_distance, distance_scale))?;
        let steps = step_count("protocol.steps", p.steps)?;
        let approach_steps = step_count(
            "protocol.approach_steps",
            p.approach_steps.unwrap_or(DEFAULT_APPROACH_STEPS),
        )?;
        let depth_step = (depth - start_depth) / approach_steps as f64;
        self.check_step(
            start_depth,
            depth,
            depth_step,
            "protocol.depth, protocol.approach_steps",
        )?;
        let stationary_from = p.stationary_from.unwrap_or(DEFAULT_STATIONARY_FROM);
        if !(0.0..1.0).contains(&stationary_from) {
            bail!(ScenarioError::invalid_as(
                "protocol.stationary_from",
                stationary_from,
                "in [0, 1)",
                format!("protocol.stationary_from must lie in [0, 1), got {stationary_from}")
            ));
        }
        let (gammas, tau0) = analysis_inputs(&self.analysis)?;
        let friction = self.interface_friction(material.contact_modulus(), gamma0)?;
        let friction = translation_drive(kind, p.drive_stiffness, friction)?;
        if let (Some(_), Some(layer)) = (&friction, &layer) {
            crate::shear::layer_shear(layer)?;
        }
        let jump_force_threshold = self.output_checks(gamma0, &jkr, &indenter, material.contact_modulus())?;
        let protocol = Translation {
            start_depth,
            depth,
            approach_steps,
            distance,
            steps,
            return_stroke: p.return_stroke.unwrap_or(false),
            stationary_from,
            jump_force_threshold,
        };
        Ok(ValidScenario {
            file: self,
            grid,
            material,
            layer,
            gamma,
            gamma0,
            first_contact_factor: None,
            law,
            indenter,
            heights,
            start_depth,
            max_depth: depth,
            depth_step,
            approach_steps,
            max_retract_steps: 0,
            jkr,
            derived,
            jump_force_threshold,
            translation: Some(TranslationSetup {
                kind,
                contact,
                protocol,
                gammas,
                tau0,
                wavelength,
                friction,
            }),
            shear: None,
            roughness: None,
            hold: None,
            warnings: Vec::new(),
        })
    }

    /// The translating contact of a roll / slide / translate (a sphere is a wavy sphere of
    /// zero amplitude), with the slide's substrate roughness; and the waviness wavelength.
    fn translating_contact(
        &self,
        indenter: &Indenter,
        grid: &Grid,
        kind: ProtocolKind,
        substrate_angle: Option<f64>,
        substrate_roughness: Option<Vec<f64>>,
    ) -> Result<(WavySphere, Option<f64>, TranslatingContact)> {
        let name = kind.name();
        let wavy = match indenter {
            Indenter::WavySphere(w) => *w,
            Indenter::Sphere(s) => WavySphere::new(s.radius(), 0.0, grid.size_x(), 0.0)?,
            _ => bail!(ScenarioError::invalid_as(
                "indenter.shape",
                format!("\"{}\"", self.indenter.shape().name()),
                format!("\"wavy_sphere\" or \"sphere\" with protocol.kind = \"{name}\""),
                format!(
                    "protocol.kind = \"{name}\" needs indenter.shape = \"wavy_sphere\" or \"sphere\", got \"{}\"",
                    self.indenter.shape().name()
                )
            )),
        };
        let wavelength = matches!(indenter, Indenter::WavySphere(_)).then(|| wavy.waviness().wavelength());
        let kinematics = match kind {
            ProtocolKind::Roll => Kinematics::Roll,
            ProtocolKind::Translate => Kinematics::Translate,
            _ => {
                let degrees = finite(
                    "protocol.substrate_angle",
                    substrate_angle.unwrap_or(DEFAULT_SUBSTRATE_ANGLE),
                )?;
                Kinematics::Slide {
                    substrate_angle: degrees.to_radians(),
                }
            }
        };
        let mut contact = TranslatingContact::new(wavy, kinematics);
        if let Some(roughness) = substrate_roughness {
            contact = contact.with_substrate_roughness(roughness, grid).map_err(|e| {
                ScenarioError::new(ErrorKind::InvalidValue, format!("[substrate_roughness]: {e}"))
                    .with_key("substrate_roughness")
                    .with_requirement("a roughness map the library accepts")
            })?;
        }
        Ok((wavy, wavelength, contact))
    }
}

/// The contact must stay on the grid over the whole travel: the indenter's axis goes from
/// X = 0 to X = `distance` (and back with a return stroke), so the front of a contact of
/// radius a reaches X + a. The radius is estimated for the smooth sphere at the held
/// depth: on the stable JKR branch (`Jkr::radius_at_depth`, Johnson, Kendall & Roberts
/// 1971) with adhesion, Hertz's √(Rd) without. Beyond the domain's half-width L/2 the
/// contact is cut by the domain edge or lost (zero force, a frictionless "result"): an
/// error naming `protocol.distance` and the numbers (`distance_scale`: the length of one
/// `protocol.distance_unit`). A contact that comes within an element
/// of the border is caught during the run (the border warning of `summary.json`).
fn check_travel_inside(
    grid: &Grid,
    indenter: &WavySphere,
    jkr: Option<&Jkr>,
    depth: f64,
    (raw_distance, distance_scale): (f64, f64),
) -> Result<()> {
    let distance = raw_distance * distance_scale;
    let radius = indenter.sphere().radius();
    let (contact_radius, how) = match jkr {
        Some(jkr) => (
            jkr.radius_at_depth(depth).unwrap_or_else(|| jkr.critical_radius()),
            "the JKR contact radius at protocol.depth",
        ),
        None => (
            (radius * depth.max(0.0)).sqrt(),
            "the Hertz contact radius √(R·d) at protocol.depth",
        ),
    };
    // The indenter moves along x.
    let half_width = 0.5 * grid.size_x();
    let front = distance + contact_radius;
    let inside = front.is_finite() && front <= half_width;
    if !inside {
        let room = half_width - contact_radius;
        let advice = if room > 0.0 {
            let unit = if distance_scale == 1.0 {
                "length units"
            } else {
                "wavelengths"
            };
            format!("protocol.distance at most {:.4e} ({unit})", room / distance_scale)
        } else {
            "a smaller protocol.depth".to_string()
        };
        bail!(ScenarioError::invalid_as(
            "protocol.distance",
            raw_distance,
            "a travel that keeps the contact inside the grid",
            format!(
                "protocol.distance = {raw_distance} carries the contact off the grid: the indenter travels to X = {distance:.4e} and {how} is a ≈ {contact_radius:.4e}, so the contact's front reaches X + a = {front:.4e}, beyond the domain's half-width grid.size/2 = {half_width:.4e} (the contact would be cut by the edge or lost, with zero force); choose {advice}, or a larger grid.size"
            )
        ));
    }
    Ok(())
}

/// `[analysis]`: γ1, γ2 for Eq. 12 (both or neither) and τ0 for Eqs. 16–18.
#[allow(clippy::type_complexity)]
fn analysis_inputs(a: &AnalysisSection) -> Result<(Option<(f64, f64)>, Option<f64>)> {
    let gammas = match (a.gamma_approach, a.gamma_pulloff) {
        (Some(g1), Some(g2)) => Some((
            non_negative("analysis.gamma_approach", g1)?,
            non_negative("analysis.gamma_pulloff", g2)?,
        )),
        (None, None) => None,
        (Some(_), None) => bail!(ScenarioError::missing(
            "analysis.gamma_pulloff",
            "with analysis.gamma_approach",
            "analysis.gamma_pulloff is required with analysis.gamma_approach"
        )),
        (None, Some(_)) => bail!(ScenarioError::missing(
            "analysis.gamma_approach",
            "with analysis.gamma_pulloff",
            "analysis.gamma_approach is required with analysis.gamma_pulloff"
        )),
    };
    let tau0 = a.tau0.map(|t| non_negative("analysis.tau0", t)).transpose()?;
    Ok((gammas, tau0))
}

/// `protocol.drive_stiffness` of a slide or translate into `friction`: finite and > 0,
/// with `[friction]` (the spring pulls against the interface's friction) and not with a
/// roll (a rolling indenter does not carry its surface along).
fn translation_drive(
    kind: ProtocolKind,
    drive_stiffness: Option<f64>,
    friction: Option<InterfaceFriction>,
) -> Result<Option<InterfaceFriction>> {
    let Some(stiffness) = drive_stiffness else {
        return Ok(friction);
    };
    let stiffness = positive("protocol.drive_stiffness", stiffness)?;
    if kind == ProtocolKind::Roll {
        bail!(ScenarioError::invalid_as(
            "protocol.drive_stiffness",
            stiffness,
            "absent with protocol.kind = \"roll\"",
            "protocol.drive_stiffness pulls a slide or a translate through a spring; a rolling indenter does not carry its surface along, so a roll takes a rigid drive"
        ));
    }
    let Some(friction) = friction else {
        bail!(ScenarioError::invalid_as(
            "protocol.drive_stiffness",
            stiffness,
            "with [friction]",
            format!(
                "protocol.drive_stiffness = {stiffness} pulls the indenter through a spring against the interface's friction; give [friction] (law and its bound), or drop the key for a rigid drive"
            )
        ));
    };
    if friction.mode_mixity.weakens() {
        bail!(ScenarioError::invalid_as(
            "protocol.drive_stiffness",
            stiffness,
            "absent with friction.mode_mixity",
            format!(
                "protocol.drive_stiffness = {stiffness} with friction.mode_mixity ({:?}): the spring's rounds (the profile moved to where the indenter goes) are not built around the weakened edge's rounds; drop the key for a rigid drive",
                friction.mode_mixity
            )
        ));
    }
    if friction.coupled {
        bail!(ScenarioError::invalid_as(
            "protocol.drive_stiffness",
            stiffness,
            "absent with friction.coupling = \"full\"",
            format!(
                "protocol.drive_stiffness = {stiffness} with friction.coupling = \"full\": the spring's rounds (the profile moved to where the indenter goes) are not built around the coupled operator's rounds; drop the key for a rigid drive, or use friction.coupling = \"none\" with the spring"
            )
        ));
    }
    Ok(Some(InterfaceFriction {
        drive_stiffness: Some(stiffness),
        ..friction
    }))
}
