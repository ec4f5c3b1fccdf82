mod checkpoint;

pub use checkpoint::NestedCheckpoint;

use super::contact_window::WindowLevel;
use super::workspace::{precondition_rows, Workspace};
use super::{dot, masked_pcg, ContactState, SolveError, SolveReport};
use crate::elastic::{ElasticOperator, FreeOperator};
use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;

/// Parameters of [`NestedActiveSet`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NestedParams {
    /// Converged when the exact residual satisfies ‖d − z − u‖_C ≤ this·‖d − z‖_C on a
    /// contact set that no longer changes (default 1e-10).
    pub relative_tolerance: f64,
    /// CG iteration limit per active-set round (default 2 000).
    pub max_cg_iterations: usize,
    /// Active-set round limit per grid level (default 200).
    pub max_rounds: usize,
    /// Coarse-to-fine continuation halves the grid while it stays even and at least this
    /// size (default 32; a value above N disables it).
    pub coarsest: usize,
    /// Keep a warm start when the depth decreases from the previous solve (default
    /// false: an unload starts cold, with the nested continuation, which measured 1.2–2×
    /// cheaper than the warm start for every unload fraction at N = 512; the warm start
    /// stays for loading. See BENCHMARKS.md §What did not pay, warm starts on unloads).
    pub warm_unload: bool,
    /// Pre-solve each level on the contact's bounding box as a grid of its own (default
    /// true; see the `contact_window` module): the same solution, from transforms of twice
    /// the window's side. False solves every level on its whole grid.
    pub contact_window: bool,
}

impl Default for NestedParams {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-10,
            max_cg_iterations: 2_000,
            max_rounds: 200,
            coarsest: 32,
            warm_unload: false,
            contact_window: true,
        }
    }
}

/// Relative residual to which the coarse levels are solved: they only supply the fine
/// level's first contact set and pressures, which the fine rounds correct anyway.
const COARSE_TOLERANCE: f64 = 1e-6;

/// A coarse level of the continuation: its own operator, heights and state.
struct CoarseLevel {
    grid: Grid,
    heights: Vec<f64>,
    state: ContactState,
    window: Option<WindowLevel>,
    /// Operator and buffers of the whole level, made when the window does not suffice.
    full: Option<(FreeOperator, Workspace)>,
}

/// Non-adhesive frictionless normal contact under displacement control by a primal
/// active-set method with |q|-preconditioned conjugate gradients on the fixed contact
/// set, and nested-grid (coarse-to-fine) continuation.
///
/// Each round solves K_CC p_C = (d − z)_C on the current set C, then drops elements with
/// p < 0 and adds those with gap g = z − d + u < 0, until C is stable and the residual
/// meets the tolerance. The set changes at the front only, so a good first set makes the
/// rounds few: the solution of the same problem on a grid of half the resolution
/// (heights averaged over 2×2 blocks, recursively down to [`NestedParams::coarsest`]),
/// injected into the fine grid, gives it. The CG search directions are applied in single
/// precision and every round starts from an exact double-precision residual (iterative
/// refinement), so the final accuracy is that of double precision. Free grids only (a
/// periodic one is refused with [`SolveError::PeriodicUnsupported`]).
///
/// The ingredients are those of the fast half-space solvers: the |q| spectral
/// preconditioner (e.g. Vollebregt 2014, *J. Optim. Theory Appl.* 162, 977–1002, where it
/// is used within a bound-constrained CG), nested grids (Brandt & Lubrecht 1990, *J.
/// Comput. Phys.* 90, 348–370) and mixed precision.
pub struct NestedActiveSet {
    params: NestedParams,
    grid: Grid,
    fine: Workspace,
    coarse: Vec<CoarseLevel>,
    coarse_applications: u64,
    /// The fine level's contact window (see [`super::contact_window`]).
    fine_window: Option<WindowLevel>,
    window_applications: u64,
    /// Applications of the CG's preconditioner (all levels and windows) during the last
    /// solve.
    preconditioner_applications: u64,
    material: ElasticMaterial,
    /// Depth of the last successful solve (decides whether a warm start is an unload).
    last_depth: Option<f64>,
}

impl NestedActiveSet {
    /// Plans the levels for `grid` (FFTs and kernel spectra of every coarse level are
    /// computed here, once).
    pub fn new(grid: Grid, material: ElasticMaterial, params: NestedParams) -> Self {
        let modulus = material.contact_modulus();
        let mut coarse = Vec::new();
        let (mut nx, mut ny) = (grid.nx(), grid.ny());
        if grid.boundary() == Boundary::Free {
            let coarsest = params.coarsest.max(2);
            while nx.is_multiple_of(2) && ny.is_multiple_of(2) && nx / 2 >= coarsest && ny / 2 >= coarsest {
                (nx, ny) = (nx / 2, ny / 2);
                let level_grid = Grid::rectangular(nx, ny, grid.size_x(), grid.size_y(), Boundary::Free)
                    .expect("a halved grid is valid");
                coarse.push(CoarseLevel {
                    grid: level_grid,
                    heights: vec![0.0; level_grid.len()],
                    state: ContactState::new(&level_grid),
                    window: None,
                    full: None,
                });
            }
        }
        Self {
            params,
            grid,
            fine: Workspace::with_target(&grid, modulus),
            coarse,
            coarse_applications: 0,
            fine_window: None,
            window_applications: 0,
            preconditioner_applications: 0,
            material,
            last_depth: None,
        }
    }

    /// The parameters.
    pub fn params(&self) -> &NestedParams {
        &self.params
    }

    /// Grid levels below the fine one used by the continuation.
    pub fn coarse_levels(&self) -> usize {
        self.coarse.len()
    }

    /// Operator applications on the coarse levels during the last solve (each costs a
    /// quarter of the next finer level's).
    pub fn coarse_applications(&self) -> u64 {
        self.coarse_applications
    }

    /// Operator applications on contact windows (all levels) during the last solve: each
    /// is a DC-FFT convolution of twice the window's side instead of twice the level's.
    pub fn window_applications(&self) -> u64 {
        self.window_applications
    }

    /// Whether the contact in `state` is kept as the warm start at `depth`; when not (an
    /// unload, see [`NestedParams::warm_unload`]) the state is cleared for a cold start.
    fn keep_warm_start(&self, depth: f64, state: &mut ContactState) -> bool {
        if !state.contact.iter().any(|&c| c) {
            return false;
        }
        let unload = self.last_depth.is_some_and(|previous| depth < previous);
        if unload && !self.params.warm_unload {
            state.contact.fill(false);
            state.pressure.fill(0.0);
            return false;
        }
        true
    }

    /// The nested continuation: heights restricted down the levels (2×2 means), each level
    /// solved from the coarsest up, seeded by the level below. A level whose contact
    /// settled in its window skips the level's full-grid rounds: it only seeds the next
    /// level, whose own rounds decide. The full operator of a level is built only when a
    /// level needs it.
    fn solve_coarse_levels(&mut self, heights: &[f64], depth: f64) -> Result<(), SolveError> {
        let mut finer: &[f64] = heights;
        let mut finer_n = (self.grid.nx(), self.grid.ny());
        for level in self.coarse.iter_mut() {
            restrict(finer, finer_n, &mut level.heights);
            finer = &level.heights;
            finer_n = (finer_n.0 / 2, finer_n.1 / 2);
        }
        let levels = self.coarse.len();
        let tolerance = self.params.relative_tolerance.max(COARSE_TOLERANCE);
        for index in (0..levels).rev() {
            let (head, tail) = self.coarse.split_at_mut(index + 1);
            let level = &mut head[index];
            if index + 1 == levels {
                cold_start(&level.heights, depth, &mut level.state);
            } else {
                prolong(
                    &tail[0].state,
                    &level.heights,
                    (level.grid.nx(), level.grid.ny()),
                    &mut level.state,
                );
            }
            let window = solve_in_window(
                &mut level.window,
                &level.grid,
                self.material,
                (&level.heights, depth),
                &mut level.state,
                &self.params,
                tolerance,
            )?;
            self.window_applications += window.applications;
            self.preconditioner_applications += window.preconditioner_applications;
            // A level without contact has nothing to solve (nothing penetrates: the
            // coarsest level's cold start holds every penetrated element).
            if window.settled || !level.state.contact.iter().any(|&c| c) {
                continue;
            }
            let (operator, workspace) = level.full.get_or_insert_with(|| {
                (
                    FreeOperator::new(level.grid, self.material),
                    Workspace::with_target(&level.grid, self.material.contact_modulus()),
                )
            });
            let before = (operator.applications(), workspace.preconditioner_applications);
            solve_level(
                operator,
                &level.heights,
                depth,
                &mut level.state,
                workspace,
                &self.params,
                tolerance,
            )?;
            self.coarse_applications += operator.applications() - before.0;
            self.preconditioner_applications += workspace.preconditioner_applications - before.1;
        }
        Ok(())
    }

    /// Solves at indentation `depth`. A `state` that already has contact is the warm start
    /// (no continuation) unless the depth decreased since the previous solve (see
    /// [`NestedParams::warm_unload`]); otherwise the coarse levels supply the
    /// first contact set.
    ///
    /// # Panics
    /// If `operator` acts on another grid than the one the solver was planned for.
    pub fn solve<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<SolveReport, SolveError> {
        super::on_worker(|| self.solve_on_worker(operator, heights, depth, state))
    }

    fn solve_on_worker<O: ElasticOperator + ?Sized>(
        &mut self,
        operator: &mut O,
        heights: &[f64],
        depth: f64,
        state: &mut ContactState,
    ) -> Result<SolveReport, SolveError> {
        assert_eq!(operator.grid(), &self.grid, "operator and solver grids differ");
        let len = self.grid.len();
        if heights.len() != len {
            return Err(SolveError::SizeMismatch {
                expected: len,
                got: heights.len(),
            });
        }
        if operator.grid().boundary() != Boundary::Free {
            // K̂(0) = 0 on a periodic grid: depth control is mean-gap control there.
            return Err(SolveError::PeriodicUnsupported {
                solver: "NestedActiveSet",
            });
        }
        if !depth.is_finite() {
            return Err(SolveError::NonFinite { iteration: 0 });
        }
        self.coarse_applications = 0;
        self.window_applications = 0;
        self.preconditioner_applications = 0;
        let warm = self.keep_warm_start(depth, state);
        self.last_depth = None;
        if !warm && !self.coarse.is_empty() {
            self.solve_coarse_levels(heights, depth)?;
            prolong(&self.coarse[0].state, heights, (self.grid.nx(), self.grid.ny()), state);
        } else if !warm {
            cold_start(heights, depth, state);
        }
        let window = solve_in_window(
            &mut self.fine_window,
            &self.grid,
            self.material,
            (heights, depth),
            state,
            &self.params,
            self.params.relative_tolerance,
        )?;
        self.window_applications += window.applications;
        self.preconditioner_applications += window.preconditioner_applications;
        let before = operator.applications();
        let preconditioned_before = self.fine.preconditioner_applications;
        let (iterations, residual) = solve_level(
            operator,
            heights,
            depth,
            state,
            &mut self.fine,
            &self.params,
            self.params.relative_tolerance,
        )?;
        self.preconditioner_applications += self.fine.preconditioner_applications - preconditioned_before;
        self.last_depth = Some(depth);
        let area = self.grid.element_area();
        let contact_elements = state.contact.iter().filter(|&&c| c).count();
        Ok(SolveReport {
            iterations: iterations + window.iterations,
            residual,
            contact_elements,
            contact_area: area * contact_elements as f64,
            force: state.force(area),
            depth,
            operator_applications: operator.applications() - before + window.applications,
            preconditioner_applications: self.preconditioner_applications,
        })
    }
}

/// Moves of the window per solve before the full grid takes over.
const MAX_WINDOW_MOVES: usize = 4;

/// What a window pre-solve did.
struct WindowWork {
    applications: u64,
    /// The CG preconditioner's applications on the window.
    preconditioner_applications: u64,
    iterations: usize,
    /// The contact settled inside the window (it did not reach an open edge).
    settled: bool,
}

/// Pre-solves the contact in `state` on its window (see [`super::contact_window`]),
/// moving the window while the contact reaches its open edges, and leaves the window's
/// pressures and set in `state` for the full grid's rounds, which decide convergence.
/// Does nothing when there is no contact or the window would be nearly the grid.
fn solve_in_window(
    cache: &mut Option<WindowLevel>,
    grid: &Grid,
    material: ElasticMaterial,
    (heights, depth): (&[f64], f64),
    state: &mut ContactState,
    params: &NestedParams,
    relative_tolerance: f64,
) -> Result<WindowWork, SolveError> {
    let mut work = WindowWork {
        applications: 0,
        preconditioner_applications: 0,
        iterations: 0,
        settled: false,
    };
    let moves = if params.contact_window { MAX_WINDOW_MOVES } else { 0 };
    for _ in 0..moves {
        let Some(level) = WindowLevel::enter(cache, grid, material, heights, state) else {
            break;
        };
        let before = (
            level.operator.applications(),
            level.workspace.preconditioner_applications,
        );
        let result = solve_level(
            &mut level.operator,
            &level.heights,
            depth,
            &mut level.state,
            &mut level.workspace,
            params,
            relative_tolerance,
        );
        work.applications += level.operator.applications() - before.0;
        work.preconditioner_applications += level.workspace.preconditioner_applications - before.1;
        work.iterations += result?.0;
        work.settled = !level.leave((grid.nx(), grid.ny()), state);
        if work.settled {
            break;
        }
    }
    Ok(work)
}

/// Residual reduction of a round whose set changed in the round before (or that starts a
/// level): N = 512 Hertz, 28 → 20 CG iterations on the fine level, the same set (1e-3:
/// 23, 1e-1: 18 but two more rounds; docs/history.md §2026-11-23: the non-adhesive whole
/// run). Convergence is still decided by a round on an unchanged set at the full tolerance.
const LOOSE_ROUND_REDUCTION: f64 = 1e-2;

/// First set without information: the elements the rigid indenter penetrates, p = 0.
fn cold_start(heights: &[f64], depth: f64, state: &mut ContactState) {
    for k in 0..heights.len() {
        state.contact[k] = heights[k] < depth;
        state.pressure[k] = 0.0;
    }
}

/// Coarse heights as means of 2×2 fine blocks (+∞ where any is +∞).
fn restrict(fine: &[f64], (fine_n, fine_rows): (usize, usize), coarse: &mut [f64]) {
    let n = fine_n / 2;
    for i in 0..fine_rows / 2 {
        for j in 0..n {
            let at = |a: usize, b: usize| fine[(2 * i + a) * fine_n + 2 * j + b];
            coarse[i * n + j] = 0.25 * (at(0, 0) + at(0, 1) + at(1, 0) + at(1, 1));
        }
    }
}

/// Injects a coarse solution into the finer grid: each coarse element's pressure and
/// contact flag go to its four children (where the fine surface exists).
fn prolong(coarse: &ContactState, fine_heights: &[f64], (fine_n, fine_rows): (usize, usize), fine: &mut ContactState) {
    let n = fine_n / 2;
    for i in 0..fine_rows {
        for j in 0..fine_n {
            let parent = (i / 2) * n + j / 2;
            let k = i * fine_n + j;
            let exists = fine_heights[k].is_finite();
            fine.contact[k] = coarse.contact[parent] && exists;
            fine.pressure[k] = if fine.contact[k] { coarse.pressure[parent] } else { 0.0 };
        }
    }
}

/// Active-set rounds on one grid from the set and pressures in `state`. Returns the CG
/// iterations and the final relative residual.
fn solve_level<O: ElasticOperator + ?Sized>(
    operator: &mut O,
    heights: &[f64],
    depth: f64,
    state: &mut ContactState,
    work: &mut Workspace,
    params: &NestedParams,
    relative_tolerance: f64,
) -> Result<(usize, f64), SolveError> {
    let len = heights.len();
    for k in 0..len {
        work.target[k] = if heights[k].is_finite() {
            depth - heights[k]
        } else {
            0.0
        };
    }
    let mut iterations = 0;
    let mut set_changed = true;
    for _ in 0..params.max_rounds {
        for k in 0..len {
            if !state.contact[k] {
                state.pressure[k] = 0.0;
            }
            work.mask[k] = if state.contact[k] { 1.0 } else { 0.0 };
        }
        if state.contact.iter().any(|&c| c) {
            operator.apply(&state.pressure, &mut state.displacement);
        } else {
            // No pressure, no displacement: an unload to zero depth needs no transform.
            state.displacement.fill(0.0);
        }
        let mut target_norm = 0.0;
        for k in 0..len {
            work.residual[k] = (work.target[k] - state.displacement[k]) * work.mask[k];
            target_norm += work.target[k] * work.target[k] * work.mask[k];
        }
        let target_norm = target_norm.sqrt();
        let initial = dot(&work.residual, &work.residual).sqrt();
        let tolerance = relative_tolerance * target_norm;
        if initial > tolerance {
            // Single-precision directions limit one round to ≈ 1e-5 of its starting
            // residual; the next round restarts from the exact one. A round on a set that
            // just changed is likely to change it again: it solves only to
            // LOOSE_ROUND_REDUCTION, enough to decide which elements move.
            let reduction = if set_changed { LOOSE_ROUND_REDUCTION } else { 1e-5 };
            let goal = tolerance.max(reduction * initial);
            iterations += conjugate_gradients(
                operator,
                state,
                work,
                (goal, target_norm, relative_tolerance),
                params.max_cg_iterations,
            )?;
        }
        // Active-set update: tensile elements leave, penetrated ones join.
        let mut changed = false;
        for k in 0..len {
            if state.contact[k] {
                if state.pressure[k] < 0.0 {
                    state.contact[k] = false;
                    state.pressure[k] = 0.0;
                    changed = true;
                }
            } else if heights[k].is_finite() && heights[k] - depth + state.displacement[k] < 0.0 {
                state.contact[k] = true;
                changed = true;
            }
        }
        set_changed = changed;
        if !changed && initial <= tolerance {
            let relative = if target_norm > 0.0 { initial / target_norm } else { 0.0 };
            return Ok((iterations, relative));
        }
    }
    Err(SolveError::TooManyRounds {
        rounds: params.max_rounds,
    })
}

/// Preconditioned CG on the set `work.mask` from the residual in `work.residual`, until
/// ‖r‖ ≤ `goal`; updates p and u in `state`. Returns the iterations. `target_norm` =
/// ‖d − z‖ on the set and the relative tolerance state the residual of a failure
/// ([`SolveError::NotConverged`]).
fn conjugate_gradients<O: ElasticOperator + ?Sized>(
    operator: &mut O,
    state: &mut ContactState,
    work: &mut Workspace,
    (goal, target_norm, relative_tolerance): (f64, f64, f64),
    max_iterations: usize,
) -> Result<usize, SolveError> {
    let row_length = operator.grid().nx();
    let (buffers, mut preconditioner) = work.buffers();
    let mut applications = 0;
    let solved = masked_pcg(
        operator,
        &mut state.pressure,
        &mut state.displacement,
        buffers,
        |residual, preconditioned, rows| {
            let preconditioner = preconditioner.as_deref_mut();
            precondition_rows(
                preconditioner,
                (residual, preconditioned),
                rows,
                row_length,
                &mut applications,
            );
        },
        |residual, _, _, _, _| {
            let norm = residual.norm2.sqrt();
            norm.is_finite().then_some(norm <= goal)
        },
        max_iterations,
    );
    work.preconditioner_applications += applications;
    solved
        .map(|info| info.iterations)
        .map_err(|error| error.into_solve_error(target_norm, relative_tolerance))
}
