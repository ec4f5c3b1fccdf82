//! One summary for a run of any protocol, and the counters every protocol keeps.

use super::{ProtocolSummary, ShearSummary, TranslationSummary};

/// What a run gives back, whatever its protocol: the protocol's own summary, with the
/// counters they all keep ([`counters`](Self::counters)).
#[derive(Debug, Clone)]
pub enum RunSummary {
    /// An indentation (approach and pull-off, with or without a hold).
    Indentation(ProtocolSummary),
    /// A roll, slide or translate.
    Translation(TranslationSummary),
    /// A shear.
    Shear(ShearSummary),
}

/// The solver's counters of a run (the performance section of `summary.json`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RunCounters {
    /// Steps done.
    pub steps: usize,
    /// Fixed-set solves.
    pub solves: usize,
    /// CG iterations summed over all solves.
    pub cg_iterations: usize,
    /// Forward + inverse FFT pairs of the elastic operators.
    pub operator_applications: u64,
    /// Of those, the pairs of the adhesive CG on contact windows.
    pub window_applications: u64,
    /// The CG preconditioner's applications (not in `operator_applications`).
    pub preconditioner_applications: u64,
    /// Contact on the border of a free grid at some step.
    pub touches_border: bool,
}

/// The counters of a summary: every protocol's summary names them alike.
macro_rules! counters_of {
    ($summary:expr) => {
        RunCounters {
            steps: $summary.steps,
            solves: $summary.solves,
            cg_iterations: $summary.cg_iterations,
            operator_applications: $summary.operator_applications,
            window_applications: $summary.window_applications,
            preconditioner_applications: $summary.preconditioner_applications,
            touches_border: $summary.touches_border,
        }
    };
}

impl RunSummary {
    /// The run's counters.
    ///
    /// # Example
    /// ```
    /// use adhesim::{RunSummary, TranslationSummary};
    ///
    /// let summary = RunSummary::from(TranslationSummary {
    ///     steps: 40,
    ///     solves: 52,
    ///     ..TranslationSummary::default()
    /// });
    /// let counters = summary.counters();
    /// assert_eq!((counters.steps, counters.solves, counters.cg_iterations), (40, 52, 0));
    /// ```
    pub fn counters(&self) -> RunCounters {
        match self {
            Self::Indentation(summary) => counters_of!(summary),
            Self::Translation(summary) => counters_of!(summary),
            Self::Shear(summary) => counters_of!(summary),
        }
    }
}

impl From<ProtocolSummary> for RunSummary {
    fn from(summary: ProtocolSummary) -> Self {
        Self::Indentation(summary)
    }
}

impl From<TranslationSummary> for RunSummary {
    fn from(summary: TranslationSummary) -> Self {
        Self::Translation(summary)
    }
}

impl From<ShearSummary> for RunSummary {
    fn from(summary: ShearSummary) -> Self {
        Self::Shear(summary)
    }
}
