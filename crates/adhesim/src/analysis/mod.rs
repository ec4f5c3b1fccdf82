//! Closed-form references and the analysis of simulated curves.

pub mod contact;
pub mod curve;
pub mod fit;
pub mod friction;
pub mod johnson;
pub mod reference;
pub mod scale;
