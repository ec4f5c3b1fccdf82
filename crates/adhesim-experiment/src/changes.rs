//! Change maps between two contact masks (paper Figs. 16, 18, 24).

use crate::{ContactMask, ExperimentError};

/// State of one pixel in a change map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Change {
    /// Same state in both masks.
    Unchanged,
    /// In contact now, free in the reference (shown red).
    New,
    /// Free now, in contact in the reference (shown blue).
    Vanished,
}

/// Pixel-wise comparison of a current mask with a reference mask.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChangeMap {
    width: usize,
    height: usize,
    changes: Vec<Change>,
    new_pixels: usize,
    vanished_pixels: usize,
}

impl ChangeMap {
    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Row-major pixel changes.
    pub fn changes(&self) -> &[Change] {
        &self.changes
    }

    /// Number of new contact pixels (C_t ∧ ¬C_ref).
    pub fn new_pixels(&self) -> usize {
        self.new_pixels
    }

    /// Number of vanished contact pixels (C_ref ∧ ¬C_t).
    pub fn vanished_pixels(&self) -> usize {
        self.vanished_pixels
    }
}

/// new = C_t ∧ ¬C_ref, vanished = C_ref ∧ ¬C_t.
pub fn change_map(reference: &ContactMask, current: &ContactMask) -> Result<ChangeMap, ExperimentError> {
    if (reference.width(), reference.height()) != (current.width(), current.height()) {
        return Err(ExperimentError::SizeMismatch(
            reference.width(),
            reference.height(),
            current.width(),
            current.height(),
        ));
    }
    let (mut new_pixels, mut vanished_pixels) = (0, 0);
    let changes = reference
        .cells()
        .iter()
        .zip(current.cells())
        .map(|(&r, &c)| match (r != 0, c != 0) {
            (false, true) => {
                new_pixels += 1;
                Change::New
            }
            (true, false) => {
                vanished_pixels += 1;
                Change::Vanished
            }
            _ => Change::Unchanged,
        })
        .collect();
    Ok(ChangeMap {
        width: current.width(),
        height: current.height(),
        changes,
        new_pixels,
        vanished_pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The four combinations of reference/current states map to the right change (exact).
    #[test]
    fn truth_table() {
        let reference = ContactMask::from_cells(4, 1, vec![0, 0, 1, 1]).unwrap();
        let current = ContactMask::from_cells(4, 1, vec![0, 1, 0, 1]).unwrap();
        let map = change_map(&reference, &current).unwrap();
        assert_eq!(
            map.changes(),
            &[Change::Unchanged, Change::New, Change::Vanished, Change::Unchanged]
        );
        assert_eq!((map.new_pixels(), map.vanished_pixels()), (1, 1));
        assert!(change_map(&reference, &ContactMask::empty(2, 2).unwrap()).is_err());
    }
}
