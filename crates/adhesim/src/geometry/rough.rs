use super::{GeometryError, Profile, Sphere};
use crate::grid::{Boundary, Grid};

/// The smooth shape under the roughness of a [`RoughProfile`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RoughBase {
    /// An infinite flat plane (`rough_flat`): the contact is the roughness alone.
    Flat,
    /// A paraboloid (`rough_sphere`).
    Sphere(Sphere),
}

impl RoughBase {
    #[inline]
    fn height(&self, x: f64, y: f64) -> f64 {
        match self {
            Self::Flat => 0.0,
            Self::Sphere(sphere) => sphere.height(x, y),
        }
    }
    #[inline]
    fn slope_x(&self, x: f64, y: f64) -> f64 {
        match self {
            Self::Flat => 0.0,
            Self::Sphere(sphere) => sphere.slope_x(x, y),
        }
    }
}

/// A rough indenter: a smooth base shape (plane or paraboloid) carrying a surface height
/// map h, e.g. a random self-affine surface (`crate::surface::SelfAffine`) — the
/// `rough_flat` and `rough_sphere` indenters of multi-asperity contact studies (Persson
/// 2001, *J. Chem. Phys.* 115, 3840, doi:10.1063/1.1388626; Pastewka & Robbins 2014,
/// *PNAS* 111, 3298, doi:10.1073/pnas.1320846111).
///
/// ## Sign convention (settled here once)
/// h is a height of the indenter's surface *towards the half-space*: its peaks touch
/// first. The indenter profile (the gap to the undeformed half-space at zero depth) is
///
/// z(x, y) = base(x, y) − h(x, y) − z_min,   z_min = min over the samples of (base − h),
///
/// so z ≥ 0 at every sample and z = 0 at the first contact point: the sample where
/// h − base is largest (for `rough_flat`, the highest asperity). Indentation depths are
/// therefore counted from first contact, not from the paraboloid's apex (unlike
/// [`WavySphere`](super::WavySphere), whose waviness has a known mean plane).
///
/// ## Sampling
/// The map holds one height per element of a [`Grid`], sample (row i, column j) at the
/// element centre ((j − Nx/2)·Δx, (i − Ny/2)·Δy), the grid's own convention (the origin
/// is the centre of element (Ny/2, Nx/2)). This differs by half an element from
/// [`Topography`](super::Topography), whose map centre (the middle of its samples) is on
/// the axis; a `RoughProfile` therefore reproduces the samples exactly at the element
/// centres of its grid with the axis at the origin ([`Profile::fill_heights`] with offset
/// (0, 0) uses no interpolation). Between samples h is bilinear; beyond the map it is
/// continued periodically when the map's grid is periodic, and with its edge value
/// otherwise (only reached when the indenter is moved sideways).
#[derive(Debug, Clone, PartialEq)]
pub struct RoughProfile {
    base: RoughBase,
    roughness: Vec<f64>,
    /// Samples along x and y (the grid's Nx, Ny).
    counts: (usize, usize),
    /// Sample spacings Δx, Δy.
    spacing: (f64, f64),
    periodic: bool,
    lowest: f64,
    highest_roughness: f64,
}

impl RoughProfile {
    /// A base shape carrying the height map `roughness` (row-major, one value per element
    /// of `grid`, peaks positive: see the type's sign convention).
    pub fn new(base: RoughBase, roughness: Vec<f64>, grid: &Grid) -> Result<Self, GeometryError> {
        if roughness.len() != grid.len() {
            return Err(GeometryError::Topography(format!(
                "roughness map has {} values, the grid has {} elements ({}×{})",
                roughness.len(),
                grid.len(),
                grid.nx(),
                grid.ny()
            )));
        }
        if let Some(bad) = roughness.iter().position(|h| !h.is_finite()) {
            return Err(GeometryError::Topography(format!(
                "roughness at index {bad} (row {}, column {}) is not finite ({})",
                bad / grid.nx(),
                bad % grid.nx(),
                roughness[bad]
            )));
        }
        let lowest = roughness
            .iter()
            .enumerate()
            .map(|(k, h)| {
                let (x, y) = grid.centre(k);
                base.height(x, y) - h
            })
            .fold(f64::INFINITY, f64::min);
        let highest_roughness = roughness.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Ok(Self {
            base,
            roughness,
            counts: (grid.nx(), grid.ny()),
            spacing: (grid.dx(), grid.dy()),
            periodic: grid.boundary() == Boundary::Periodic,
            lowest,
            highest_roughness,
        })
    }

    /// `rough_sphere`: a paraboloid of radius `radius` carrying `roughness`.
    pub fn rough_sphere(radius: f64, roughness: Vec<f64>, grid: &Grid) -> Result<Self, GeometryError> {
        Self::new(RoughBase::Sphere(Sphere::new(radius)?), roughness, grid)
    }

    /// `rough_flat`: a plane carrying `roughness`; first contact at its highest asperity.
    pub fn rough_flat(roughness: Vec<f64>, grid: &Grid) -> Result<Self, GeometryError> {
        Self::new(RoughBase::Flat, roughness, grid)
    }

    /// The base shape.
    pub fn base(&self) -> &RoughBase {
        &self.base
    }

    /// The roughness samples h (row-major, as given).
    pub fn roughness(&self) -> &[f64] {
        &self.roughness
    }

    /// z_min = min over the samples of (base − h): the shift that puts first contact at z = 0.
    pub fn first_contact_offset(&self) -> f64 {
        self.lowest
    }

    /// Sample index along an axis of `n` samples for a fractional index: wrapped
    /// (periodic) or clamped.
    #[inline]
    fn sample_index(&self, index: isize, n: usize) -> usize {
        let n = n as isize;
        if self.periodic {
            index.rem_euclid(n) as usize
        } else {
            index.clamp(0, n - 1) as usize
        }
    }

    /// Cell (row0, column0) and fractions of a point given in fractional sample indices.
    #[inline]
    fn cell(&self, column: f64, row: f64) -> (usize, usize, usize, usize, f64, f64) {
        let (c, r) = (column.floor(), row.floor());
        let (fc, fr) = (column - c, row - r);
        let (c, r) = (c as isize, r as isize);
        let (nx, ny) = self.counts;
        let (c0, c1) = (self.sample_index(c, nx), self.sample_index(c + 1, nx));
        let (r0, r1) = (self.sample_index(r, ny), self.sample_index(r + 1, ny));
        (r0, r1, c0, c1, fr, fc)
    }

    /// Bilinear h at fractional sample indices (column, row); exactly the sample at
    /// integer indices.
    #[inline]
    fn roughness_at(&self, column: f64, row: f64) -> f64 {
        let (r0, r1, c0, c1, fr, fc) = self.cell(column, row);
        let at = |r: usize, c: usize| self.roughness[r * self.counts.0 + c];
        if fr == 0.0 && fc == 0.0 {
            return at(r0, c0);
        }
        (1.0 - fr) * ((1.0 - fc) * at(r0, c0) + fc * at(r0, c1)) + fr * ((1.0 - fc) * at(r1, c0) + fc * at(r1, c1))
    }

    /// Fractional sample indices of the point (x, y) relative to the axis.
    #[inline]
    fn indices(&self, x: f64, y: f64) -> (f64, f64) {
        let (nx, ny) = self.counts;
        (
            x / self.spacing.0 + (nx / 2) as f64,
            y / self.spacing.1 + (ny / 2) as f64,
        )
    }
}

impl Profile for RoughProfile {
    fn height(&self, x: f64, y: f64) -> f64 {
        let (column, row) = self.indices(x, y);
        self.base.height(x, y) - self.roughness_at(column, row) - self.lowest
    }

    fn reach(&self, depth: f64) -> Option<f64> {
        match self.base {
            // z ≤ d needs base ≤ d + z_min + max h.
            RoughBase::Sphere(sphere) => sphere.reach(depth + self.lowest + self.highest_roughness),
            RoughBase::Flat => None,
        }
    }

    /// On the map's own lattice (same Nx, Ny, Δx and Δy) the roughness is looked up by element index
    /// shifted by offset/Δ, so that with the axis at the origin the samples are used
    /// exactly; on any other grid, the analytic height at each element centre.
    fn fill_heights(&self, grid: &Grid, offset: (f64, f64), heights: &mut [f64]) {
        assert_eq!(heights.len(), grid.len(), "heights buffer does not match the grid");
        if (grid.nx(), grid.ny()) != self.counts || (grid.dx(), grid.dy()) != self.spacing {
            for (k, height) in heights.iter_mut().enumerate() {
                let (x, y) = grid.centre(k);
                *height = self.height(x - offset.0, y - offset.1);
            }
            return;
        }
        let (shift_column, shift_row) = (offset.0 / self.spacing.0, offset.1 / self.spacing.1);
        for (k, height) in heights.iter_mut().enumerate() {
            let (x, y) = grid.centre(k);
            let (row, column) = ((k / self.counts.0) as f64, (k % self.counts.0) as f64);
            let roughness = self.roughness_at(column - shift_column, row - shift_row);
            *height = self.base.height(x - offset.0, y - offset.1) - roughness - self.lowest;
        }
    }

    fn radius_of_curvature(&self) -> Option<f64> {
        match self.base {
            RoughBase::Sphere(sphere) => Some(sphere.radius()),
            RoughBase::Flat => None,
        }
    }

    /// Base slope minus ∂h/∂x of the bilinear map: the cell's slope inside a cell, the
    /// mean of the two neighbouring cells' slopes (a central difference) on a sample column.
    fn slope_x(&self, x: f64, y: f64) -> f64 {
        let (column, row) = self.indices(x, y);
        let cell_slope = |column: f64| {
            let (r0, r1, c0, c1, fr, _) = self.cell(column, row);
            let at = |r: usize, c: usize| self.roughness[r * self.counts.0 + c];
            ((1.0 - fr) * (at(r0, c1) - at(r0, c0)) + fr * (at(r1, c1) - at(r1, c0))) / self.spacing.0
        };
        let roughness_slope = if column.fract() == 0.0 {
            0.5 * (cell_slope(column) + cell_slope(column - 1.0))
        } else {
            cell_slope(column)
        };
        self.base.slope_x(x, y) - roughness_slope
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_between_samples_and_continued_beyond_the_map() {
        let free = Grid::new(4, 4.0, Boundary::Free).unwrap();
        // h = column index: a ramp of slope 1 in x (sample j at x = j − 2)
        let ramp: Vec<f64> = (0..16).map(|k| (k % 4) as f64).collect();
        let flat = RoughProfile::rough_flat(ramp.clone(), &free).unwrap();
        // z = max h − h = 3 − h
        assert_eq!(flat.height(0.0, 0.0), 1.0);
        assert!((flat.height(0.25, 0.3) - 0.75).abs() < 1e-15);
        assert!((flat.slope_x(0.25, 0.3) + 1.0).abs() < 1e-15);
        assert!((flat.slope_x(0.0, 0.0) + 1.0).abs() < 1e-15);
        // clamped beyond the edge of a free map
        assert_eq!(flat.height(10.0, 0.0), 0.0);
        assert_eq!(flat.height(-10.0, 0.0), 3.0);
        // wrapped on a periodic one: between the last sample (h = 3) and the first (h = 0)
        let periodic = Grid::new(4, 4.0, Boundary::Periodic).unwrap();
        let wrapped = RoughProfile::rough_flat(ramp, &periodic).unwrap();
        assert!((wrapped.height(1.5, 0.0) - 1.5).abs() < 1e-15);
        assert!((wrapped.height(1.5 - 4.0, 1.0) - 1.5).abs() < 1e-15);
    }

    #[test]
    fn rejects_maps_that_do_not_fit() {
        let grid = Grid::new(4, 1.0, Boundary::Free).unwrap();
        let error = RoughProfile::rough_flat(vec![0.0; 15], &grid).unwrap_err();
        assert!(error.to_string().contains("15 values"), "{error}");
        let mut map = vec![0.0; 16];
        map[5] = f64::NAN;
        let error = RoughProfile::rough_sphere(1.0, map, &grid).unwrap_err();
        assert!(error.to_string().contains("row 1, column 1"), "{error}");
        assert!(RoughProfile::rough_sphere(-1.0, vec![0.0; 16], &grid).is_err());
    }
}
