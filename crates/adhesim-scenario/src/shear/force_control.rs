//! Force control of a shear: `protocol.tangential_force` in place of `protocol.distance`,
//! with what it does not combine with refused by name.

use crate::checks::positive;
use crate::error::ScenarioError;
use crate::model::*;
use adhesim::{FrictionLaw, TangentialForce};
use anyhow::{bail, Result};

/// `protocol.distance` or, for force control, `protocol.tangential_force` (exactly one), with
/// what force control does not combine with refused by name.
pub(super) fn shift_or_force(
    p: &ShearProtocol,
    friction: &FrictionSection,
    law: FrictionLaw,
    static_law: Option<FrictionLaw>,
) -> Result<(f64, Option<TangentialForce>)> {
    let (distance, force) = match (p.distance, p.tangential_force) {
        (Some(distance), None) => {
            if let Some(unit) = p.tangential_force_unit {
                bail!(ScenarioError::invalid_as(
                    "protocol.tangential_force_unit",
                    format!("{unit:?}").to_lowercase(),
                    "absent without protocol.tangential_force",
                    "protocol.tangential_force_unit is the unit of protocol.tangential_force, which is not given"
                ));
            }
            return Ok((positive("protocol.distance", distance)?, None));
        }
        (None, Some(force)) => (0.0, positive("protocol.tangential_force", force)?),
        (Some(_), Some(force)) => bail!(ScenarioError::invalid_as(
            "protocol.tangential_force",
            force,
            "absent with protocol.distance",
            "give protocol.distance (the shift is imposed) or protocol.tangential_force (the force is imposed), not both"
        )),
        (None, None) => bail!(ScenarioError::missing(
            "protocol.distance",
            "protocol.distance or protocol.tangential_force with protocol.kind = \"shear\"",
            "protocol.kind = \"shear\" needs protocol.distance (the shift) or protocol.tangential_force (an imposed force)"
        )),
    };
    let refuse = |key: &str, why: &str| -> Result<()> {
        bail!(ScenarioError::invalid_as(
            "protocol.tangential_force",
            force,
            format!("absent with {key}"),
            format!("protocol.tangential_force does not go with {key}: {why}")
        ))
    };
    if static_law.is_some() {
        refuse("friction.static_*", "a static friction law's force falls when the contact breaks loose, which no imposed force follows quasi-statically")?;
    }
    if p.drive_stiffness.is_some() {
        refuse(
            "protocol.drive_stiffness",
            "the drive's spring and an imposed force both set the force; give one",
        )?;
    }
    if p.incline.is_some_and(|incline| incline != 0.0) {
        refuse(
            "protocol.incline",
            "force control holds the normal problem fixed, which an inclined path changes at each step",
        )?;
    }
    if let Some((key, _)) = super::mixity_keys(friction).find(|&(_, m)| m != 0.0) {
        refuse(
            key,
            "force control holds the normal problem fixed, which a weakened edge changes at each step",
        )?;
    }
    let control = match p.tangential_force_unit.unwrap_or_default() {
        TangentialForceUnit::Force => TangentialForce::Absolute(force),
        TangentialForceUnit::FrictionLimit => {
            if law == FrictionLaw::NoSlip {
                refuse(
                    "friction.law = \"no_slip\"",
                    "a glued interface has no friction limit to share",
                )?;
            }
            if force >= 1.0 {
                bail!(ScenarioError::invalid_as(
                    "protocol.tangential_force",
                    force,
                    "below 1 with tangential_force_unit = \"friction_limit\"",
                    format!("protocol.tangential_force = {force} of the friction limit: at 1 and above the interface slides without end (gross slip), so no shift carries it; control the shift (protocol.distance) to slide")
                ));
            }
            TangentialForce::OfCapacity(force)
        }
    };
    Ok((distance, Some(control)))
}
