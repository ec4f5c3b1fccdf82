//! Solutions of small dense systems kept by the shape of their window: the local peel's
//! window solves and the peel predictor's rises. Both systems have entries that depend
//! only on the offsets between the window's elements, and right-hand sides that depend
//! only on the offsets from the window's centre, so two windows of one shape have the same
//! solution, and a stored one is the bits a new solve would give. A peeling front meets
//! the same local configurations over and over, so most windows have been met before.

use std::collections::HashMap;

/// A window's offsets (row, column) from its centre, in window order.
pub(crate) type Shape = Vec<(i8, i8)>;

/// Writes the offsets of `window` about `centre` into `shape`.
pub(crate) fn window_shape(window: &[(i64, i64)], centre: (i64, i64), shape: &mut Shape) {
    shape.clear();
    // Windows lie within a few elements of their centre, so the offsets fit an i8.
    shape.extend(
        window
            .iter()
            .map(|&(r, c)| ((r - centre.0) as i8, (c - centre.1) as i8)),
    );
}

/// Shapes kept at most (each under 1 KiB of offsets and values); the cache is emptied
/// when full.
const CAPACITY: usize = 1 << 14;

/// Values by window shape.
#[derive(Default)]
pub(crate) struct ShapeCache {
    values: HashMap<Shape, Vec<f64>>,
    /// The shape of the last look-up (reused: no allocation on a hit).
    key: Shape,
}

impl ShapeCache {
    /// The values stored under the shape of `window` about `centre`, which becomes the
    /// key of the next [`store`](Self::store).
    pub(crate) fn look_up(&mut self, window: &[(i64, i64)], centre: (i64, i64)) -> Option<&[f64]> {
        window_shape(window, centre, &mut self.key);
        self.values.get(self.key.as_slice()).map(Vec::as_slice)
    }

    /// The values stored under `shape` (read-only, for look-ups in parallel with keys of
    /// their own).
    pub(crate) fn get(&self, shape: &[(i8, i8)]) -> Option<&[f64]> {
        self.values.get(shape).map(Vec::as_slice)
    }

    /// Stores `values` under the shape of the last look-up.
    pub(crate) fn store(&mut self, values: &[f64]) {
        if self.values.len() >= CAPACITY {
            self.values.clear();
        }
        self.values.insert(self.key.clone(), values.to_vec());
    }

    /// Stores `values` under the shape of `window` about `centre` (a shape solved twice in
    /// one parallel batch is stored twice, with the same values).
    pub(crate) fn insert(&mut self, window: &[(i64, i64)], centre: (i64, i64), values: &[f64]) {
        window_shape(window, centre, &mut self.key);
        self.store(values);
    }

    /// Shapes stored.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.values.len()
    }
}
