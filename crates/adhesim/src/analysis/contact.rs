//! Geometry of a contact set: connected patches, extent.

use crate::grid::Grid;
use crate::protocol::{Observer, StepView};
use std::ops::ControlFlow;

/// Number of edge-connected (4-neighbour) patches of the contact set.
pub fn count_patches(grid: &Grid, contact: &[bool]) -> usize {
    assert_eq!(contact.len(), grid.len(), "contact set does not match the grid");
    let mut seen = vec![false; contact.len()];
    let mut stack = Vec::new();
    let mut patches = 0;
    for start in 0..contact.len() {
        if !contact[start] || seen[start] {
            continue;
        }
        patches += 1;
        seen[start] = true;
        stack.push(start);
        while let Some(k) = stack.pop() {
            grid.for_each_neighbour(k, |neighbour| {
                if contact[neighbour] && !seen[neighbour] {
                    seen[neighbour] = true;
                    stack.push(neighbour);
                }
            });
        }
    }
    patches
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Boundary;

    #[test]
    fn counts_patches() {
        let grid = Grid::new(4, 1.0, Boundary::Free).unwrap();
        let mut contact = vec![false; 16];
        assert_eq!(count_patches(&grid, &contact), 0);
        contact[0] = true;
        contact[1] = true;
        contact[3] = true;
        assert_eq!(count_patches(&grid, &contact), 2);
        // diagonal neighbours are not connected
        contact[6] = true;
        assert_eq!(count_patches(&grid, &contact), 3);
        let periodic = Grid::new(4, 1.0, Boundary::Periodic).unwrap();
        assert_eq!(count_patches(&periodic, &contact), 2);
    }
}

/// An observer of a run that records where the contact first lets go (the centres of the
/// elements released in the first step with a detachment) and the largest number of
/// separate patches the contact splits into: the detachment pattern of a flat punch
/// (paper Sect. 5.1, Fig. 12).
#[derive(Debug, Clone)]
pub struct DetachmentWatch {
    grid: Grid,
    /// Centres (x, y) of the first released elements, `None` before any release.
    pub first_detached: Option<Vec<(f64, f64)>>,
    /// The most patches seen at the end of a step.
    pub most_patches: usize,
}

impl DetachmentWatch {
    /// A watch of runs on `grid`.
    pub fn new(grid: Grid) -> Self {
        Self {
            grid,
            first_detached: None,
            most_patches: 0,
        }
    }
}

impl Observer for DetachmentWatch {
    fn on_step(&mut self, view: StepView<'_>) -> ControlFlow<()> {
        if self.first_detached.is_none() && view.record.report.detached > 0 {
            let positions = (0..self.grid.len())
                .filter(|&k| view.previous_contact[k] && !view.state.contact[k])
                .map(|k| self.grid.centre(k))
                .collect();
            self.first_detached = Some(positions);
        }
        self.most_patches = self.most_patches.max(count_patches(&self.grid, &view.state.contact));
        ControlFlow::Continue(())
    }
}
