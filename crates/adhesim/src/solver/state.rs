use crate::grid::Grid;

/// Fields of a contact configuration; also the warm start of the next solve.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactState {
    /// Pressure per element (> 0 compressive).
    pub pressure: Vec<f64>,
    /// Normal surface displacement per element (> 0 into the body), u = K p.
    pub displacement: Vec<f64>,
    /// Contact set C.
    #[cfg_attr(feature = "serde", serde(with = "crate::bit_string"))]
    pub contact: Vec<bool>,
}

impl ContactState {
    /// No contact, no load.
    pub fn new(grid: &Grid) -> Self {
        Self {
            pressure: vec![0.0; grid.len()],
            displacement: vec![0.0; grid.len()],
            contact: vec![false; grid.len()],
        }
    }

    /// Δ²Σp.
    pub fn force(&self, element_area: f64) -> f64 {
        element_area * self.pressure.iter().sum::<f64>()
    }

    /// Number of elements in contact.
    pub fn contact_elements(&self) -> usize {
        self.contact.iter().filter(|&&c| c).count()
    }

    /// Largest distance from `centre` to the centre of an element in contact (the
    /// paper's contact radius, Sect. 2.3), or 0 without contact.
    pub fn contact_radius(&self, grid: &Grid, centre: (f64, f64)) -> f64 {
        self.contact
            .iter()
            .enumerate()
            .filter(|(_, &c)| c)
            .map(|(k, _)| {
                let (x, y) = grid.centre(k);
                (x - centre.0).hypot(y - centre.1)
            })
            .fold(0.0, f64::max)
    }

    /// Largest |y| over the contact set: the half-width perpendicular to motion in x.
    pub fn half_width(&self, grid: &Grid) -> f64 {
        self.contact
            .iter()
            .enumerate()
            .filter(|(_, &c)| c)
            .map(|(k, _)| grid.centre(k).1.abs())
            .fold(0.0, f64::max)
    }

    /// (attached, detached): elements in contact now but not in `before`, and the reverse.
    pub fn changes_from(&self, before: &[bool]) -> (usize, usize) {
        let (mut attached, mut detached) = (0, 0);
        for (&was, &is) in before.iter().zip(&self.contact) {
            match (was, is) {
                (false, true) => attached += 1,
                (true, false) => detached += 1,
                _ => {}
            }
        }
        (attached, detached)
    }

    /// True when an element in contact lies on the border of the grid.
    pub fn touches_border(&self, grid: &Grid) -> bool {
        self.contact.iter().enumerate().any(|(k, &c)| c && grid.is_border(k))
    }
}
