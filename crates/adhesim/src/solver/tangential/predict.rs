//! The predictor of a step's starting tractions from the last step's change.

use super::{SlipStatus, StepHistory, TangentialSolver, TangentialState};
use crate::solver::ContactState;

/// What a step leaves the next beyond its [`TangentialState`]: the predictor's memory and
/// the secant stiffness of force control.
#[derive(Debug, Clone)]
pub(crate) struct StepMemory {
    history: Option<StepHistory>,
    force_stiffness: Option<f64>,
}

impl TangentialSolver {
    /// The start of a step that continues the last one in the same direction: the last
    /// step's traction change, scaled to this step's shift increment, added to each
    /// contact element's traction and put back in its disc (on the circle: slipping along
    /// it). Only the starting point of the Newton rounds changes, not their solution.
    /// (Not after a slip event: its change is no guide to the next step's.) `rho` is the
    /// Newton point's 1/K_ii, with which a predicted break estimates its slip.
    pub(super) fn predict(
        &mut self,
        normal: &ContactState,
        increment: [f64; 2],
        state: &mut TangentialState,
        rho: f64,
    ) {
        if state.at_rest {
            return;
        }
        let Some(history) = self.history.take() else {
            return;
        };
        self.extrapolate(&history, normal, increment, state, rho);
        self.history = Some(history);
    }

    /// The memory the next step starts from: a step tried and undone (a trial depth of
    /// normal-force control) puts it back with [`put_back_memory`](Self::put_back_memory),
    /// so that the step it keeps starts as it would have without the trials.
    pub(crate) fn memory(&self) -> StepMemory {
        StepMemory {
            history: self.history.clone(),
            force_stiffness: self.force_stiffness,
        }
    }

    /// Puts back a [`memory`](Self::memory).
    pub(crate) fn put_back_memory(&mut self, memory: &StepMemory) {
        self.history.clone_from(&memory.history);
        self.force_stiffness = memory.force_stiffness;
    }

    /// [`predict`](Self::predict) from the last step's tractions `before` and increment.
    fn extrapolate(
        &mut self,
        (before, last): &([Vec<f64>; 2], [f64; 2]),
        normal: &ContactState,
        increment: [f64; 2],
        state: &mut TangentialState,
        rho: f64,
    ) {
        let last_squared = last[0] * last[0] + last[1] * last[1];
        let along = increment[0] * last[0] + increment[1] * last[1];
        if before[0].len() != state.status.len() || !(last_squared > 0.0 && along > 0.0) {
            return;
        }
        let ratio = along / last_squared;
        for i in 0..state.status.len() {
            let bound = self.bound[i];
            if !normal.contact[i] || bound == 0.0 {
                continue;
            }
            let qx = state.traction[0][i] + ratio * (state.traction[0][i] - before[0][i]);
            let qy = state.traction[1][i] + ratio * (state.traction[1][i] - before[1][i]);
            let magnitude = qx.hypot(qy);
            if magnitude >= bound {
                if state.status[i] != SlipStatus::Slip {
                    self.break_loose(i);
                    // Under slip weakening, by the slip its excess over the disc predicts.
                    self.weaken(i, (magnitude - bound) / rho);
                }
                let bound = self.bound[i];
                state.status[i] = SlipStatus::Slip;
                self.unit[i] = (qx / magnitude, qy / magnitude);
                state.traction[0][i] = bound * self.unit[i].0;
                state.traction[1][i] = bound * self.unit[i].1;
            } else {
                state.status[i] = SlipStatus::Stick;
                state.traction[0][i] = qx;
                state.traction[1][i] = qy;
            }
        }
    }
}
