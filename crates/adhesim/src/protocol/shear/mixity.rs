//! The mode mixity of the shear-weakened edge by the side of the edge an element is on
//! (docs/physics.md §8.5).
//!
//! At a straight stretch of the contact's edge with outward normal n̂, an element's shear
//! traction q splits into the part across the edge, q·n̂ (mode II), and the part along it,
//! q·t̂ (mode III). A mode II share that differs with its sign is the asymmetric shielding
//! of interfacial fracture under in-plane shear (Liechti & Chai 1992, J. Appl. Mech. 59,
//! 295; Hutchinson & Suo 1992, Adv. Appl. Mech. 29, 63, §5): the toughness depends on
//! whether the shear opens the interface's crack ahead of it or closes it. On a sliding
//! indenter's contact q points along the slide, so q·n̂ > 0 at the front of the contact and
//! q·n̂ < 0 at its rear.

use crate::grid::{Boundary, Grid};

/// Mode mixities m ∈ [0, 1] of the shear-weakened edge: the share of an element's shear
/// energy that counts toward its detachment, by the side of the edge it is on.
///
/// An element counts m_front·(q·n̂)² where its traction points out of the contact
/// (q·n̂ > 0), m_rear·(q·n̂)² where it points in, and m_along·(q·t̂)² for the part along the
/// edge. An element with no open neighbour, or open on opposite sides, has no edge
/// direction and counts m_along·|q|². With the three equal this is one constant m·|q|².
///
/// # Example
/// ```
/// use adhesim::protocol::ModeMixity;
///
/// // The front edge of a slide weakened fully, the rear not at all.
/// let mixity = ModeMixity { along: 0.5, front: 1.0, rear: 0.0 };
/// // Traction (2, 0) at an edge open towards +x (the front): 1·2² counts.
/// assert_eq!(mixity.counted_square([2.0, 0.0], [1.0, 0.0]), 4.0);
/// // The same traction at an edge open towards −x (the rear): nothing counts.
/// assert_eq!(mixity.counted_square([2.0, 0.0], [-1.0, 0.0]), 0.0);
/// // Along an edge open towards +y: the mode III share, 0.5·2².
/// assert_eq!(mixity.counted_square([2.0, 0.0], [0.0, 1.0]), 2.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ModeMixity {
    /// m of the shear along the edge (mode III) and of an element without an edge direction.
    pub along: f64,
    /// m of the shear across the edge where it points out of the contact (mode II, front).
    pub front: f64,
    /// m of the shear across the edge where it points into the contact (mode II, rear).
    pub rear: f64,
}

impl ModeMixity {
    /// One mixity m for every side of the edge.
    pub fn uniform(mode_mixity: f64) -> Self {
        Self {
            along: mode_mixity,
            front: mode_mixity,
            rear: mode_mixity,
        }
    }

    /// Whether the shear weakens the edge anywhere.
    pub fn weakens(&self) -> bool {
        self.along > 0.0 || self.front > 0.0 || self.rear > 0.0
    }

    /// Whether the three mixities are one (then no edge direction is needed).
    pub fn is_uniform(&self) -> bool {
        self.front == self.along && self.rear == self.along
    }

    /// The three values with their names, for checks.
    pub fn named(&self) -> [(&'static str, f64); 3] {
        [("along", self.along), ("front", self.front), ("rear", self.rear)]
    }

    /// The counted m·q² of a `traction` at an edge of unit outward `normal` ([0, 0]: none).
    pub fn counted_square(&self, traction: [f64; 2], normal: [f64; 2]) -> f64 {
        let across = traction[0] * normal[0] + traction[1] * normal[1];
        let magnitude = traction[0] * traction[0] + traction[1] * traction[1];
        if normal == [0.0, 0.0] {
            return self.along * magnitude;
        }
        let across_mixity = if across > 0.0 { self.front } else { self.rear };
        across_mixity * across * across + self.along * (magnitude - across * across).max(0.0)
    }
}

/// The unit outward normal of the contact's edge at element `index` of `grid`: the sum of
/// the directions to its open face neighbours, normalised; [0, 0] where it has none, or
/// where they cancel. Beyond a free grid's border counts as open.
pub(super) fn edge_normal(grid: &Grid, contact: &[bool], index: usize) -> [f64; 2] {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (row, column) = (index / nx, index % nx);
    let periodic = grid.boundary() == Boundary::Periodic;
    let open = |row: Option<usize>, column: Option<usize>| match (row, column) {
        (Some(r), Some(c)) if r < ny && c < nx => !contact[r * nx + c],
        _ => !periodic,
    };
    let wrap = |value: usize, step: isize, n: usize| {
        let moved = value as isize + step;
        if periodic {
            Some(moved.rem_euclid(n as isize) as usize)
        } else {
            usize::try_from(moved).ok()
        }
    };
    let mut normal = [0.0f64; 2];
    for (step_row, step_column) in [(0isize, 1isize), (0, -1), (1, 0), (-1, 0)] {
        if open(wrap(row, step_row, ny), wrap(column, step_column, nx)) {
            normal[0] += step_column as f64;
            normal[1] += step_row as f64;
        }
    }
    let length = normal[0].hypot(normal[1]);
    if length == 0.0 {
        return [0.0, 0.0];
    }
    [normal[0] / length, normal[1] / length]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The normal of a disc's edge points away from its centre on the axes, along a
    /// diagonal at a corner step, and is zero inside and on a one-element strip.
    #[test]
    fn edge_normals_of_a_disc_and_a_strip() {
        let grid = Grid::new(9, 9.0, Boundary::Free).unwrap();
        let disc: Vec<bool> = (0..81)
            .map(|k| {
                let (i, j) = ((k / 9) as f64 - 4.0, (k % 9) as f64 - 4.0);
                i * i + j * j <= 9.0
            })
            .collect();
        assert_eq!(edge_normal(&grid, &disc, 4 * 9 + 7), [1.0, 0.0]);
        assert_eq!(edge_normal(&grid, &disc, 4 * 9 + 1), [-1.0, 0.0]);
        assert_eq!(edge_normal(&grid, &disc, 7 * 9 + 4), [0.0, 1.0]);
        assert_eq!(edge_normal(&grid, &disc, 4 * 9 + 4), [0.0, 0.0]);
        let diagonal = edge_normal(&grid, &disc, 2 * 9 + 2);
        let half = std::f64::consts::FRAC_1_SQRT_2;
        assert!(
            (diagonal[0] + half).abs() < 1e-15 && (diagonal[1] + half).abs() < 1e-15,
            "{diagonal:?}"
        );
        let strip: Vec<bool> = (0..81).map(|k| k % 9 == 4).collect();
        assert_eq!(edge_normal(&grid, &strip, 4 * 9 + 4), [0.0, 0.0]);
        // On a periodic grid a column at the border sees the last column as its neighbour.
        let periodic = Grid::new(9, 9.0, Boundary::Periodic).unwrap();
        let wrapped: Vec<bool> = (0..81).map(|k| k % 9 != 8).collect();
        assert_eq!(edge_normal(&periodic, &wrapped, 4 * 9), [-1.0, 0.0]);
        assert_eq!(edge_normal(&grid, &wrapped, 4 * 9), [-1.0, 0.0]);
    }

    /// Equal mixities count m·|q|² whatever the edge's direction; the mode II and III
    /// parts add up to |q|² at any angle.
    #[test]
    fn equal_mixities_count_the_whole_shear() {
        let mixity = ModeMixity::uniform(0.7);
        for angle in [0.0f64, 0.3, 1.2, 2.5, -2.0] {
            let normal = [angle.cos(), angle.sin()];
            let counted = mixity.counted_square([1.5, -0.5], normal);
            assert!((counted - 0.7 * 2.5).abs() < 1e-14, "{angle}: {counted}");
        }
        assert!(mixity.is_uniform() && mixity.weakens());
        assert!(!ModeMixity::default().weakens());
    }
}
