//! What the checkpoint tests of indentations and translations share: an observer that
//! keeps every record and the checkpoints asked for, the checkpoint read back as a fresh
//! process would, and records compared by their bits.
#![allow(dead_code)]

use adhesim::{IndentCheckpoint, Observer, ProtocolCheckpoint, StepRecord, StepView, TranslationCheckpoint};
use std::ops::ControlFlow;

/// The protocol's own checkpoint inside a [`ProtocolCheckpoint`].
pub trait OfProtocol: Sized {
    fn of(checkpoint: ProtocolCheckpoint) -> Option<Self>;
}

impl OfProtocol for IndentCheckpoint {
    fn of(checkpoint: ProtocolCheckpoint) -> Option<Self> {
        match checkpoint {
            ProtocolCheckpoint::Indentation(c) => Some(*c),
            ProtocolCheckpoint::Translation(_) => None,
        }
    }
}

impl OfProtocol for TranslationCheckpoint {
    fn of(checkpoint: ProtocolCheckpoint) -> Option<Self> {
        match checkpoint {
            ProtocolCheckpoint::Translation(c) => Some(*c),
            ProtocolCheckpoint::Indentation(_) => None,
        }
    }
}

/// Keeps every record and the checkpoints after the steps in `at` (steps done).
pub struct Taker<C> {
    pub records: Vec<StepRecord>,
    pub at: Vec<usize>,
    pub taken: Vec<C>,
}

impl<C> Taker<C> {
    pub fn at(at: Vec<usize>) -> Self {
        Self {
            records: Vec::new(),
            at,
            taken: Vec::new(),
        }
    }
}

impl<C: OfProtocol> Observer for Taker<C> {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        self.records.push(*view.record);
        ControlFlow::Continue(())
    }

    fn wants_checkpoint(&mut self) -> bool {
        self.at.contains(&self.records.len())
    }

    fn on_checkpoint(&mut self, checkpoint: ProtocolCheckpoint) -> ControlFlow<()> {
        let name = checkpoint.protocol_name();
        let checkpoint = C::of(checkpoint).unwrap_or_else(|| panic!("the protocol offered {name}'s checkpoint"));
        self.taken.push(checkpoint);
        ControlFlow::Continue(())
    }
}

/// The checkpoint as a fresh process would read it back: through JSON bytes with the
/// `serde` feature (the form the scenario crate writes), else a clone.
#[cfg(feature = "serde")]
pub fn round_trip<C>(checkpoint: &C) -> C
where
    C: std::fmt::Debug + serde::Serialize + serde::de::DeserializeOwned,
{
    let bytes = serde_json::to_vec(checkpoint).unwrap();
    let back: C = serde_json::from_slice(&bytes).unwrap();
    assert_eq!(format!("{back:?}"), format!("{checkpoint:?}"));
    back
}

#[cfg(not(feature = "serde"))]
pub fn round_trip<C: Clone>(checkpoint: &C) -> C {
    checkpoint.clone()
}

/// Each record as text: every f64 in its shortest round-trip form, −0 told from +0.
pub fn bits(records: &[StepRecord]) -> Vec<String> {
    records.iter().map(|r| format!("{r:?}")).collect()
}
