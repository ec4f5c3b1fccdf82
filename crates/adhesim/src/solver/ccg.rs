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
    /// Periodic displacement control (a secant iteration on the load): stop when the
    /// reached mean depth is within this times max(height range, |d|) of d (default 1e-10) ...
    pub depth_tolerance: f64,
    /// ... or when the load bracket has shrunk to this times the load (default 1e-14, a
    /// few ulps: the depth cannot get closer) ...
    pub load_bracket_tolerance: f64,
    /// ... giving up after this many secant iterations (default 200).
    pub max_depth_iterations: usize,
}

impl Default for CcgParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 20_000,
            depth_tolerance: 1e-10,
            load_bracket_tolerance: 1e-14,
            max_depth_iterations: 200,
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
        super::on_worker(|| match control {
            Control::Displacement(depth) if operator.grid().boundary() == Boundary::Periodic => {
                self.solve_periodic_depth(operator, heights, depth, state)
            }
            _ => self.solve_constrained(operator, heights, control, state),
        })
    }

    /// Periodic displacement control: the load-controlled solve whose mean depth is d,
    /// found by bracketing and Illinois regula falsi (the depth is increasing in the load).
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
        let tolerance = self.params.depth_tolerance * scale;
        // Every element reachable (no infinite height): full contact closes the cell at
        // d = mean(z) (the zero-mean displacement), under a finite load, and no load goes
        // deeper. Without this check the load bracket below doubles to infinity.
        if heights.iter().all(|z| z.is_finite()) {
            let full_contact_depth = heights.iter().sum::<f64>() / heights.len() as f64;
            if depth > full_contact_depth + tolerance {
                return Err(SolveError::BeyondFullContact {
                    depth,
                    full_contact_depth,
                });
            }
        }
        if depth <= lowest {
            state.pressure.iter_mut().for_each(|p| *p = 0.0);
            state.displacement.iter_mut().for_each(|u| *u = 0.0);
            state.contact.iter_mut().for_each(|c| *c = false);
            return Ok(SolveReport {
                depth,
                ..SolveReport::default()
            });
        }
        let current = state.force(grid.element_area());
        // First guess: the stiffness of full contact is of order E*·L (the longer side).
        let mut load = if current > 0.0 {
            current
        } else {
            grid.size_x().max(grid.size_y()) * operator.contact_modulus() * (depth - lowest)
        };
        let mut total = SolveReport::default();
        let mut solve_at = |ccg: &mut Self, load: f64, state: &mut ContactState| {
            let report = ccg.solve_constrained(operator, heights, Control::Load(load), state)?;
            total.iterations += report.iterations;
            total.operator_applications += report.operator_applications;
            Ok::<_, SolveError>((report, report.depth - depth))
        };
        let done = |report: SolveReport, total: &SolveReport| SolveReport {
            iterations: total.iterations,
            operator_applications: total.operator_applications,
            depth,
            ..report
        };
        let mut low = (0.0, lowest - depth);
        let (mut report, mut value) = solve_at(self, load, state)?;
        let mut high;
        loop {
            if value.abs() <= tolerance {
                return Ok(done(report, &total));
            }
            if value > 0.0 {
                high = (load, value);
                break;
            }
            low = (load, value);
            load *= 2.0;
            if !load.is_finite() {
                // Unreachable after the full-contact check (the depth is reached at a
                // finite load); kept so that no input can make the bracket run away.
                return Err(SolveError::NonFinite {
                    iteration: total.iterations,
                });
            }
            (report, value) = solve_at(self, load, state)?;
        }
        let mut side = 0i8;
        for _ in 0..self.params.max_depth_iterations {
            load = (low.0 * high.1 - high.0 * low.1) / (high.1 - low.1);
            (report, value) = solve_at(self, load, state)?;
            if value.abs() <= tolerance || (high.0 - low.0) <= self.params.load_bracket_tolerance * high.0 {
                return Ok(done(report, &total));
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
        // The gap residual on C is the depth mismatch on every element of C.
        let (count, target) = (0..grid.len())
            .filter(|&k| state.contact[k])
            .fold((0usize, 0.0), |(c, t), k| (c + 1, t + (depth - heights[k]).powi(2)));
        let absolute_residual = value.abs() * (count as f64).sqrt();
        Err(SolveError::NotConverged {
            iterations: total.iterations,
            absolute_residual,
            relative_residual: absolute_residual / target.sqrt().max(f64::MIN_POSITIVE),
            tolerance: self.params.depth_tolerance,
        })
    }

    /// The Polonsky–Keer iteration under `control`, from `state`.
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
        let (depth, load) = match control {
            Control::Displacement(depth) => (depth, None),
            Control::Load(load) => {
                if !(load.is_finite() && load > 0.0) {
                    return Err(SolveError::InvalidLoad(load));
                }
                (0.0, Some(load / grid.element_area()))
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
        start_pressure(&mut state.pressure, heights, depth, load, operator.self_compliance());
        let mut progress = Progress {
            delta: 0.0,
            previous_norm: 1.0,
            residual: f64::INFINITY,
            gap_norm: f64::INFINITY,
            target_norm: 0.0,
            found_depth: depth,
        };
        for iteration in 1..=self.params.max_iterations {
            match self.iterate(operator, heights, depth, load, state, &mut progress, iteration)? {
                Outcome::Continue => {}
                Outcome::Converged => {
                    operator.apply(&state.pressure, &mut state.displacement);
                    return Ok(self.finish(
                        operator,
                        heights,
                        state,
                        progress.found_depth,
                        load,
                        iteration,
                        progress.residual,
                        applications_before,
                    ));
                }
                Outcome::NothingLoaded => {
                    operator.apply(&state.pressure, &mut state.displacement);
                    return Ok(self.finish(operator, heights, state, depth, load, 0, 0.0, applications_before));
                }
            }
        }
        Err(SolveError::NotConverged {
            iterations: self.params.max_iterations,
            absolute_residual: progress.gap_norm,
            relative_residual: progress.gap_norm / progress.target_norm.max(f64::MIN_POSITIVE),
            tolerance: self.params.tolerance,
        })
    }

    /// One Polonsky–Keer iteration: gaps, conjugate direction and step on the active set,
    /// projection onto p ≥ 0 with closure of penetrating elements, load rescaling.
    #[allow(clippy::too_many_arguments)]
    fn iterate<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        load: Option<f64>,
        state: &mut ContactState,
        progress: &mut Progress,
        iteration: usize,
    ) -> Result<Outcome, SolveError> {
        let len = heights.len();
        let self_compliance = operator.self_compliance();
        operator.apply(&state.pressure, &mut state.displacement);
        let pressure = &mut state.pressure;
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
                return Ok(Outcome::NothingLoaded);
            }
            progress.delta = 0.0;
            return Ok(Outcome::Continue);
        }
        if load.is_some() {
            // Polonsky & Keer's (1999) shift ḡ must come out exact when the gaps on I are all
            // equal (one row of a strip contact, docs/validation.md §13). A rounded ḡ left
            // g − ḡ a uniform vector of rounding size, along which the curvature Σ(r − r̄)t
            // vanishes too: the step Σg·t / Σ(r − r̄)t was rounding over rounding (4e16 there),
            // it wiped the pressure, and the cold restart retraced the same path without end.
            mean_gap = refined_mean(&self.gap, pressure, mean_gap / active as f64, active);
            progress.found_depth = mean_gap;
            self.gap.iter_mut().for_each(|g| *g -= mean_gap);
        }
        let (mut norm, mut target) = (0.0, 0.0);
        for k in 0..len {
            if pressure[k] > 0.0 {
                norm += self.gap[k] * self.gap[k];
                target += (progress.found_depth - heights[k]).powi(2);
            }
        }
        if !norm.is_finite() {
            return Err(SolveError::NonFinite { iteration });
        }
        (progress.gap_norm, progress.target_norm) = (norm.sqrt(), target.sqrt());
        let step = self.conjugate_step(operator, pressure, load, active, norm, progress, iteration)?;
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
        progress.delta = if overlap { 0.0 } else { 1.0 };
        if let Some(total) = load {
            rescale_to(pressure, total);
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
            progress.residual = f64::INFINITY;
            progress.delta = 0.0;
            return Ok(Outcome::Continue);
        }
        progress.residual = change / magnitude;
        Ok(if progress.residual < self.params.tolerance && !overlap {
            Outcome::Converged
        } else {
            Outcome::Continue
        })
    }

    /// The conjugate direction on the active set (p > 0) and its step length (0 when the
    /// curvature vanishes).
    #[allow(clippy::too_many_arguments)]
    fn conjugate_step<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        pressure: &[f64],
        load: Option<f64>,
        active: usize,
        norm: f64,
        progress: &mut Progress,
        iteration: usize,
    ) -> Result<f64, SolveError> {
        let len = pressure.len();
        // Restart (steepest descent) after an overlap, and after an iteration whose gap
        // vanished on the active set: under load control one active element has a zero
        // mean-free gap, and norm/0 would fill the direction with NaN.
        let ratio = if progress.previous_norm > 0.0 {
            progress.delta * norm / progress.previous_norm
        } else {
            0.0
        };
        for k in 0..len {
            self.direction[k] = if pressure[k] > 0.0 {
                self.gap[k] + ratio * self.direction[k]
            } else {
                0.0
            };
        }
        progress.previous_norm = norm;
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
        Ok(if denominator > 0.0 {
            numerator / denominator
        } else {
            0.0
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
            // Polonsky–Keer's CCG runs unpreconditioned.
            preconditioner_applications: 0,
        }
    }
}

/// Convergence state of the Polonsky–Keer iteration.
struct Progress {
    /// 0 after an overlap correction (restart the conjugation), else 1.
    delta: f64,
    previous_norm: f64,
    /// Relative pressure change of the last iteration (the stopping measure).
    residual: f64,
    /// ‖g‖₂ and ‖d − z‖₂ over the active set (stated in [`SolveError::NotConverged`]).
    gap_norm: f64,
    target_norm: f64,
    /// Depth found under load control (the mean of u + z over the active set).
    found_depth: f64,
}

/// What an iteration concluded.
enum Outcome {
    Continue,
    Converged,
    /// No element carries load and none penetrates: p = 0 is the solution.
    NothingLoaded,
}

/// Starting pressure: a cold start closes each penetrating element on its own (under load
/// control, Polonsky & Keer's uniform pressure on every reachable element); a warm start is
/// clipped to p ≥ 0; under load control the total is rescaled to the load.
fn start_pressure(pressure: &mut [f64], heights: &[f64], depth: f64, load: Option<f64>, self_compliance: f64) {
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
        rescale_to(pressure, total);
    }
}

/// Scales p so that Σp = `total` (if Σp > 0).
fn rescale_to(pressure: &mut [f64], total: f64) {
    let sum: f64 = pressure.iter().sum();
    if sum > 0.0 {
        let scale = total / sum;
        pressure.iter_mut().for_each(|p| *p *= scale);
    }
}

/// The mean over the active set (p > 0) of `values`, refined from `mean` by one correction
/// pass: when the values are all equal the result is exactly that value (x − m is exact near
/// x, Sterbenz, and so are the sum of the equal small differences and its quotient), so
/// that a mean-free vector on such a set is exactly zero rather than its rounding error.
fn refined_mean(values: &[f64], pressure: &[f64], mean: f64, active: usize) -> f64 {
    let correction: f64 = values
        .iter()
        .zip(pressure)
        .filter(|(_, &p)| p > 0.0)
        .map(|(&v, _)| v - mean)
        .sum();
    mean + correction / active as f64
}
