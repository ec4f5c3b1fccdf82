//! The integration tests of `adhesim-topography`, gathered into one test binary so that the
//! crate and its dependencies are linked once: a module per topic (a file of this folder),
//! run alone with the module as the filter:
//! `cargo test --release -p adhesim-topography --test integration writers::`.

// Helpers shared by the modules below.
mod common;

mod processing;
mod reference_files;
mod robustness;
mod round_trips;
mod surfacetopography;
mod text_and_units;
mod writers;
