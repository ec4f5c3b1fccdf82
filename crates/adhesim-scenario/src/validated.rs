//! What `ScenarioFile::validate` hands to the validator of the scenario's protocol
//! ([`ValidatedSections`]: the library objects of every section but `[protocol]`) and the
//! default approach steps that the roll / slide / translate and the shear validators share.
//! validate.rs builds it, translation.rs and shear.rs take it apart; it imports neither,
//! so that the protocols' validators need not import validate.rs or each other.

use crate::model::{AdhesionLaw, Derived};
use adhesim::analysis::reference::Jkr;
use adhesim::{ElasticLayer, ElasticMaterial, Grid, Indenter};

/// What `validate` has built from every section but `[protocol]`, handed to the
/// indentation or the roll/slide part (not the friction analysis's `TranslationInputs`).
pub(crate) struct ValidatedSections {
    pub(crate) grid: Grid,
    pub(crate) material: ElasticMaterial,
    /// The layer of `material.thickness` (None: the half-space).
    pub(crate) layer: Option<ElasticLayer>,
    pub(crate) gamma: Vec<f64>,
    pub(crate) gamma0: f64,
    /// `[adhesion]`'s law with its parameters.
    pub(crate) law: AdhesionLaw,
    pub(crate) indenter: Indenter,
    /// Length of one `depth_unit`.
    pub(crate) unit: f64,
    pub(crate) jkr: Option<Jkr>,
    pub(crate) derived: Derived,
    /// `[substrate_roughness]` on the grid (slide only).
    pub(crate) substrate_roughness: Option<Vec<f64>>,
}

/// Default approach steps of roll / slide / translate.
pub const DEFAULT_APPROACH_STEPS: i64 = 50;
