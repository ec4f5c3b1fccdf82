//! What an [`AdhesiveSolver`] carries from one step to the next, taken between steps and
//! put back into a fresh solver of the same problem (mid-run checkpoints of a protocol).
//!
//! Carried between steps (everything else is scratch written before it is read in a step,
//! or built once from the problem): the last two steps' final depth, pressure and contact
//! (the extrapolated warm start), the completely failed trial rings of the last two steps
//! and the ring being tried (the failed-ring prediction), the bans (carried while
//! retracting), the xorshift state of [`super::Detachment::RandomHalf`], the error bounds
//! and flags of the last solve, and the counters over the solver's life.

use super::ring::RingAttempt;
use super::AdhesiveSolver;
use crate::solver::ContactState;

/// The final state of one earlier step, for the extrapolated warm start.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct HistoryEntry {
    depth: f64,
    pressure: Vec<f64>,
    #[cfg_attr(feature = "serde", serde(with = "crate::bit_string"))]
    contact: Vec<bool>,
}

/// The state of an [`AdhesiveSolver`] between two steps (see the module text).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AdhesiveCheckpoint {
    elements: usize,
    history: Vec<HistoryEntry>,
    ring_history: Vec<RingAttempt>,
    current_ring: Option<RingAttempt>,
    #[cfg_attr(feature = "serde", serde(with = "crate::bit_string"))]
    banned: Vec<bool>,
    random_state: u64,
    pressure_error_bound: f64,
    gap_error_bound: f64,
    last_solve_certified: bool,
    displacement_drifted: bool,
    preconditioner_applications: u64,
    certified_stops: u64,
    tie_refinements: u64,
    unresolved_ties: u64,
    local_releases: u64,
    predicted_rings: u64,
    prediction_fallbacks: u64,
    prediction_seconds: f64,
}

impl AdhesiveSolver {
    /// The state this solver carries into its next step.
    pub fn checkpoint(&self) -> AdhesiveCheckpoint {
        AdhesiveCheckpoint {
            elements: self.grid.len(),
            history: self
                .history
                .iter()
                .map(|(depth, pressure, contact)| HistoryEntry {
                    depth: *depth,
                    pressure: pressure.clone(),
                    contact: contact.clone(),
                })
                .collect(),
            ring_history: self.ring_history.clone(),
            current_ring: self.current_ring.clone(),
            banned: self.banned.clone(),
            random_state: self.random_state,
            pressure_error_bound: self.pressure_error_bound,
            gap_error_bound: self.gap_error_bound,
            last_solve_certified: self.last_solve_certified,
            displacement_drifted: self.displacement_drifted,
            preconditioner_applications: self.preconditioner_applications,
            certified_stops: self.certified_stops,
            tie_refinements: self.tie_refinements,
            unresolved_ties: self.unresolved_ties,
            local_releases: self.local_releases,
            predicted_rings: self.predicted_rings,
            prediction_fallbacks: self.prediction_fallbacks,
            prediction_seconds: self.prediction_seconds,
        }
    }

    /// Puts back the state of `checkpoint`, taken when the step that left `state` ended
    /// (the displacement of `state` belongs to its pressure). An error (nothing changed)
    /// when the checkpoint is of another grid size.
    pub fn restore(&mut self, checkpoint: &AdhesiveCheckpoint, state: &ContactState) -> Result<(), String> {
        let len = self.grid.len();
        let sizes_match = checkpoint.elements == len
            && checkpoint.banned.len() == len
            && state.pressure.len() == len
            && checkpoint.history.len() <= 2
            && checkpoint
                .history
                .iter()
                .all(|h| h.pressure.len() == len && h.contact.len() == len)
            && checkpoint.ring_history.len() <= 2
            && checkpoint
                .ring_history
                .iter()
                .chain(&checkpoint.current_ring)
                .all(|ring| ring.fits(len));
        if !sizes_match {
            return Err(format!(
                "the adhesive solver's checkpoint is of {} elements (or malformed), the grid has {len}",
                checkpoint.elements
            ));
        }
        self.reset();
        let c = checkpoint;
        self.history = c
            .history
            .iter()
            .map(|h| (h.depth, h.pressure.clone(), h.contact.clone()))
            .collect();
        self.ring_history = c.ring_history.clone();
        self.current_ring = c.current_ring.clone();
        self.banned.copy_from_slice(&c.banned);
        self.random_state = c.random_state;
        self.displacement_pressure.copy_from_slice(&state.pressure);
        (self.pressure_error_bound, self.gap_error_bound) = (c.pressure_error_bound, c.gap_error_bound);
        self.last_solve_certified = c.last_solve_certified;
        self.displacement_drifted = c.displacement_drifted;
        self.preconditioner_applications = c.preconditioner_applications;
        self.certified_stops = c.certified_stops;
        self.tie_refinements = c.tie_refinements;
        self.unresolved_ties = c.unresolved_ties;
        self.local_releases = c.local_releases;
        self.predicted_rings = c.predicted_rings;
        self.prediction_fallbacks = c.prediction_fallbacks;
        self.prediction_seconds = c.prediction_seconds;
        Ok(())
    }
}
