//! The same problem gives bit-identical results on 1, 2 and 3 threads: every FFT row and
//! column is transformed independently of how the work is split, element-wise loops and
//! exact reductions (max, any) run on the pool in chunks, and every sum is sequential.

use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, ElasticMaterial, FreeOperator, Grid, IndentPulloff, NormalSolver,
    Problem, Profile, StepRecord, WavySphere,
};

fn wavy_sphere_cycle(n: usize) -> Vec<StepRecord> {
    let grid = Grid::new(n, 0.3 * n as f64 / 48.0, Boundary::Free).unwrap();
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let profile = WavySphere::new(1.0, 5e-4, 0.025, 0.0).unwrap();
    let heights = profile.heights(&grid);
    let start = heights.iter().cloned().fold(f64::INFINITY, f64::min);
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        1.0,
        vec![2e-5; grid.len()],
        AdhesiveParams::default(),
    )));
    let protocol = IndentPulloff {
        start_depth: start,
        max_depth: 3e-3,
        depth_step: 1e-4,
        max_retract_steps: 10_000,
        jump_force_threshold: 0.0,
    };
    let mut records = Vec::new();
    let mut problem = Problem::new(Box::new(operator), heights).unwrap();
    protocol.run(&mut problem, &mut solver, &mut records).unwrap();
    records
}

/// Runs the cycle on pools of 1, 2 and 3 threads and compares every step bit for bit.
fn check_thread_counts(n: usize) {
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| wavy_sphere_cycle(n))
    };
    let single = run(1);
    assert!(single.len() > 20);
    assert!(single.iter().any(|r| r.force_normal < 0.0), "adhesive case expected");
    for threads in [2, 3] {
        let other = run(threads);
        assert_eq!(single.len(), other.len());
        for (a, b) in single.iter().zip(&other) {
            assert_eq!(a.force_normal.to_bits(), b.force_normal.to_bits(), "step {}", a.step);
            assert_eq!(a.contact_elements, b.contact_elements);
            assert_eq!(
                a.report.dissipated_energy.to_bits(),
                b.report.dissipated_energy.to_bits()
            );
        }
    }
}

#[test]
fn one_and_two_threads_agree_bit_for_bit() {
    check_thread_counts(48);
}

/// 96² elements: more than one chunk of the pool's element-wise loops and reductions
/// (`PARALLEL_CHUNK` = 8192 elements), so the chunked paths are the ones compared.
#[test]
fn chunked_loops_agree_bit_for_bit() {
    check_thread_counts(96);
}
