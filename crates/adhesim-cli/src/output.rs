//! The command line's progress bar of a run (a [`RunProgress`] handed to the scenario
//! crate's run pipeline, `adhesim_scenario::output::run::run_into_folder`, which writes
//! the folder; the pictures are `adhesim_figures::run_figures::RunFigures`).

use adhesim::analysis::reference::Jkr;
use adhesim::StepRecord;
use adhesim_scenario::output::observer::RunProgress;
use anyhow::Result;
use indicatif::ProgressBar;

/// The progress bar (hidden when quiet or when stderr is not a terminal) with the
/// current depth and force, normalised by the JKR scales where they exist.
pub struct TerminalProgress {
    bar: ProgressBar,
    jkr: Option<Jkr>,
}

impl TerminalProgress {
    pub fn new(expected_steps: usize, quiet: bool, jkr: Option<Jkr>) -> Self {
        let bar = crate::progress::bar(
            expected_steps as u64,
            crate::progress::RUN_STEPS,
            crate::progress::drawn(quiet),
        );
        Self { bar, jkr }
    }

    fn show(&self, r: &StepRecord) {
        if r.step as u64 >= self.bar.length().unwrap_or(0) {
            self.bar.inc_length(1);
        }
        self.bar.set_position(r.step as u64 + 1);
        let phase = r.phase.map(|p| p.name()).unwrap_or("");
        match &self.jkr {
            Some(jkr) => self.bar.set_message(format!(
                "{phase} d/|d_JKR| = {:.2}, F/|F_JKR| = {:.3}",
                r.depth / jkr.critical_depth().abs(),
                r.force_normal / jkr.critical_force().abs()
            )),
            None => self
                .bar
                .set_message(format!("{phase} d = {:.3e}, F = {:.3e}", r.depth, r.force_normal)),
        }
    }
}

impl RunProgress for TerminalProgress {
    fn step(&mut self, record: &StepRecord) -> Result<()> {
        self.show(record);
        Ok(())
    }

    fn warning(&mut self, message: &str) {
        self.bar.suspend(|| eprintln!("warning: {message}"));
    }

    fn finish(&mut self) {
        self.bar.finish_and_clear();
    }
}
