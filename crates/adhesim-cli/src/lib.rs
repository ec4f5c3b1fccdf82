//! The `adhesim` command line as a library: [`main_with_args`] parses the arguments and
//! dispatches to `commands/`. The binary (`src/main.rs`) and the Python wheel's console
//! script (`adhesim._adhesim.cli_main`) both call it, so they behave alike, exit codes
//! included (docs/cli.md).

/// `println!` for the commands' reports: a reader that closed the pipe early (`adhesim
/// sweep merge DIR | head -1`) has what it wanted, so a closed pipe is ignored, where
/// `println!` panics; any other failure to write standard output ends the command with
/// exit code 1 and a message, never a panic or a silently cut report.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::write_stdout_line(format_args!($($arg)*))
    };
}

/// The line of [`outln!`].
fn write_stdout_line(line: std::fmt::Arguments) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let written = stdout.write_fmt(line).and_then(|()| stdout.write_all(b"\n"));
    match written {
        Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => {}
        Err(error) => {
            eprintln!("error: cannot write to standard output: {error}");
            std::process::exit(1);
        }
        Ok(()) => {}
    }
}

mod commands;
mod output;
mod progress;
mod resources;

/// The frame reader of `adhesim experiment` (public for the integration tests, which
/// compare it pixel by pixel with reference decodings).
pub use commands::experiment::read_frame;

use adhesim_scenario::error_text::error_line;
use clap::{Parser, Subcommand};
use commands::{experiment, plot, reference, run, study, sweep, topography};

/// Adhesive contacts of rough elastic bodies (FFT-accelerated BEM, Popov et al. 2021).
///
/// Without a subcommand, runs the built-in default scenario (the paper's Fig. 1 case)
/// into ./out/default/.
#[derive(Parser)]
#[command(name = "adhesim", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scenario file.
    Run(run::RunArgs),
    /// Print a closed-form reference curve as CSV to stdout.
    Reference(reference::ReferenceArgs),
    /// Run a parameter study (resumable, parallel, shardable); `sweep merge DIR` rebuilds
    /// its table and plots.
    Sweep(sweep::SweepArgs),
    /// Redraw figures, e.g. `plot master TABLE.csv... [--out DIR]` (master curves).
    Plot(plot::PlotArgs),
    /// Rolling / sliding friction study over the Johnson parameter (paper Figs. 7, 8, 10).
    Study(study::StudyArgs),
    /// Analyse a filmed contact experiment (`adhesim experiment SPEC.toml [--out DIR]`), or
    /// generate a synthetic one (`adhesim experiment synth`).
    Experiment(experiment::ExperimentArgs),
    /// Statistics, PSD plot and height map of an instrument file or a scenario's roughness.
    Topography(topography::TopographyArgs),
}

/// A write past the file-size limit (`ulimit -f`, RLIMIT_FSIZE, which batch schedulers
/// set) raises SIGXFSZ, whose default action kills the process mid-write with no message.
/// Ignored, the write fails with EFBIG and the command stops with the error naming the
/// file, as on a full disk (`cannot write DIR/curve.csv.partial: File too large`), leaving
/// no file cut under a final name. (Python ignores SIGXFSZ itself.)
fn ignore_file_size_signal() {
    #[cfg(unix)]
    // SAFETY: SIG_IGN installs no handler code; it only changes the signal's disposition,
    // which no other part of the program sets.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

/// Runs the command line on `args` (the program name first, as `std::env::args_os`
/// gives it) and returns the exit code: 0 success, 1 an error (printed on stderr as one
/// line), 2 a usage error (clap's message).
pub fn main_with_args<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    ignore_file_size_signal();
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(error) => {
            let _ = error.print();
            return if error.use_stderr() { 2 } else { 0 };
        }
    };
    let result = match cli.command {
        None => run::run_default(),
        Some(Command::Run(args)) => run::command(&args),
        Some(Command::Reference(args)) => reference::print(&args),
        Some(Command::Sweep(args)) => sweep::command(&args),
        Some(Command::Plot(args)) => plot::command(&args),
        Some(Command::Study(args)) => study::run(&args),
        Some(Command::Experiment(args)) => experiment::main(args),
        Some(Command::Topography(args)) => topography::command(&args),
    };
    match result {
        Ok(()) => 0,
        Err(error) => {
            eprintln!("error: {}", error_line(error.chain()));
            1
        }
    }
}
