//! Sweeps: the plan of a sweep file (cases, pseudo-keys, hashes) and its `table.csv`.

pub mod plan;
pub mod table;
