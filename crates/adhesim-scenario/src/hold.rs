//! A hold at the deepest indentation (`protocol.hold_time`, `protocol.time_step`) and the
//! aging of the work of adhesion during it (`[adhesion] aging`), validated into the
//! library's [`Hold`]; each refusal names its key.

use crate::checks::{non_negative, positive};
use crate::error::ScenarioError;
use crate::model::*;
use adhesim::{AgingLaw, Hold};
use anyhow::{bail, Result};

/// Hold steps when `protocol.time_step` is not given.
pub const DEFAULT_HOLD_STEPS: f64 = 20.0;
/// The most hold steps.
const MAX_HOLD_STEPS: f64 = 100_000.0;

impl ScenarioFile {
    /// `adhesion.aging` acts during a hold, which only an indentation has.
    pub(crate) fn check_aging_pairing(&self) -> Result<()> {
        let kind = self.protocol.kind();
        if self.adhesion.aging.is_some() && kind != ProtocolKind::IndentPulloff {
            bail!(ScenarioError::invalid_as(
                "adhesion.aging",
                "[adhesion.aging]",
                "absent unless protocol.kind = \"indent_pulloff\" with protocol.hold_time",
                format!(
                    "adhesion.aging ages the bonds during a hold at the deepest indentation (protocol.kind = \"indent_pulloff\" with protocol.hold_time), got protocol.kind = \"{}\"",
                    kind.name()
                )
            ));
        }
        Ok(())
    }

    /// The hold of `protocol` with its aging (None without `hold_time`); `gamma0` is the
    /// scenario's work of adhesion.
    pub(crate) fn validate_hold(&self, protocol: &IndentationProtocol, gamma0: f64) -> Result<Option<Hold>> {
        let Some(time) = protocol.hold_time else {
            if let Some(step) = protocol.time_step {
                bail!(ScenarioError::invalid_as(
                    "protocol.time_step",
                    step,
                    "absent without protocol.hold_time",
                    "protocol.time_step is the step of a hold, and protocol.hold_time is not given"
                ));
            }
            if self.adhesion.aging.is_some() {
                bail!(ScenarioError::missing(
                    "protocol.hold_time",
                    "protocol.hold_time with adhesion.aging",
                    "adhesion.aging ages the bonds during a hold: give protocol.hold_time (and protocol.time_step)"
                ));
            }
            return Ok(None);
        };
        let time = positive("protocol.hold_time", time)?;
        let time_step = match protocol.time_step {
            Some(step) => positive("protocol.time_step", step)?,
            None => time / DEFAULT_HOLD_STEPS,
        };
        if time / time_step > MAX_HOLD_STEPS {
            bail!(ScenarioError::invalid_as(
                "protocol.time_step",
                time_step,
                format!("at least protocol.hold_time/{MAX_HOLD_STEPS}"),
                format!("protocol.hold_time = {time} in steps of protocol.time_step = {time_step} makes more than {MAX_HOLD_STEPS} hold steps")
            ));
        }
        let aging = match &self.adhesion.aging {
            None => None,
            Some(section) => Some(self.aging_law(section, gamma0)?),
        };
        Ok(Some(Hold { time, time_step, aging }))
    }

    /// The law of `[adhesion.aging]`: its own parameter required, the other's refused.
    fn aging_law(&self, section: &AgingSection, gamma0: f64) -> Result<AgingLaw> {
        let law_name = self.adhesion.law.unwrap_or_default();
        if law_name != LawName::Jkr {
            bail!(ScenarioError::invalid_as(
                "adhesion.law",
                format!("\"{}\"", law_name.name()),
                "\"jkr\" with adhesion.aging",
                "adhesion.aging ages the JKR-type detachment rule (adhesion.law = \"jkr\"); a cohesive law's aging is not modelled"
            ));
        }
        if gamma0 <= 0.0 {
            bail!(ScenarioError::invalid_as(
                "adhesion.work_of_adhesion",
                gamma0,
                "> 0 with adhesion.aging",
                "adhesion.aging multiplies the work of adhesion, which is 0: give adhesion.work_of_adhesion > 0"
            ));
        }
        let reference_time = positive("adhesion.aging.reference_time", section.reference_time)?;
        let (own, other) = match section.law {
            AgingLawName::Power => (("exponent", section.exponent), ("coefficient", section.coefficient)),
            AgingLawName::Logarithmic => (("coefficient", section.coefficient), ("exponent", section.exponent)),
        };
        let law = format!("{:?}", section.law).to_lowercase();
        if let (name, Some(value)) = other {
            bail!(ScenarioError::invalid_as(
                &format!("adhesion.aging.{name}"),
                value,
                format!("absent with adhesion.aging.law = \"{law}\""),
                format!("adhesion.aging.{name} belongs to another aging law than \"{law}\" (give adhesion.aging.{} instead)", own.0)
            ));
        }
        let key = format!("adhesion.aging.{}", own.0);
        let Some(value) = own.1 else {
            bail!(ScenarioError::missing(
                &key,
                format!("{key} with adhesion.aging.law = \"{law}\""),
                format!("adhesion.aging.law = \"{law}\" needs {key}")
            ));
        };
        let value = non_negative(&key, value)?;
        let built = match section.law {
            AgingLawName::Power => AgingLaw::power(value, reference_time),
            AgingLawName::Logarithmic => AgingLaw::logarithmic(value, reference_time),
        };
        Ok(built?)
    }
}
