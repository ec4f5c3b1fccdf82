//! Closed-form references and the analysis of simulated curves.

pub mod reference;
