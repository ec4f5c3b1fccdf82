use super::{ContactState, Control, SolveError, SolveReport};
use crate::elastic::ElasticOperator;
use crate::grid::Boundary;

/// Parameters of [`Ccg`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CcgParams {
    /// Stop when Σ|p_new − p_old| / Σ|p| falls below this (default 1e-10).
    pub tolerance: f64,
    /// Give up (with [`SolveError::NotConverged`]) after this many iterations (default 20 000).
    pub max_iterations: usize,
}

impl Default for CcgParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 20_000,
        }
    }
}

/// Non-adhesive frictionless normal contact by constrained conjugate gradients.
///
/// Polonsky & Keer (1999), "A numerical method for solving rough contact problems based
/// on the multi-level multi-summation and conjugate gradient techniques", *Wear* 231,
/// 206–219, doi:10.1016/S0043-1648(99)00113-1. Displacement control is the same
/// iteration without the load constraint (no mean subtraction, no rescaling). Buffers are
/// allocated once per grid size; the iteration does not allocate.
#[derive(Debug, Clone, Default)]
pub struct Ccg {
    params: CcgParams,
    gap: Vec<f64>,
    direction: Vec<f64>,
    response: Vec<f64>,
    previous: Vec<f64>,
}

impl Ccg {
    /// A solver with the given parameters.
    pub fn new(params: CcgParams) -> Self {
        Self {
            params,
            ..Self::default()
        }
    }

    /// The parameters.
    pub fn params(&self) -> &CcgParams {
        &self.params
    }

    /// Solves for p ≥ 0 with g ≥ 0 and p·g = 0, starting from `state` (warm start) and
    /// leaving the solution there. `heights` are the indenter heights z at element centres.
    ///
    /// On a periodic half-space the uniform pressure produces no displacement (K̂(0) = 0),
    /// so displacement control there means mean-gap control; it is solved as load control
    /// with a bracketed secant iteration on the load (d(F) is increasing).
    pub fn solve<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        control: Control,
        state: &mut ContactState,
    ) -> Result<SolveReport, SolveError> {
        match control {
            Control::Displacement(depth) if operator.grid().boundary() == Boundary::Periodic => {
                self.solve_periodic_depth(operator, heights, depth, state)
            }
            _ => self.solve_constrained(operator, heights, control, state),
        }
    }

    fn solve_periodic_depth<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<SolveReport, SolveError> {
        let grid = *operator.grid();
        let lowest = heights.iter().cloned().fold(f64::INFINITY, f64::min);
        let highest = heights
            .iter()
            .cloned()
            .filter(|z| z.is_finite())
            .fold(f64::NEG_INFINITY, f64::max);
        let scale = (highest - lowest).max(depth.abs()).max(f64::MIN_POSITIVE);
        if depth <= lowest {
            state.pressure.iter_mut().for_each(|p| *p = 0.0);
            state.displacement.iter_mut().for_each(|u| *u = 0.0);
            state.contact.iter_mut().for_each(|c| *c = false);
            return Ok(SolveReport {
                depth,
                ..SolveReport::default()
            });
        }
        // Depth found by a load-controlled solve is increasing in the load: bracket, then
        // Illinois regula falsi.
        let current = state.force(grid.element_area());
        let modulus = operator.contact_modulus();
        let mut total = SolveReport::default();
        let mut low = (0.0, lowest - depth);
        // First guess: the stiffness of full contact is of order E*·L.
        let mut load = if current > 0.0 {
            current
        } else {
            grid.size() * modulus * (depth - lowest)
        };
        let mut report = {
            let report = self.solve_constrained(operator, heights, Control::Load(load), state)?;
            total.iterations += report.iterations;
            total.operator_applications += report.operator_applications;
            report
        };
        let mut high;
        loop {
            let value = report.depth - depth;
            if value.abs() <= 1e-10 * scale {
                return Ok(SolveReport {
                    iterations: total.iterations,
                    operator_applications: total.operator_applications,
                    depth,
                    ..report
                });
            }
            if value > 0.0 {
                high = (load, value);
                break;
            }
            low = (load, value);
            load *= 2.0;
            report = {
                let report = self.solve_constrained(operator, heights, Control::Load(load), state)?;
                total.iterations += report.iterations;
                total.operator_applications += report.operator_applications;
                report
            };
        }
        let mut side = 0i8;
        for _ in 0..200 {
            load = (low.0 * high.1 - high.0 * low.1) / (high.1 - low.1);
            report = {
                let report = self.solve_constrained(operator, heights, Control::Load(load), state)?;
                total.iterations += report.iterations;
                total.operator_applications += report.operator_applications;
                report
            };
            let value = report.depth - depth;
            if value.abs() <= 1e-10 * scale || (high.0 - low.0) <= 1e-14 * high.0 {
                return Ok(SolveReport {
                    iterations: total.iterations,
                    operator_applications: total.operator_applications,
                    depth,
                    ..report
                });
            }
            if value > 0.0 {
                high = (load, value);
                if side == 1 {
                    low.1 *= 0.5;
                }
                side = 1;
            } else {
                low = (load, value);
                if side == -1 {
                    high.1 *= 0.5;
                }
                side = -1;
            }
        }
        Err(SolveError::NotConverged {
            iterations: total.iterations,
            residual: (report.depth - depth).abs() / scale,
            tolerance: 1e-10,
        })
    }

    fn solve_constrained<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        control: Control,
        state: &mut ContactState,
    ) -> Result<SolveReport, SolveError> {
        let grid = *operator.grid();
        let len = grid.len();
        if heights.len() != len {
            return Err(SolveError::SizeMismatch {
                expected: len,
                got: heights.len(),
            });
        }
        let element_area = grid.element_area();
        let (depth, load) = match control {
            Control::Displacement(depth) => (depth, None),
            Control::Load(load) => {
                if !(load.is_finite() && load > 0.0) {
                    return Err(SolveError::InvalidLoad(load));
                }
                (0.0, Some(load / element_area))
            }
        };
        for buffer in [
            &mut self.gap,
            &mut self.direction,
            &mut self.response,
            &mut self.previous,
        ] {
            buffer.clear();
            buffer.resize(len, 0.0);
        }
        let applications_before = operator.applications();
        let self_compliance = operator.self_compliance();
        let pressure = &mut state.pressure;

        // Cold start: a pressure that closes each penetrating element on its own.
        if pressure.iter().all(|&p| p <= 0.0) {
            let lowest = heights.iter().cloned().fold(f64::INFINITY, f64::min);
            for (p, &z) in pressure.iter_mut().zip(heights) {
                let reference = if load.is_some() { lowest } else { depth };
                *p = if z < reference + f64::EPSILON * reference.abs() || z <= reference {
                    (reference - z).max(0.0) / self_compliance
                } else {
                    0.0
                };
            }
            if let Some(total) = load {
                // Load control from nothing: Polonsky & Keer's uniform pressure on every
                // element the indenter can touch; the iteration shrinks the set.
                let reachable = heights.iter().filter(|z| z.is_finite()).count().max(1);
                for (p, &z) in pressure.iter_mut().zip(heights) {
                    *p = if z.is_finite() { total / reachable as f64 } else { 0.0 };
                }
            }
        } else {
            for p in pressure.iter_mut() {
                *p = p.max(0.0);
            }
        }
        if let Some(total) = load {
            let sum: f64 = pressure.iter().sum();
            if sum > 0.0 {
                let scale = total / sum;
                pressure.iter_mut().for_each(|p| *p *= scale);
            }
        }

        let mut delta = 0.0;
        let mut previous_norm = 1.0;
        let mut residual = f64::INFINITY;
        let mut found_depth = depth;
        for iteration in 1..=self.params.max_iterations {
            operator.apply(pressure, &mut state.displacement);
            // g = u + z − d (d = 0 under load control; the mean over I plays its role).
            let mut mean_gap = 0.0;
            let mut active = 0usize;
            for k in 0..len {
                self.gap[k] = state.displacement[k] + heights[k] - depth;
                if pressure[k] > 0.0 {
                    mean_gap += self.gap[k];
                    active += 1;
                }
            }
            if active == 0 {
                // Nothing carries load: done if nothing penetrates, else close the penetration.
                let mut penetrating = false;
                for k in 0..len {
                    if self.gap[k] < 0.0 {
                        pressure[k] = -self.gap[k] / self_compliance;
                        penetrating = true;
                    }
                }
                if !penetrating {
                    residual = 0.0;
                    break;
                }
                delta = 0.0;
                continue;
            }
            if load.is_some() {
                mean_gap /= active as f64;
                found_depth = mean_gap;
                self.gap.iter_mut().for_each(|g| *g -= mean_gap);
            }
            let mut norm = 0.0;
            for k in 0..len {
                if pressure[k] > 0.0 {
                    norm += self.gap[k] * self.gap[k];
                }
            }
            if !norm.is_finite() {
                return Err(SolveError::NonFinite { iteration });
            }
            let ratio = delta * norm / previous_norm;
            for k in 0..len {
                self.direction[k] = if pressure[k] > 0.0 {
                    self.gap[k] + ratio * self.direction[k]
                } else {
                    0.0
                };
            }
            previous_norm = norm;
            operator.apply(&self.direction, &mut self.response);
            let mut mean_response = 0.0;
            if load.is_some() {
                for k in 0..len {
                    if pressure[k] > 0.0 {
                        mean_response += self.response[k];
                    }
                }
                mean_response /= active as f64;
            }
            let (mut numerator, mut denominator) = (0.0, 0.0);
            for k in 0..len {
                if pressure[k] > 0.0 {
                    numerator += self.gap[k] * self.direction[k];
                    denominator += (self.response[k] - mean_response) * self.direction[k];
                }
            }
            if !(numerator.is_finite() && denominator.is_finite()) {
                return Err(SolveError::NonFinite { iteration });
            }
            let step = if denominator > 0.0 {
                numerator / denominator
            } else {
                0.0
            };
            // With a single active element (or a vanishing direction) the CG step is zero;
            // penetrating elements are then closed by the element's own compliance.
            let overlap_step = if step > 0.0 { step } else { 1.0 / self_compliance };
            self.previous.copy_from_slice(pressure);
            let mut overlap = false;
            for k in 0..len {
                if self.previous[k] > 0.0 {
                    pressure[k] = (pressure[k] - step * self.direction[k]).max(0.0);
                } else if self.gap[k] < 0.0 {
                    pressure[k] -= overlap_step * self.gap[k];
                    overlap = true;
                }
            }
            delta = if overlap { 0.0 } else { 1.0 };
            if let Some(total) = load {
                let sum: f64 = pressure.iter().sum();
                if sum > 0.0 {
                    let scale = total / sum;
                    pressure.iter_mut().for_each(|p| *p *= scale);
                }
            }
            let (mut change, mut magnitude) = (0.0, 0.0);
            for k in 0..len {
                change += (pressure[k] - self.previous[k]).abs();
                magnitude += pressure[k].abs();
            }
            if !(change.is_finite() && magnitude.is_finite()) {
                return Err(SolveError::NonFinite { iteration });
            }
            if magnitude == 0.0 {
                // Everything was released: not a solution while anything penetrates. The
                // next iteration closes the penetrating elements again from scratch.
                residual = f64::INFINITY;
                delta = 0.0;
                continue;
            }
            residual = change / magnitude;
            if residual < self.params.tolerance && !overlap {
                operator.apply(pressure, &mut state.displacement);
                return Ok(self.finish(
                    operator,
                    heights,
                    state,
                    found_depth,
                    load,
                    iteration,
                    residual,
                    applications_before,
                ));
            }
        }
        if residual == 0.0 {
            operator.apply(&state.pressure, &mut state.displacement);
            return Ok(self.finish(operator, heights, state, found_depth, load, 0, 0.0, applications_before));
        }
        Err(SolveError::NotConverged {
            iterations: self.params.max_iterations,
            residual,
            tolerance: self.params.tolerance,
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn finish<O: ElasticOperator + ?Sized>(
        &self,
        operator: &O,
        heights: &[f64],
        state: &mut ContactState,
        depth: f64,
        load: Option<f64>,
        iterations: usize,
        residual: f64,
        applications_before: u64,
    ) -> SolveReport {
        let grid = *operator.grid();
        let depth = if load.is_some() {
            // d = mean over the contact of u + z (the rigid-body offset).
            let (mut sum, mut count) = (0.0, 0usize);
            for k in 0..grid.len() {
                if state.pressure[k] > 0.0 {
                    sum += state.displacement[k] + heights[k];
                    count += 1;
                }
            }
            if count > 0 {
                sum / count as f64
            } else {
                depth
            }
        } else {
            depth
        };
        for (c, &p) in state.contact.iter_mut().zip(&state.pressure) {
            *c = p > 0.0;
        }
        let contact_elements = state.contact_elements();
        SolveReport {
            iterations,
            residual,
            contact_elements,
            contact_area: contact_elements as f64 * grid.element_area(),
            force: state.force(grid.element_area()),
            depth,
            operator_applications: operator.applications() - applications_before,
        }
    }
}
