//! What a run solves, checked once: the body's normal operator (which carries the grid),
//! the indenter's heights over the grid and the interface's work of adhesion per element.
//! Every protocol takes a [`Problem`]; the solvers are built from its adhesion map
//! ([`Problem::work_of_adhesion`]) and stepped on its operator and heights.

use crate::elastic::ElasticOperator;
use crate::geometry::TranslatingContact;
use crate::grid::Grid;
use crate::solver::{AdhesiveParams, AdhesiveSolver};
use thiserror::Error;

/// Why a [`Problem`] could not be built, or does not fit the protocol given it.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ProblemError {
    /// A per-element field has another length than the grid's element count.
    #[error("the {field} has {got} values, the operator's {rows} × {columns} grid has {expected} elements")]
    Length {
        /// The field, in words ("heights", "work of adhesion").
        field: &'static str,
        /// Values given.
        got: usize,
        /// Elements of the grid.
        expected: usize,
        /// Grid rows.
        rows: usize,
        /// Grid columns.
        columns: usize,
    },
    /// A height is NaN or −∞ (+∞ marks an element the indenter does not cover).
    #[error("height {index} is {value}: a height is finite, or +∞ where the indenter has no surface")]
    Height {
        /// Row-major element index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// No height is finite: the indenter covers no element of the grid.
    #[error("every height is +∞: the indenter covers no element of the grid")]
    NoSurface,
    /// A work of adhesion is negative, NaN or infinite.
    #[error("work of adhesion {index} is {value}: it must be finite and ≥ 0")]
    WorkOfAdhesion {
        /// Row-major element index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A roll, slide or translate was given a problem of fixed heights.
    #[error("a roll, slide or translate moves its indenter: build its problem with Problem::translating")]
    NotTranslating,
}

/// A body, an indenter and an interface, checked once: the protocols drive a solver on it.
///
/// A Hertz indentation on a free 32 × 32 grid, its largest force against Hertz's
/// F = (4/3)E*R^{1/2}d^{3/2}:
/// ```
/// use adhesim::{Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff, Problem, Profile, Sphere};
///
/// let grid = Grid::new(32, 0.5, Boundary::Free)?;
/// let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0)?);
/// let mut problem = Problem::new(Box::new(operator), Sphere::new(1.0)?.heights(&grid))?;
/// let protocol = IndentPulloff {
///     start_depth: 0.0,
///     max_depth: 4e-3,
///     depth_step: 1e-3,
///     max_retract_steps: 100,
///     jump_force_threshold: 0.0,
/// };
/// let mut solver = adhesim::protocol::non_adhesive_solver(grid, ElasticMaterial::new(1.0)?);
/// let mut records = Vec::new();
/// protocol.run(&mut problem, &mut solver, &mut records)?;
/// let largest = records.iter().map(|r| r.force_normal).fold(0.0, f64::max);
/// let hertz = 4.0 / 3.0 * 4e-3_f64.powf(1.5);
/// // 3 %: the contact radius √(Rd) = 0.063 spans 4 elements.
/// assert!((largest / hertz - 1.0).abs() < 0.03, "{}", largest / hertz);
///
/// // A height per element, and none NaN: checked when the problem is built.
/// let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0)?);
/// assert!(Problem::new(Box::new(operator), vec![0.0; 10]).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Problem {
    operator: Box<dyn ElasticOperator>,
    heights: Vec<f64>,
    work_of_adhesion: Vec<f64>,
    translating: Option<TranslatingContact>,
}

impl Problem {
    /// A problem without adhesion (γ = 0 everywhere) of `heights` (row-major, one per
    /// element of the operator's grid; finite, or +∞ where the indenter has no surface).
    pub fn new(operator: Box<dyn ElasticOperator>, heights: Vec<f64>) -> Result<Self, ProblemError> {
        let grid = *operator.grid();
        check_length(&grid, "heights", heights.len())?;
        if let Some((index, &value)) = heights
            .iter()
            .enumerate()
            .find(|(_, z)| z.is_nan() || **z == f64::NEG_INFINITY)
        {
            return Err(ProblemError::Height { index, value });
        }
        if !heights.iter().any(|z| z.is_finite()) {
            return Err(ProblemError::NoSurface);
        }
        Ok(Self {
            operator,
            work_of_adhesion: vec![0.0; heights.len()],
            heights,
            translating: None,
        })
    }

    /// The problem of a roll, slide or translate: `contact` moves over the grid, the
    /// heights are its profile with the axis at the origin, where the approach is made.
    pub fn translating(operator: Box<dyn ElasticOperator>, contact: TranslatingContact) -> Result<Self, ProblemError> {
        let grid = *operator.grid();
        let mut heights = vec![0.0; grid.len()];
        contact.fill_heights(&grid, 0.0, &mut heights);
        let mut problem = Self::new(operator, heights)?;
        problem.translating = Some(contact);
        Ok(problem)
    }

    /// The same problem with the work of adhesion `work_of_adhesion` (row-major, one
    /// finite value ≥ 0 per element).
    pub fn with_work_of_adhesion(mut self, work_of_adhesion: Vec<f64>) -> Result<Self, ProblemError> {
        check_length(self.grid(), "work of adhesion", work_of_adhesion.len())?;
        if let Some((index, &value)) = work_of_adhesion
            .iter()
            .enumerate()
            .find(|(_, w)| !(w.is_finite() && **w >= 0.0))
        {
            return Err(ProblemError::WorkOfAdhesion { index, value });
        }
        self.work_of_adhesion = work_of_adhesion;
        Ok(self)
    }

    /// The grid of the operator.
    pub fn grid(&self) -> &Grid {
        self.operator.grid()
    }

    /// The indenter's heights (for a translating problem, with its axis at the origin).
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// The work of adhesion per element (0 where the interface does not adhere): the
    /// adhesive and cohesive solvers of this problem are built from it.
    pub fn work_of_adhesion(&self) -> &[f64] {
        &self.work_of_adhesion
    }

    /// The body's normal operator (its counters: `applications`).
    pub fn operator(&self) -> &dyn ElasticOperator {
        self.operator.as_ref()
    }

    /// The moving contact of a roll, slide or translate; `None` for fixed heights.
    pub fn translating_contact(&self) -> Option<&TranslatingContact> {
        self.translating.as_ref()
    }

    /// The operator and the heights, as a solver's step takes them.
    pub fn parts_mut(&mut self) -> (&mut dyn ElasticOperator, &[f64]) {
        (self.operator.as_mut(), &self.heights)
    }

    /// The operator and the moving contact of a translating problem.
    pub(crate) fn translating_parts(
        &mut self,
    ) -> Result<(&mut dyn ElasticOperator, &TranslatingContact), ProblemError> {
        match &self.translating {
            Some(contact) => Ok((self.operator.as_mut(), contact)),
            None => Err(ProblemError::NotTranslating),
        }
    }

    /// The JKR-type adhesive solver of this problem: its work of adhesion per element and
    /// the operator's contact modulus.
    pub fn adhesive_solver(&self, params: AdhesiveParams) -> AdhesiveSolver {
        AdhesiveSolver::new(
            *self.grid(),
            self.operator.contact_modulus(),
            self.work_of_adhesion.clone(),
            params,
        )
    }
}

fn check_length(grid: &Grid, field: &'static str, got: usize) -> Result<(), ProblemError> {
    if got == grid.len() {
        return Ok(());
    }
    Err(ProblemError::Length {
        field,
        got,
        expected: grid.len(),
        rows: grid.ny(),
        columns: grid.nx(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Boundary, ElasticMaterial, FreeOperator};

    fn operator() -> Box<dyn ElasticOperator> {
        let grid = Grid::new(8, 1.0, Boundary::Free).unwrap();
        Box::new(FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap()))
    }

    #[test]
    fn a_problem_refuses_each_bad_field_by_name_and_value() {
        let length = Problem::new(operator(), vec![0.0; 63]).err().unwrap();
        assert!(length.to_string().contains("heights has 63 values"), "{length}");
        assert!(length.to_string().contains("64 elements"), "{length}");
        let mut heights = vec![0.0; 64];
        heights[5] = f64::NAN;
        assert_eq!(
            Problem::new(operator(), heights).err().unwrap().to_string(),
            "height 5 is NaN: a height is finite, or +∞ where the indenter has no surface"
        );
        let bare = Problem::new(operator(), vec![f64::INFINITY; 64]).err().unwrap();
        assert_eq!(bare, ProblemError::NoSurface);
        let mut work = vec![0.1; 64];
        work[7] = -0.1;
        let problem = Problem::new(operator(), vec![0.0; 64]).unwrap();
        let negative = problem.with_work_of_adhesion(work).err().unwrap();
        assert_eq!(negative, ProblemError::WorkOfAdhesion { index: 7, value: -0.1 });
    }

    #[test]
    fn a_translation_on_fixed_heights_is_refused_before_any_step() {
        let mut problem = Problem::new(operator(), vec![0.0; 64]).unwrap();
        let protocol = crate::Translation {
            start_depth: 0.0,
            depth: 1e-3,
            approach_steps: 2,
            distance: 0.1,
            steps: 2,
            return_stroke: false,
            stationary_from: 0.5,
            jump_force_threshold: 0.0,
        };
        let mut solver = crate::NormalSolver::NonAdhesive(crate::Ccg::new(crate::CcgParams::default()));
        let mut records: Vec<crate::StepRecord> = Vec::new();
        let error = protocol.run(&mut problem, &mut solver, &mut records).err().unwrap();
        assert!(error.to_string().contains("Problem::translating"), "{error}");
        assert!(records.is_empty());
    }

    #[test]
    fn a_problem_keeps_what_it_was_given() {
        let mut heights = vec![1.0; 64];
        heights[0] = f64::INFINITY;
        let problem = Problem::new(operator(), heights.clone())
            .unwrap()
            .with_work_of_adhesion(vec![0.25; 64])
            .unwrap();
        assert_eq!(problem.heights(), &heights[..]);
        assert_eq!(problem.work_of_adhesion(), &[0.25; 64][..]);
        assert_eq!(problem.grid().len(), 64);
        assert!(problem.translating_contact().is_none());
    }
}
