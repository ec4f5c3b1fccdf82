//! Records of completely failed trial rings and the exact failed-ring prediction of quiet
//! steps (docs/physics.md §2.4), with recycled buffers: no allocation per ring round.

use super::params::over_stress_ratio;
use super::{AdhesiveSolver, Detachment};
use crate::solver::ContactState;

/// One round of a trial-ring peel: the trial elements present, their pressures after the
/// solve, and which of them failed.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct RingRound {
    members: Vec<usize>,
    pressures: Vec<f64>,
    #[cfg_attr(feature = "serde", serde(with = "crate::bit_string"))]
    failed: Vec<bool>,
    /// Bound on the error of `pressures` (the solve may have stopped on a certificate).
    error_bound: f64,
}

/// A trial ring tried on contact set `contact` at `depth` that failed completely.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct RingAttempt {
    depth: f64,
    #[cfg_attr(feature = "serde", serde(with = "crate::bit_string"))]
    contact: Vec<bool>,
    rounds: Vec<RingRound>,
}

impl RingAttempt {
    /// Whether the record is of a grid of `len` elements (a restored checkpoint).
    pub(super) fn fits(&self, len: usize) -> bool {
        self.contact.len() == len
            && self.rounds.iter().all(|r| {
                r.members.len() == r.pressures.len()
                    && r.members.len() == r.failed.len()
                    && r.members.iter().all(|&k| k < len)
            })
    }
}

/// Buffers of dropped ring records, reused by the next ones.
#[derive(Debug, Default)]
pub(super) struct RingPool {
    rounds: Vec<RingRound>,
    contacts: Vec<Vec<bool>>,
    round_lists: Vec<Vec<RingRound>>,
}

impl RingPool {
    /// A record of a ring tried on `contact` at `depth`, without rounds yet.
    pub(super) fn attempt(&mut self, depth: f64, contact: &[bool]) -> RingAttempt {
        let mut copy = self.contacts.pop().unwrap_or_default();
        copy.clear();
        copy.extend_from_slice(contact);
        RingAttempt {
            depth,
            contact: copy,
            rounds: self.round_lists.pop().unwrap_or_default(),
        }
    }

    /// An empty round.
    fn round(&mut self) -> RingRound {
        let mut round = self.rounds.pop().unwrap_or_default();
        round.members.clear();
        round.pressures.clear();
        round.failed.clear();
        round
    }

    /// Takes back the buffers of `attempt`.
    fn recycle(&mut self, mut attempt: RingAttempt) {
        self.rounds.append(&mut attempt.rounds);
        self.round_lists.push(attempt.rounds);
        self.contacts.push(attempt.contact);
    }
}

impl AdhesiveSolver {
    /// Forgets the failed rings of the last steps.
    pub(super) fn clear_ring_history(&mut self) {
        for attempt in self.ring_history.drain(..) {
            self.ring_pool.recycle(attempt);
        }
    }

    /// Forgets the ring being tried.
    pub(super) fn drop_current_ring(&mut self) {
        if let Some(attempt) = self.current_ring.take() {
            self.ring_pool.recycle(attempt);
        }
    }

    /// Appends a completely failed ring to the history of the last two.
    pub(super) fn push_ring_history(&mut self, attempt: RingAttempt) {
        if self.ring_history.len() == 2 {
            let oldest = self.ring_history.remove(0);
            self.ring_pool.recycle(oldest);
        }
        self.ring_history.push(attempt);
    }

    /// Records the trial members' pressures and failures of this solve in the ring being
    /// tried (for the failed-ring prediction).
    pub(super) fn record_ring_round(&mut self, state: &ContactState) {
        if self.current_ring.is_none() {
            return;
        }
        let mut round = self.ring_pool.round();
        round.members.extend((0..self.grid.len()).filter(|&k| self.trial[k]));
        round.pressures.extend(round.members.iter().map(|&k| state.pressure[k]));
        round.failed.resize(round.members.len(), false);
        for &k in &self.violators {
            if let Ok(position) = round.members.binary_search(&k) {
                round.failed[position] = true;
            }
        }
        round.error_bound = self.pressure_error_bound;
        if let Some(ring) = self.current_ring.as_mut() {
            ring.rounds.push(round);
        }
    }

    /// Exact shortcut for a quiet step: if the last two steps tried the same trial ring on
    /// the same contact set and every round of its peel released the same elements, the
    /// trial pressures of each round are linear in d (fixed sets), so this step's rounds
    /// are known by extrapolation. When every extrapolated round releases exactly the
    /// recorded elements, the ring fails again: record it and report `true` (no solve).
    pub(super) fn predict_failed_ring(&mut self, depth: f64, state: &ContactState) -> bool {
        if self.params.detachment != Detachment::AllViolators || self.ring_history.len() < 2 {
            return false;
        }
        let (older, newer) = (&self.ring_history[0], &self.ring_history[1]);
        if older.depth == newer.depth
            || newer.depth == depth
            || older.rounds.len() != newer.rounds.len()
            || newer.contact != state.contact
            || older.contact != state.contact
        {
            return false;
        }
        if newer.rounds.first().map(|r| &r.members) != Some(&self.candidates) {
            return false;
        }
        let factor = (depth - newer.depth) / (newer.depth - older.depth);
        let mut predicted = self.ring_pool.attempt(depth, &state.contact);
        let (older, newer) = (&self.ring_history[0], &self.ring_history[1]);
        for (a, b) in older.rounds.iter().zip(&newer.rounds) {
            let mut round = self.ring_pool.round();
            let holds =
                a.members == b.members && a.failed == b.failed && self.extrapolate_round(a, b, factor, &mut round);
            predicted.rounds.push(round);
            if !holds {
                self.ring_pool.recycle(predicted);
                return false;
            }
        }
        self.push_ring_history(predicted);
        true
    }

    /// Fills `round` with the extrapolation of rounds `a` (older) and `b` (newer) by
    /// `factor`, and tells whether it releases exactly b's elements with every decision
    /// outside the extrapolated error bound (the reference rule trusts converged pressures).
    fn extrapolate_round(&self, a: &RingRound, b: &RingRound, factor: f64, round: &mut RingRound) -> bool {
        round.members.extend_from_slice(&b.members);
        round.pressures.extend(
            a.pressures
                .iter()
                .zip(&b.pressures)
                .map(|(p0, p1)| p1 + factor * (p1 - p0)),
        );
        // The same violator rule as find_violators, on the trial members.
        let ratio = |i: usize| over_stress_ratio(round.pressures[i], self.critical_stress[round.members[i]]);
        let any_violator = (0..round.members.len()).any(|i| ratio(i) > 1.0);
        let smallest = (0..round.members.len())
            .map(ratio)
            .filter(|&r| r > 1.0)
            .fold(f64::INFINITY, f64::min);
        round.failed.extend((0..b.members.len()).map(|i| {
            let r = over_stress_ratio(round.pressures[i], self.critical_stress[b.members[i]]);
            any_violator && r >= smallest * (1.0 - 1e-9)
        }));
        if round.failed != b.failed {
            return false;
        }
        // Extrapolated from pressures known to ±error_bound: predict only decisions that
        // bound cannot flip.
        round.error_bound = (1.0 + factor.abs()) * b.error_bound + factor.abs() * a.error_bound;
        self.params.reference_rule
            || !round
                .members
                .iter()
                .zip(&round.pressures)
                .any(|(&k, p)| (-p - self.critical_stress[k]).abs() <= round.error_bound)
    }
}
