//! A hold at the deepest indentation, with adhesion that ages: each element's work of
//! adhesion grows with the time it has been in contact (the paper's Sect. 5.2, Eq. 15:
//! the pull-off force grows as t^0.0883 with the waiting time t; docs/physics.md §2.7).

use super::{IndentPulloff, RunState};
use crate::elastic::ElasticOperator;
use crate::problem::Problem;
use crate::protocol::{IndentCheckpoint, NormalSolver, Observer, Phase, ProtocolError, ProtocolSummary};

/// How an element's work of adhesion grows with the time t it has been in contact, as
/// the factor γ(t)/γ(0).
///
/// # Example
/// ```
/// use adhesim::AgingLaw;
///
/// let power = AgingLaw::power(0.0883, 1.0)?;
/// assert_eq!(power.factor(0.0), 1.0);
/// // Far beyond the reference time the factor grows as t^β.
/// let ratio = power.factor(3000.0) / power.factor(300.0);
/// assert!((ratio.ln() / 10f64.ln() - 0.0883).abs() < 1e-3);
/// assert!(AgingLaw::power(-0.1, 1.0).is_err());
/// # Ok::<(), adhesim::ProtocolError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AgingLaw {
    /// γ(t) = γ0·(1 + t/t_ref)^β: a power of the contact time once t ≫ t_ref, as the
    /// paper's Eq. 15 has the pull-off force.
    Power {
        /// β ≥ 0.
        exponent: f64,
        /// t_ref > 0.
        reference_time: f64,
    },
    /// γ(t) = γ0·[1 + b·ln(1 + t/t_ref)]: the logarithmic strengthening of contacts at
    /// rest (Dieterich 1972, *J. Geophys. Res.* 77, 3690).
    Logarithmic {
        /// b ≥ 0.
        coefficient: f64,
        /// t_ref > 0.
        reference_time: f64,
    },
}

impl AgingLaw {
    /// [`AgingLaw::Power`]; an error for β not finite and ≥ 0 or t_ref not finite and > 0.
    pub fn power(exponent: f64, reference_time: f64) -> Result<Self, ProtocolError> {
        check("exponent", exponent, reference_time)?;
        Ok(Self::Power {
            exponent,
            reference_time,
        })
    }

    /// [`AgingLaw::Logarithmic`]; an error for b not finite and ≥ 0 or t_ref not finite
    /// and > 0.
    pub fn logarithmic(coefficient: f64, reference_time: f64) -> Result<Self, ProtocolError> {
        check("coefficient", coefficient, reference_time)?;
        Ok(Self::Logarithmic {
            coefficient,
            reference_time,
        })
    }

    /// γ(t)/γ(0) after a contact time `age`.
    pub fn factor(&self, age: f64) -> f64 {
        match *self {
            Self::Power {
                exponent,
                reference_time,
            } => (1.0 + age / reference_time).powf(exponent),
            Self::Logarithmic {
                coefficient,
                reference_time,
            } => 1.0 + coefficient * (age / reference_time).ln_1p(),
        }
    }
}

fn check(name: &str, value: f64, reference_time: f64) -> Result<(), ProtocolError> {
    if !(value.is_finite() && value >= 0.0 && reference_time.is_finite() && reference_time > 0.0) {
        return Err(ProtocolError::InvalidParameter(format!(
            "aging {name} must be finite and >= 0 and the reference time finite and > 0, got {value} and {reference_time}"
        )));
    }
    Ok(())
}

/// A hold at the deepest indentation between the approach and the retraction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hold {
    /// How long the indenter is held.
    pub time: f64,
    /// The longest time step: the hold takes ⌈time/time_step⌉ equal steps.
    pub time_step: f64,
    /// The aging of the work of adhesion (None: time passes and nothing ages).
    pub aging: Option<AgingLaw>,
}

impl Hold {
    /// Steps of the hold.
    pub fn steps(&self) -> usize {
        ((self.time / self.time_step) * (1.0 - 1e-12)).ceil().max(1.0) as usize
    }

    fn check(&self) -> Result<(), ProtocolError> {
        let positive = |value: f64| value.is_finite() && value > 0.0;
        if !(positive(self.time) && positive(self.time_step)) || self.steps() > MAX_HOLD_STEPS {
            return Err(ProtocolError::InvalidParameter(format!(
                "hold time ({}) and time step ({}) must be finite and > 0, with at most {MAX_HOLD_STEPS} steps",
                self.time, self.time_step
            )));
        }
        Ok(())
    }
}

/// The most steps of a hold.
const MAX_HOLD_STEPS: usize = 100_000;

/// The ages and the work of adhesion of the elements during a hold.
struct Aging {
    law: AgingLaw,
    /// γ per element at the hold's start.
    fresh: Vec<f64>,
    /// Time each element has been in contact (0 off contact).
    ages: Vec<f64>,
    /// γ per element now.
    work_of_adhesion: Vec<f64>,
}

impl IndentPulloff {
    /// Approach to the deepest indentation, `hold` there, then retract until contact is
    /// lost; reports each step to `observer` (the hold's with [`Phase::Hold`] and their
    /// time in [`StepRecord::time`](crate::protocol::StepRecord::time)). From `start`, a
    /// checkpoint of the approach, when given (none is offered from the hold on: the ages
    /// are not in it).
    ///
    /// At each hold step the elements in contact age by the step's time and the others
    /// start again from 0 (a bond that opens is lost); the JKR-type solver's work of
    /// adhesion is set to γ0·factor(age) per element, and the step is solved at the held
    /// depth, so the contact may grow as its edge strengthens. The retraction is fast next
    /// to the hold: the ages stop with it. Aging needs the JKR-type adhesive solver.
    pub fn run_holding(
        &self,
        problem: &mut Problem,
        solver: &mut NormalSolver,
        observer: &mut dyn Observer,
        start: Option<&IndentCheckpoint>,
        hold: &Hold,
    ) -> Result<ProtocolSummary, ProtocolError> {
        hold.check()?;
        if hold.aging.is_some() && solver.as_adhesive_mut().is_none() {
            return Err(ProtocolError::InvalidParameter(
                "aging adhesion needs the JKR-type adhesive solver (adhesion with a sharp detachment rule)".into(),
            ));
        }
        self.run_phases(problem, solver, observer, start, Some(hold))
    }

    /// The hold's steps at the deepest indentation.
    pub(super) fn hold(
        &self,
        operator: &mut dyn ElasticOperator,
        heights: &[f64],
        solver: &mut NormalSolver,
        observer: &mut dyn Observer,
        run: &mut RunState,
        hold: &Hold,
    ) -> Result<(), ProtocolError> {
        let steps = hold.steps();
        let time_step = hold.time / steps as f64;
        let mut aging = match (hold.aging, solver.as_adhesive_mut()) {
            (Some(law), Some(adhesive)) => Some(Aging {
                law,
                fresh: adhesive.work_of_adhesion().to_vec(),
                ages: vec![0.0; run.state.contact.len()],
                work_of_adhesion: adhesive.work_of_adhesion().to_vec(),
            }),
            _ => None,
        };
        for k in 0..steps {
            run.time = (k + 1) as f64 * time_step;
            if let (Some(aging), Some(adhesive)) = (aging.as_mut(), solver.as_adhesive_mut()) {
                for (i, &contact) in run.state.contact.iter().enumerate() {
                    aging.ages[i] = if contact { aging.ages[i] + time_step } else { 0.0 };
                    aging.work_of_adhesion[i] = aging.fresh[i] * aging.law.factor(aging.ages[i]);
                }
                adhesive.set_work_of_adhesion(&aging.work_of_adhesion);
            }
            self.run_step(operator, heights, solver, observer, run, self.max_depth, Phase::Hold)?;
        }
        Ok(())
    }
}
