//! Slip weakening (Palmer & Rice 1973, *Proc. R. Soc. A* 332, 527; Ida 1972): an element's
//! bound falls linearly from its static value to its kinetic one over the slip distance D_c
//! it has slid since it last stuck, g(s) = g_k + (g_s − g_k)·max(0, 1 − s/D_c). Breaking
//! loose then costs the energy (g_s − g_k)·D_c/2 per area, a fracture energy, so the peak
//! force before a slip event converges with the mesh once the zone over which the bound
//! falls spans a few elements; D_c → 0 is the static law's drop at the first slip.

use super::{FrictionLawError, SlipStatus, TangentialSolver, TangentialState};
use crate::solver::ContactState;

/// The bound of an element of static bound `static_bound` and kinetic bound `kinetic` after
/// a slip `slip` since it last stuck, over the weakening distance `distance`.
#[inline]
pub(super) fn weakened_bound(static_bound: f64, kinetic: f64, slip: f64, distance: f64) -> f64 {
    kinetic + (static_bound - kinetic) * (1.0 - slip / distance).max(0.0)
}

impl TangentialSolver {
    /// The same solver with slip weakening over `distance` (D_c > 0, finite): a stuck
    /// element holds up to its static bound, and once it slips its bound falls linearly
    /// with the slip it has made since it last stuck, to the kinetic bound at D_c
    /// (docs/physics.md §8.2). Needs a static law ([`with_static_law`](Self::with_static_law)
    /// first); D_c = 0 would be the static law's drop itself.
    pub fn with_slip_weakening(mut self, distance: f64) -> Result<Self, FrictionLawError> {
        if self.static_law.is_none() {
            return Err(FrictionLawError::WeakeningWithoutStaticLaw(distance));
        }
        if !(distance.is_finite() && distance > 0.0) {
            return Err(FrictionLawError::WeakeningDistance(distance));
        }
        self.weakening_distance = Some(distance);
        Ok(self)
    }

    /// The slip weakening distance D_c (None: the bound drops at once when an element breaks
    /// loose).
    pub fn slip_weakening_distance(&self) -> Option<f64> {
        self.weakening_distance
    }

    /// Element `i`'s starting bound under slip weakening: the static bound `static_bound`
    /// if it starts stuck, weakened by the slip since it last stuck if it keeps slipping.
    pub(super) fn start_weakening(
        &mut self,
        i: usize,
        static_bound: f64,
        slipping: bool,
        state: &TangentialState,
    ) -> f64 {
        let distance = self.weakening_distance.unwrap_or(f64::INFINITY);
        let slip = if slipping {
            state.slip_since_stuck.get(i).copied().unwrap_or(0.0)
        } else {
            0.0
        };
        self.static_bound[i] = static_bound;
        self.slip_before[i] = slip;
        weakened_bound(static_bound, self.kinetic[i], slip, distance)
    }

    /// Element `i`, slipping, with `slip` its slip in the step as the round's Newton point
    /// estimates it ((|z| − g)/ρ, which is also what a stuck element breaking loose is about
    /// to slip): its bound weakened by the slip since it last stuck, never above its bound
    /// of the last round (so the rounds end). Returns the bound's relative fall (0 without
    /// weakening).
    pub(super) fn weaken(&mut self, i: usize, slip: f64) -> f64 {
        let Some(distance) = self.weakening_distance else {
            return 0.0;
        };
        let was = self.bound[i];
        let weakened = weakened_bound(
            self.static_bound[i],
            self.kinetic[i],
            self.slip_before[i] + slip,
            distance,
        )
        .min(was);
        self.bound[i] = weakened;
        if was > 0.0 {
            (was - weakened) / was
        } else {
            0.0
        }
    }

    /// Each element's slip since it last stuck at the end of a step (kept only under slip
    /// weakening): the slip before the step plus this step's for a slipping element, 0 for
    /// the others.
    pub(super) fn record_weakening_slip(&self, normal: &ContactState, state: &mut TangentialState) {
        if self.weakening_distance.is_none() {
            state.slip_since_stuck.clear();
            return;
        }
        let n = state.status.len();
        state.slip_since_stuck.resize(n, 0.0);
        for i in 0..n {
            state.slip_since_stuck[i] = if normal.contact[i] && state.status[i] == SlipStatus::Slip {
                let (sx, sy) = self.gap(state, i);
                self.slip_before[i] + sx.hypot(sy)
            } else {
                0.0
            };
        }
    }
}

#[cfg(test)]
#[path = "weakening_tests.rs"]
mod tests;
