//! Geometry of a contact set: connected patches, extent.

use crate::grid::Grid;

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
