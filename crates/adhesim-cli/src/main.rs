//! `adhesim`: command-line front end of the adhesim simulator (see `docs/cli.md`). The
//! command line itself is the library's [`adhesim_cli::main_with_args`].

use std::process::ExitCode;

fn main() -> ExitCode {
    ExitCode::from(adhesim_cli::main_with_args(std::env::args_os()))
}
