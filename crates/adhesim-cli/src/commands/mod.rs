//! One module per subcommand; `main.rs` parses the command line and calls them.

pub mod experiment;
pub mod reference;
pub mod run;
pub mod study;
pub mod sweep;
pub mod topography;
