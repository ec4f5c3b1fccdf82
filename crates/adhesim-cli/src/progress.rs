//! The command line's one progress-bar builder: every bar (a run's steps, a sweep's cases
//! and steps, an experiment's frames) is drawn on stderr in one style, and none is drawn
//! when quiet or when stderr is not a terminal (a log file gets no control characters).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// A run's steps (`adhesim run`), with the depth and force as the message.
pub const RUN_STEPS: &str = "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} steps {msg}";
/// A sweep's finished cases.
pub const SWEEP_CASES: &str = "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} cases (eta {eta}) {msg}";
/// The steps of a sweep's running cases, under its cases.
pub const SWEEP_STEPS: &str = "  {bar:40} {pos}/{len} steps {msg}";
/// Frames of an experiment (analysed or rendered), the message saying which.
pub const FRAMES: &str = "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} {msg} {per_sec} eta {eta}";

/// Whether bars are drawn: not when `quiet`, nor when stderr is not a terminal.
pub fn drawn(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

/// The style of a `template` (one of this module's constants).
pub fn style(template: &str) -> ProgressStyle {
    ProgressStyle::with_template(template).expect("the module's templates are valid")
}

/// A bar of `length` in `template`'s style, on stderr where `drawn`, else hidden.
pub fn bar(length: u64, template: &str, drawn: bool) -> ProgressBar {
    let target = if drawn {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(length), target);
    bar.set_style(style(template));
    bar
}
