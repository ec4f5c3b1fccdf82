//! The integration tests of `adhesim-scenario`, gathered into one test binary so that the
//! crate and its dependencies are linked once: a module per topic (a file of this folder),
//! run alone with the module as the filter:
//! `cargo test --release -p adhesim-scenario --test integration fuzz::`.

mod fuzz;
mod house;
mod roughness;
mod roughness_files;
