//! The integration tests of the library `adhesim`, gathered into one test binary so that
//! the crate and its dependencies are linked once: a module per topic (a file of this
//! folder), run alone with the module as the filter:
//! `cargo test --release -p adhesim --test integration validation_jkr::`.

// Helpers shared by the modules below.
mod checkpoint_common;
mod common;

mod analysis_fits;
mod ccg_strip;
mod checkpoint;
mod checkpoint_translation;
mod determinism;
mod fast_step;
mod nested_window;
mod periodic_matrix;
mod punch_face_at_depth;
mod rough_indenter;
mod rough_sphere_limit;
mod solver_options;
mod step_size;
mod surface_generator;
mod validation_cohesive_periodic;
mod validation_exponential;
mod validation_hertz;
mod validation_jkr;
mod validation_layer;
mod validation_maugis;
mod validation_operator;
mod validation_patch;
mod validation_periodic;
mod validation_persson;
mod validation_punch;
mod validation_rectangle;
mod validation_translation;
