//! The integration tests of the `adhesim` command (its binary run end to end), gathered
//! into one test binary so that the crate and its dependencies are linked once: a module
//! per topic (a file of this folder), run alone with the module as the filter:
//! `cargo test --release -p adhesim-cli --test integration sweep::`.

// Helpers shared by the modules below.
mod common;

mod cli;
mod determinism;
mod experiment_cli;
mod experiment_film;
mod experiment_inputs;
mod experiment_speed;
mod fields;
mod friction_library;
mod guards;
mod hostile;
mod periodic_runs;
mod rectangular;
mod safe_outputs;
mod study_resume;
mod sweep;
mod topography;
mod translation;
