//! Time per single-precision application of the free operator with row windows (issue #14
//! item 5): the full `apply_single` against `apply_single_rows` with the input's support on
//! a centred band of N, N/2 or N/4 rows, (a) all output rows kept (what the masked PCG of
//! the fixed-set solves does: it updates the displacement everywhere) and (b) only the
//! band's output rows (the bound for a caller that reads the band only). Median of
//! repeated applications, per thread count. Also checks that every timed windowed result
//! has the full result's bits on its output rows.
//!
//! `cargo run --release -p adhesim --example row_window_apply -- [N ...] [--threads T ...] [--repeats R]`
//! (default: N = 256 512, threads 1 2, 41 repeats).
use adhesim::{Boundary, ElasticMaterial, ElasticOperator, FreeOperator, Grid};
use std::ops::Range;
use std::time::Instant;

fn median_seconds(repeats: usize, mut run: impl FnMut()) -> f64 {
    run(); // warm the caches and the scratch buffers
    let mut times: Vec<f64> = (0..repeats)
        .map(|_| {
            let start = Instant::now();
            run();
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[repeats / 2]
}

fn field_on_rows(n: usize, rows: &Range<usize>) -> Vec<f64> {
    (0..n * n)
        .map(|k| {
            let (i, j) = (k / n, k % n);
            if rows.contains(&i) {
                1.0 + 0.37 * ((i * 7 + j * 13) % 17) as f64
            } else {
                0.0
            }
        })
        .collect()
}

fn measure(n: usize, repeats: usize) {
    let grid = Grid::new(n, 1.0, Boundary::Free).expect("grid");
    let material = ElasticMaterial::new(1.0).expect("material");
    let mut operator = FreeOperator::new(grid, material);
    let mut full_output = vec![0.0; n * n];
    let mut windowed = vec![0.0; n * n];
    for height in [n, n / 2, n / 4] {
        let start = (n - height) / 2;
        let rows = start..start + height;
        let input = field_on_rows(n, &rows);
        let full = median_seconds(repeats, || operator.apply_single(&input, &mut full_output));
        let all_out = median_seconds(repeats, || {
            operator.apply_single_rows(&input, &mut windowed, rows.clone(), 0..n)
        });
        assert!(
            windowed
                .iter()
                .zip(&full_output)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "windowed result differs from the full one"
        );
        let band_out = median_seconds(repeats, || {
            operator.apply_single_rows(&input, &mut windowed, rows.clone(), rows.clone())
        });
        let band = rows.start * n..rows.end * n;
        assert!(
            windowed[band.clone()]
                .iter()
                .zip(&full_output[band])
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "windowed result differs from the full one on the band"
        );
        println!(
            "{n:>5} {:>7} {height:>6} {:>9.3} {:>14.3} ({:>5.1} %) {:>14.3} ({:>5.1} %)",
            rayon::current_num_threads(),
            full * 1e3,
            all_out * 1e3,
            100.0 * (1.0 - all_out / full),
            band_out * 1e3,
            100.0 * (1.0 - band_out / full),
        );
    }
}

fn main() {
    let mut sizes = Vec::new();
    let mut threads = Vec::new();
    let mut repeats = 41;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = |name: &str| -> usize {
            let text = args.next().unwrap_or_else(|| panic!("{name} needs a value"));
            text.parse()
                .unwrap_or_else(|_| panic!("{name}: `{text}` is not a count"))
        };
        match arg.as_str() {
            "--threads" => threads.push(value("--threads")),
            "--repeats" => repeats = value("--repeats").max(1),
            size => sizes.push(
                size.parse()
                    .unwrap_or_else(|_| panic!("grid size: `{size}` is not a count")),
            ),
        }
    }
    if sizes.is_empty() {
        sizes = vec![256, 512];
    }
    if threads.is_empty() {
        threads = vec![1, 2];
    }
    println!("    N threads  rows  full [ms]  all rows out [ms] (gain)  band out [ms] (gain)");
    for &thread_count in &threads {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(thread_count)
            .build()
            .expect("thread pool");
        // The operator plans its per-thread scratch from the pool it is built in.
        pool.install(|| {
            for &n in &sizes {
                measure(n, repeats);
            }
        });
    }
}
