//! One module per subcommand; `main.rs` parses the command line and calls them.

pub mod experiment;
pub mod plot;
pub mod reference;
pub mod run;
pub mod study;
pub mod sweep;
pub mod topography;

/// The name among `candidates` that `given` most likely misspells, by the rule of clap's
/// "a similar subcommand exists" tip (Jaro similarity above 0.7), so that a misspelt
/// subcommand read as a file name gets the same suggestion as one clap parses.
pub(crate) fn similar_name<'a>(given: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|name| (strsim::jaro(given, name), name))
        .filter(|(similarity, _)| *similarity > 0.7)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, name)| name)
}
