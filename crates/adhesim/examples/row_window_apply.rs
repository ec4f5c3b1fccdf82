//! Time per single-precision application of the free operator with row windows
//! (docs/history.md §2026-11-23: row-window transforms): the full `apply_single` against
//! `apply_single_rows` with the input's support on a centred band of N, N/2 or N/4 rows, (a)
//! all output rows kept (what the masked PCG of the fixed-set solves does: it updates the
//! displacement everywhere) and (b) only the band's output rows (the bound for a caller that
//! reads the band only). Median of samples (CPU time of the process and wall time per
//! application), per thread count. Also checks that every timed windowed result has the full
//! result's bits on its output rows.
//!
//! `cargo run --release -p adhesim --example row_window_apply -- [N ...] [--threads T ...] [--repeats R]`
//! (default: N = 256 512, threads 1 2, 41 repeats).
use adhesim::{Boundary, ElasticMaterial, ElasticOperator, FreeOperator, Grid};
use std::ops::Range;
use std::time::Instant;

/// CPU seconds of every thread of this process so far (Linux: /proc/self/task/*/schedstat,
/// nanoseconds on a CPU). On a shared machine wall time mostly measures the other
/// processes; CPU time does not (apart from cache sharing). Rayon's idle spinning counts.
fn process_cpu_seconds() -> f64 {
    let tasks = std::fs::read_dir("/proc/self/task").expect("/proc/self/task (Linux only)");
    tasks
        .filter_map(|task| std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok())
        .filter_map(|line| line.split_whitespace().next()?.parse::<f64>().ok())
        .sum::<f64>()
        * 1e-9
}

/// Median over `repeats` samples of (CPU, wall) seconds per call, each sample `batch` calls.
fn median_seconds(repeats: usize, batch: usize, mut run: impl FnMut()) -> (f64, f64) {
    run(); // warm the caches and the scratch buffers
    let (mut cpu, mut wall): (Vec<f64>, Vec<f64>) = (0..repeats)
        .map(|_| {
            let (cpu_start, start) = (process_cpu_seconds(), Instant::now());
            for _ in 0..batch {
                run();
            }
            let wall = start.elapsed().as_secs_f64();
            ((process_cpu_seconds() - cpu_start) / batch as f64, wall / batch as f64)
        })
        .unzip();
    cpu.sort_by(f64::total_cmp);
    wall.sort_by(f64::total_cmp);
    (cpu[repeats / 2], wall[repeats / 2])
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
        let batch = (1 << 20) / (n * n) + 1;
        let full = median_seconds(repeats, batch, || operator.apply_single(&input, &mut full_output));
        let all_out = median_seconds(repeats, batch, || {
            operator.apply_single_rows(&input, &mut windowed, rows.clone(), 0..n)
        });
        assert!(
            windowed
                .iter()
                .zip(&full_output)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "windowed result differs from the full one"
        );
        let band_out = median_seconds(repeats, batch, || {
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
        let gain = |time: f64, reference: f64| 100.0 * (1.0 - time / reference);
        println!(
            "{n:>5} {:>7} {height:>5} | {:>8.3} {:>8.3} | {:>8.3} {:>6.1} % {:>8.3} | {:>8.3} {:>6.1} % {:>8.3}",
            rayon::current_num_threads(),
            full.0 * 1e3,
            full.1 * 1e3,
            all_out.0 * 1e3,
            gain(all_out.0, full.0),
            all_out.1 * 1e3,
            band_out.0 * 1e3,
            gain(band_out.0, full.0),
            band_out.1 * 1e3,
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
    println!("milliseconds per application, median of {repeats} samples; gain = CPU time saved against the full apply");
    println!(
        "    N threads  rows | full cpu     wall | all rows out: cpu  gain     wall | band rows out: cpu gain   wall"
    );
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
