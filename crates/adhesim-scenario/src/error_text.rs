//! Errors as one line of text for the terminal and for a batch case's `error.txt`.

/// An error and its causes on one line, `a: b: c`, leaving out a cause whose text the line
/// already holds: errors whose message includes their source (thiserror's `{source}`, as in
/// `adhesim::ProtocolError::Solve`, or the image decoders' errors) would otherwise show it
/// twice with `{:#}`.
pub fn error_line(chain: anyhow::Chain) -> String {
    let mut line = String::new();
    for cause in chain {
        let text = cause.to_string();
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

#[cfg(test)]
mod tests {
    use super::error_line;
    use adhesim::{ProtocolError, SolveError};

    /// First robustness audit (docs/reliability.md): "solver produced a non-finite value" was printed twice.
    #[test]
    fn a_solver_error_is_printed_once() {
        let error = anyhow::Error::new(ProtocolError::Solve {
            step: 3,
            depth: 0.0,
            source: SolveError::NonFinite { iteration: 1 },
        })
        .context("run failed; out/curve.csv holds the steps done");
        assert_eq!(
            error_line(error.chain()),
            "run failed; out/curve.csv holds the steps done: step 3 (d = 0e0): solver produced a non-finite value at iteration 1"
        );
        // The old `{:#}` printed the solver's message twice.
        assert_eq!(format!("{error:#}").matches("non-finite").count(), 2);
        // Causes that are not repeated are all kept.
        let io = anyhow::Error::new(std::io::Error::other("disk full")).context("cannot write curve.csv");
        assert_eq!(error_line(io.chain()), "cannot write curve.csv: disk full");
    }
}
