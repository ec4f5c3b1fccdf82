//! Criterion benchmarks of adhesim (`benches/operator.rs`): the elastic operator's apply
//! against the bare FFT pair of its padded grid, and a cold Hertz solve.
//!
//! `cargo bench -p adhesim-bench --bench operator -- --noplot`
