//! No build step. The script is here for its build-dependency (Cargo.toml): the host's
//! `syn` with the features that pyo3's macros turn on when the Python wheel is built, so
//! that `cargo test --release` and the wheel's build compile the same crates once
//! (ARCHITECTURE.md, "One build for the tests and the wheel").
fn main() {
    println!("cargo::rerun-if-changed=build.rs");
}
