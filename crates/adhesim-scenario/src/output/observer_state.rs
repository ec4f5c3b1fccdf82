//! What the observer of a run into a folder carries from step to step ([`ObserverState`]),
//! as a mid-case checkpoint stores it: the observer (`observer.rs`) takes its state out and
//! puts it back, the checkpoint file (`checkpoint.rs`) writes and reads it. It lives
//! apart from both, so that the observer imports the checkpoint's writer and the
//! checkpoint does not import the observer.

use adhesim::bit_string;
use std::collections::BTreeMap;

/// A contact set in a checkpoint.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub(super) struct Bits(#[serde(with = "bit_string")] pub(super) Vec<bool>);

/// What the observer of a run carries from step to step (in a checkpoint): everything the
/// files written after the checkpoint depend on.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct ObserverState {
    pub(super) jump_snapshots: usize,
    pub(super) largest: (usize, usize, Bits),
    pub(super) last_in_contact: Option<(usize, Bits, Bits)>,
    pub(super) warnings: Vec<String>,
    pub(super) border_warned: bool,
    pub(super) snapshot_files: Vec<String>,
    pub(super) captured: Vec<(usize, Bits, Bits)>,
    pub(super) phase_seconds: BTreeMap<String, f64>,
    pub(super) phase_steps: BTreeMap<String, usize>,
    pub(super) output_seconds: f64,
    pub(super) fields: Option<crate::SnapshotRecorder>,
    /// The elements touched so far (`adhesion.first_contact_factor`; absent without).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) touched: Option<Bits>,
}

impl ObserverState {
    /// Whether its contact sets and fields are of a grid of `elements` (a checkpoint read
    /// back: a mismatch would otherwise stop the run later).
    pub(crate) fn fits(&self, elements: usize) -> bool {
        let set = |bits: &Bits| bits.0.len() == elements;
        (self.largest.2 .0.is_empty() || set(&self.largest.2))
            && self.last_in_contact.iter().all(|(_, c, p)| set(c) && set(p))
            && self.captured.iter().all(|(_, c, p)| set(c) && set(p))
            && self.fields.as_ref().is_none_or(|f| f.fits(elements))
            && self.touched.as_ref().is_none_or(set)
    }
}
