//! Elastic operator application against the bare FFT floor, and a cold Hertz solve.
//!
//! `cargo bench -p adhesim-bench --bench operator`
//!
//! The floor is a plain forward + inverse real 2-D FFT pair of the padded 2N×2N array
//! (all rows and columns transformed, no kernel product), run with the same planner,
//! threads and row/column split as the operator.
use adhesim::{
    Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, ElasticOperator, FreeOperator, Grid,
    NestedActiveSet, NestedParams, Profile, Sphere,
};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use num_complex::Complex64;
use rayon::prelude::*;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;

/// A bare 2-D real FFT pair on an m×m array.
struct FftPairFloor {
    m: usize,
    real: Vec<f64>,
    rows: Vec<Complex64>,
    columns: Vec<Complex64>,
    forward_rows: std::sync::Arc<dyn realfft::RealToComplex<f64>>,
    inverse_rows: std::sync::Arc<dyn realfft::ComplexToReal<f64>>,
    forward_columns: std::sync::Arc<dyn rustfft::Fft<f64>>,
    inverse_columns: std::sync::Arc<dyn rustfft::Fft<f64>>,
}

impl FftPairFloor {
    fn new(m: usize) -> Self {
        let mut real_planner = RealFftPlanner::<f64>::new();
        let mut planner = FftPlanner::<f64>::new();
        let h = m / 2 + 1;
        Self {
            m,
            real: (0..m * m).map(|k| (k % 7) as f64).collect(),
            rows: vec![Complex64::default(); m * h],
            columns: vec![Complex64::default(); m * h],
            forward_rows: real_planner.plan_fft_forward(m),
            inverse_rows: real_planner.plan_fft_inverse(m),
            forward_columns: planner.plan_fft_forward(m),
            inverse_columns: planner.plan_fft_inverse(m),
        }
    }

    fn run(&mut self) {
        let (m, h) = (self.m, self.m / 2 + 1);
        let (fr, ir, fc, ic) = (
            &self.forward_rows,
            &self.inverse_rows,
            &self.forward_columns,
            &self.inverse_columns,
        );
        self.real
            .par_chunks_mut(m)
            .zip(self.rows.par_chunks_mut(h))
            .for_each_init(
                || vec![Complex64::default(); fr.get_scratch_len()],
                |scratch, (row, out)| {
                    fr.process_with_scratch(row, out, scratch).unwrap();
                },
            );
        let rows = &self.rows;
        self.columns.par_chunks_mut(m).enumerate().for_each_init(
            || vec![Complex64::default(); fc.get_inplace_scratch_len()],
            |scratch, (c, column)| {
                for (i, v) in column.iter_mut().enumerate() {
                    *v = rows[i * h + c];
                }
                fc.process_with_scratch(column, scratch);
                ic.process_with_scratch(column, scratch);
            },
        );
        let columns = &self.columns;
        self.rows.par_chunks_mut(h).enumerate().for_each(|(i, row)| {
            for (c, v) in row.iter_mut().enumerate() {
                *v = columns[c * m + i];
            }
        });
        self.rows
            .par_chunks_mut(h)
            .zip(self.real.par_chunks_mut(m))
            .for_each_init(
                || vec![Complex64::default(); ir.get_scratch_len()],
                |scratch, (spectrum, row)| {
                    spectrum[0].im = 0.0;
                    spectrum[h - 1].im = 0.0;
                    ir.process_with_scratch(spectrum, row, scratch).unwrap();
                },
            );
    }
}

fn operator_against_floor(c: &mut Criterion) {
    let mut group = c.benchmark_group("free_operator");
    group.sample_size(10);
    for n in [256usize, 512, 1024] {
        let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
        let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
        let pressure: Vec<f64> = (0..grid.len()).map(|k| ((k * 31) % 17) as f64).collect();
        let mut displacement = vec![0.0; grid.len()];
        group.bench_with_input(BenchmarkId::new("apply", n), &n, |b, _| {
            b.iter(|| operator.apply(&pressure, &mut displacement))
        });
        group.bench_with_input(BenchmarkId::new("apply_single", n), &n, |b, _| {
            b.iter(|| operator.apply_single(&pressure, &mut displacement))
        });
        let mut floor = FftPairFloor::new(2 * n);
        group.bench_with_input(BenchmarkId::new("fft_pair_floor_2n", n), &n, |b, _| {
            b.iter(|| floor.run())
        });
    }
    group.finish();
}

fn hertz_cold_solve(c: &mut Criterion) {
    let mut group = c.benchmark_group("hertz_cold_solve");
    group.sample_size(10);
    let n = 512;
    let grid = Grid::new(n, 1.0, Boundary::Free).unwrap();
    let mut operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).unwrap());
    let heights = Sphere::new(1.0).unwrap().heights(&grid);
    // contact radius 128Δ = 0.25
    let depth = 0.25f64.powi(2);
    group.bench_function(BenchmarkId::new("ccg_1e-10", n), |b| {
        b.iter(|| {
            let mut state = ContactState::new(&grid);
            Ccg::new(CcgParams::default())
                .solve(&mut operator, &heights, Control::Displacement(depth), &mut state)
                .unwrap()
        })
    });
    let mut nested = NestedActiveSet::new(grid, ElasticMaterial::new(1.0).unwrap(), NestedParams::default());
    group.bench_function(BenchmarkId::new("nested_active_set_1e-10", n), |b| {
        b.iter(|| {
            let mut state = ContactState::new(&grid);
            nested.solve(&mut operator, &heights, depth, &mut state).unwrap()
        })
    });
    group.finish();
}

criterion_group!(benches, operator_against_floor, hertz_cold_solve);
criterion_main!(benches);
