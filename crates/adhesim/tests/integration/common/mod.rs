//! Shared set-ups for the validation tests.
#![allow(dead_code)]

use adhesim::analysis::reference::Jkr;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff, NormalSolver,
    Problem, Profile, ProtocolSummary, Sphere, StepRecord,
};

/// A smooth-sphere JKR case with R = E* = 1 and γ chosen so that a_JKR = 0.05.
pub struct JkrCase {
    pub jkr: Jkr,
    pub grid: Grid,
}

impl JkrCase {
    /// Resolution a_JKR/Δ and the deepest indentation in units of |d_JKR| fix the grid:
    /// the domain holds the JKR contact at max depth with ≥ 15 % margin.
    pub fn new(resolution: f64, max_depth_jkr: f64) -> Self {
        let a_jkr: f64 = 0.05;
        let gamma = a_jkr.powi(3) * 8.0 / (9.0 * std::f64::consts::PI);
        let jkr = Jkr {
            radius: 1.0,
            contact_modulus: 1.0,
            work_of_adhesion: gamma,
        };
        let delta = a_jkr / resolution;
        let reach = jkr.radius_at_depth(max_depth_jkr * jkr.critical_depth().abs()).unwrap();
        let n = ((2.3 * reach / delta).ceil() as usize).max(16);
        let n = n + n % 2;
        let grid = Grid::new(n, n as f64 * delta, Boundary::Free).unwrap();
        Self { jkr, grid }
    }

    pub fn run(&self, max_depth_jkr: f64, steps_per_unit: f64) -> (ProtocolSummary, Vec<StepRecord>) {
        self.run_with(AdhesiveParams::default(), max_depth_jkr, steps_per_unit)
    }

    /// As [`run`](Self::run), with other solver parameters.
    pub fn run_with(
        &self,
        params: AdhesiveParams,
        max_depth_jkr: f64,
        steps_per_unit: f64,
    ) -> (ProtocolSummary, Vec<StepRecord>) {
        let material = ElasticMaterial::new(1.0).unwrap();
        let operator = FreeOperator::new(self.grid, material);
        let heights = Sphere::new(1.0).unwrap().heights(&self.grid);
        let d_jkr = self.jkr.critical_depth().abs();
        let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
            self.grid,
            1.0,
            vec![self.jkr.work_of_adhesion; self.grid.len()],
            params,
        )));
        let protocol = IndentPulloff {
            start_depth: 0.0,
            max_depth: max_depth_jkr * d_jkr,
            depth_step: d_jkr / steps_per_unit,
            max_retract_steps: 100_000,
            jump_force_threshold: 0.0,
        };
        let mut records = Vec::new();
        let mut problem = Problem::new(Box::new(operator), heights).unwrap();
        let summary = protocol.run(&mut problem, &mut solver, &mut records).unwrap();
        (summary, records)
    }
}

/// ∮F dd of the recorded force–depth polyline, starting from (d = 0, F = 0).
pub fn loop_area(records: &[StepRecord]) -> f64 {
    let mut area = 0.5 * records[0].force_normal * records[0].depth;
    for pair in records.windows(2) {
        area += 0.5 * (pair[0].force_normal + pair[1].force_normal) * (pair[1].depth - pair[0].depth);
    }
    area
}
