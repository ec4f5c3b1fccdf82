//! The `[protocol]` and `[friction]` keys of a shear that shape its approach and its
//! operators: the incline, the mode mixity, the coupling, the press and the layer.

use crate::checks::{beyond_first_contact, finite, held_depth};
use crate::error::ScenarioError;
use crate::guards::step_count;
use crate::model::*;
use crate::validated::DEFAULT_APPROACH_STEPS;
use adhesim::protocol::ModeMixity;
use adhesim::{ElasticLayer, LayerBase};
use anyhow::{bail, Result};

/// `protocol.incline` in radians (default 0): strictly between −90 and 90 degrees.
pub(super) fn incline(degrees: Option<f64>) -> Result<f64> {
    let degrees = degrees.unwrap_or(0.0);
    if !(degrees.is_finite() && degrees.abs() < 90.0) {
        bail!(ScenarioError::invalid(
            "protocol.incline",
            degrees,
            "strictly between -90 and 90 (degrees from the surface; > 0 into the body)"
        ));
    }
    Ok(degrees.to_radians())
}

/// `friction.mode_mixity` (default 0) and its front and rear values
/// (`friction.mode_mixity_front`, `friction.mode_mixity_rear`, default `mode_mixity`): each
/// in [0, 1], and above 0 only where there is an adhesive edge to weaken.
pub(super) fn mode_mixity(section: &FrictionSection, work_of_adhesion: f64) -> Result<ModeMixity> {
    let along = section.mode_mixity.unwrap_or(0.0);
    let mixity = ModeMixity {
        along,
        front: section.mode_mixity_front.unwrap_or(along),
        rear: section.mode_mixity_rear.unwrap_or(along),
    };
    for (key, value) in mixity_keys(section) {
        if !(0.0..=1.0).contains(&value) {
            bail!(ScenarioError::invalid(key, value, "in [0, 1]"));
        }
        if value > 0.0 && work_of_adhesion <= 0.0 {
            bail!(ScenarioError::invalid_as(
                key,
                value,
                "0 without adhesion",
                format!("{key} = {value} weakens an adhesive edge, but adhesion.work_of_adhesion is 0: give a work of adhesion or drop {key}")
            ));
        }
    }
    Ok(mixity)
}

/// The mode mixity keys given, with their values.
pub(crate) fn mixity_keys(section: &FrictionSection) -> impl Iterator<Item = (&'static str, f64)> {
    [
        ("friction.mode_mixity", section.mode_mixity),
        ("friction.mode_mixity_front", section.mode_mixity_front),
        ("friction.mode_mixity_rear", section.mode_mixity_rear),
    ]
    .into_iter()
    .filter_map(|(key, value)| value.map(|value| (key, value)))
}

/// `friction.coupling = "full"`: the coupled operator of a half-space or a layer.
pub(super) fn coupled(section: &FrictionSection) -> bool {
    section.coupling == Some(CouplingName::Full)
}

/// `protocol.depth` and `protocol.press_depth` in length units. Without a press the held
/// depth must exceed the first contact's; with one the press must, and the held depth lies
/// below the press (at, or above, the first contact too: the contact then holds by
/// adhesion).
pub(super) fn approach_depths(p: &ShearProtocol, unit: f64, start_depth: f64) -> Result<(f64, Option<f64>)> {
    let Some(raw_press) = p.press_depth else {
        return Ok((held_depth(p.depth, unit, start_depth)?, None));
    };
    let press = beyond_first_contact("protocol.press_depth", raw_press, unit, start_depth)?;
    let depth = finite("protocol.depth", p.depth)? * unit;
    if depth >= press {
        bail!(ScenarioError::invalid_as(
            "protocol.depth",
            p.depth,
            format!("< {raw_press} (protocol.press_depth)"),
            format!(
                "protocol.depth ({}) must lie below protocol.press_depth ({raw_press}): the indenter is lifted to it after the press",
                p.depth
            )
        ));
    }
    Ok((depth, Some(press)))
}

/// `protocol.approach_steps` (default 50): at least 2 with a press, one down and one up.
pub(super) fn approach_steps(p: &ShearProtocol, pressed: bool) -> Result<usize> {
    let approach_steps = step_count(
        "protocol.approach_steps",
        p.approach_steps.unwrap_or(DEFAULT_APPROACH_STEPS),
    )?;
    if pressed && approach_steps < 2 {
        bail!(ScenarioError::invalid_as(
            "protocol.approach_steps",
            approach_steps,
            ">= 2 with protocol.press_depth",
            format!("protocol.approach_steps = {approach_steps}: a press and a lift take at least 2 approach steps")
        ));
    }
    Ok(approach_steps)
}

/// Friction on a layer (a shear, or `[friction]` with a roll, slide or translate): bonded to
/// its base (a frictionless base lets it slide). A shear-weakened edge uses the half-space
/// element's energy ratio, as the JKR-type rule uses its detachment stress: the layer's near
/// field is the half-space's to O(Δ/t).
pub(crate) fn layer_shear(layer: &ElasticLayer) -> Result<()> {
    if layer.base() == LayerBase::Frictionless {
        bail!(ScenarioError::invalid_as(
            "material.base",
            "\"frictionless\"",
            "\"bonded\" with [friction]",
            "a layer on a frictionless base slides on it under a tangential load: use material.base = \"bonded\""
        ));
    }
    Ok(())
}

/// `protocol.normal_control` (default `"depth"`): `"force"` holds the normal force of the end
/// of the approach during the shift; refused with an incline (the path sets the depth).
pub(super) fn normal_control(p: &ShearProtocol) -> Result<bool> {
    if p.normal_control.unwrap_or_default() == NormalControl::Depth {
        return Ok(false);
    }
    if p.incline.is_some_and(|incline| incline != 0.0) {
        bail!(ScenarioError::invalid_as(
            "protocol.normal_control",
            "\"force\"",
            "\"depth\" with protocol.incline",
            "protocol.normal_control = \"force\" does not go with protocol.incline: an inclined path sets the depth at each step",
        ));
    }
    Ok(true)
}
