//! Closed-form references and the analysis of simulated curves.

pub mod contact;
pub mod curve;
pub mod fit;
pub mod reference;
