//! Validation of the roll / slide / translate protocols (`[protocol]` kind roll, slide,
//! translate, and `[analysis]`).

use crate::guards::step_count;
use crate::model::*;
use crate::validate::{finite, non_negative, positive};
use adhesim::analysis::reference::Jkr;
use adhesim::geometry::WavySphere;
use adhesim::{ElasticMaterial, Grid, Indenter, Kinematics, TranslatingContact, Translation};
use anyhow::{anyhow, bail, Result};

/// What `validate` has built from every section but `[protocol]`, handed to the
/// indentation or the roll/slide part (not the friction analysis's `TranslationInputs`).
pub(crate) struct ValidatedSections {
    pub(crate) grid: Grid,
    pub(crate) material: ElasticMaterial,
    pub(crate) gamma: Vec<f64>,
    pub(crate) gamma0: f64,
    pub(crate) indenter: Indenter,
    /// Length of one `depth_unit`.
    pub(crate) unit: f64,
    pub(crate) jkr: Option<Jkr>,
    pub(crate) derived: Derived,
    /// `[substrate_roughness]` on the grid (slide only).
    pub(crate) substrate_roughness: Option<Vec<f64>>,
}

/// Default approach steps of roll / slide / translate.
pub const DEFAULT_APPROACH_STEPS: i64 = 50;
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
            gamma,
            gamma0,
            indenter,
            unit,
            jkr,
            derived,
            substrate_roughness,
        } = inputs;
        let p = &self.protocol;
        let kind = p.kind;
        let name = kind.name();
        check_translation_keys(p)?;
        let wavy = match &indenter {
            Indenter::WavySphere(w) => *w,
            Indenter::Sphere(s) => WavySphere::new(s.radius(), 0.0, grid.size(), 0.0)?,
            _ => bail!(
                "protocol.kind = \"{name}\" needs indenter.shape = \"wavy_sphere\" or \"sphere\", got \"{}\"",
                self.indenter.shape.name()
            ),
        };
        let wavelength = matches!(indenter, Indenter::WavySphere(_)).then(|| wavy.waviness().wavelength());
        let kinematics = match kind {
            ProtocolKind::Roll => Kinematics::Roll,
            ProtocolKind::Translate => Kinematics::Translate,
            _ => {
                let degrees = finite(
                    "protocol.substrate_angle",
                    p.substrate_angle.unwrap_or(DEFAULT_SUBSTRATE_ANGLE),
                )?;
                Kinematics::Slide {
                    substrate_angle: degrees.to_radians(),
                }
            }
        };
        let mut contact = TranslatingContact::new(wavy, kinematics);
        if let Some(roughness) = substrate_roughness {
            contact = contact
                .with_substrate_roughness(roughness, &grid)
                .map_err(|e| anyhow!("[substrate_roughness]: {e}"))?;
        }
        let mut heights = vec![0.0; grid.len()];
        contact.fill_heights(&grid, 0.0, &mut heights);
        let start_depth = heights.iter().copied().fold(f64::INFINITY, f64::min);
        let raw_depth = p
            .depth
            .ok_or_else(|| anyhow!("missing key `protocol.depth` (needed by protocol.kind = \"{name}\")"))?;
        let depth = finite("protocol.depth", raw_depth)? * unit;
        if depth <= start_depth {
            bail!(
                "protocol.depth must exceed the depth of first contact ({:.6e} in depth_unit), got {raw_depth}",
                start_depth / unit
            );
        }
        let raw_distance = p
            .distance
            .ok_or_else(|| anyhow!("missing key `protocol.distance` (needed by protocol.kind = \"{name}\")"))?;
        let distance_scale = match p.distance_unit.unwrap_or_default() {
            DistanceUnit::Length => 1.0,
            DistanceUnit::Wavelength => wavelength.ok_or_else(|| {
                anyhow!(
                    "protocol.distance_unit = \"wavelength\" needs indenter.shape = \"wavy_sphere\" (its indenter.wavelength)"
                )
            })?,
        };
        let distance = positive("protocol.distance", raw_distance)? * distance_scale;
        let steps = p
            .steps
            .ok_or_else(|| anyhow!("missing key `protocol.steps` (steps of the travel, protocol.kind = \"{name}\")"))?;
        let steps = step_count("protocol.steps", steps)?;
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
            bail!("protocol.stationary_from must lie in [0, 1), got {stationary_from}");
        }
        let (gammas, tau0) = analysis_inputs(&self.analysis)?;
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
            gamma,
            gamma0,
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
            }),
            roughness: None,
            warnings: Vec::new(),
        })
    }
}

/// Keys of `[protocol]` that a translation of this kind does not use.
fn check_translation_keys(p: &ProtocolSection) -> Result<()> {
    let kind = p.kind;
    let name = kind.name();
    for (key, is_set) in [
        ("max_depth", p.max_depth.is_some()),
        ("step", p.step.is_some()),
        ("max_retract_steps", p.max_retract_steps.is_some()),
    ] {
        if is_set {
            let hint = if key == "max_depth" {
                " (use protocol.depth)"
            } else {
                ""
            };
            bail!("protocol.{key} is not used by protocol.kind = \"{name}\"{hint}");
        }
    }
    if p.substrate_angle.is_some() && kind != ProtocolKind::Slide {
        bail!("protocol.substrate_angle is used by protocol.kind = \"slide\" only, not \"{name}\"");
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
        (Some(_), None) => bail!("analysis.gamma_pulloff is required with analysis.gamma_approach"),
        (None, Some(_)) => bail!("analysis.gamma_approach is required with analysis.gamma_pulloff"),
    };
    let tau0 = a.tau0.map(|t| non_negative("analysis.tau0", t)).transpose()?;
    Ok((gammas, tau0))
}
