//! The command line inside the wheel: the console script `adhesim` (pyproject.toml,
//! `adhesim._cli:main`) calls [`cli_main`], which runs the same code as the native binary
//! (`adhesim_cli::main_with_args`), so a `pip install` gives the documented `adhesim ...`
//! commands with the same behaviour and exit codes.

use pyo3::prelude::*;

/// Runs the `adhesim` command line on `argv` (program name first) and returns its exit
/// code (0 success, 1 error, 2 usage error). The GIL is released while it runs.
#[pyfunction]
pub fn cli_main(py: Python<'_>, argv: Vec<String>) -> u8 {
    py.detach(|| adhesim_cli::main_with_args(argv))
}
