use super::influence::{love_primitive, love_rectangle};
use super::spectral::SpectralConvolution;
use super::ElasticOperator;
use crate::grid::{Boundary, Grid};
use crate::material::ElasticMaterial;
use rayon::prelude::*;
use std::ops::Range;

/// K(±lΔx, ±mΔy) for 0 ≤ l < Nx, 0 ≤ m < Ny, bit for bit what [`love_rectangle`] gives at
/// each signed offset, from Love's primitive evaluated once per distinct corner pair
/// ([`PrimitiveLattice`]). Φ is odd in each argument, bitwise ([`love_primitive`]), so each
/// of the four images of an offset is the same four values with signs, summed in the order
/// `love_rectangle` sums them. Nothing of size Nx·Ny is stored but the lattice: the padded
/// kernel is filled straight from [`Self::fill_row`].
struct LoveImages {
    lattice: PrimitiveLattice,
    /// πE*.
    scale: f64,
}

impl LoveImages {
    /// For `counts` = (Nx, Ny) elements of sides `spacing` = (Δx, Δy).
    fn new(counts: (usize, usize), spacing: (f64, f64), modulus: f64) -> Self {
        Self {
            lattice: PrimitiveLattice::new(counts, spacing),
            scale: std::f64::consts::PI * modulus,
        }
    }

    /// K at offset (σ_l·lΔx, σ_m·mΔy), sign index 0 for + and 1 for − (the reference
    /// [`Self::fill_row`] is tested against, entry by entry).
    #[cfg(test)]
    fn value(&self, m: usize, sign_m: usize, l: usize, sign_l: usize) -> f64 {
        // Φ(σ_l·lΔx ± a, σ_m·mΔy ± b): for σ = −1, ±a turns into ∓a and the sign comes out.
        let term = |dx: usize, dy: usize| {
            let value = self.lattice.value(l, dx ^ sign_l, m, dy ^ sign_m);
            if sign_l ^ sign_m == 1 {
                -value
            } else {
                value
            }
        };
        (term(0, 0) - term(0, 1) - term(1, 0) + term(1, 1)) / self.scale
    }

    /// Row (σ_m·mΔy) of the 2Nx-periodic padded kernel: entry j < Nx is offset jΔx, entry
    /// Nx zero, entry j > Nx offset −(2Nx − j)Δx; the bits of [`Self::value`], read from
    /// the two lattice rows of mΔy ± b.
    fn fill_row(&self, m: usize, sign_m: usize, row: &mut [f64]) {
        let lattice = &self.lattice;
        let n = lattice.x_index.len();
        let lattice_row = |dy: usize| {
            let start = lattice.y_index[m][dy ^ sign_m] * lattice.x_count;
            &lattice.table[start..start + lattice.x_count]
        };
        let (plus, minus) = (lattice_row(0), lattice_row(1));
        let padded = row.len();
        for (j, entry) in row.iter_mut().enumerate() {
            let (l, sign_l) = match j {
                j if j < n => (j, 0),
                j if j == n => {
                    *entry = 0.0;
                    continue;
                }
                j => (padded - j, 1),
            };
            let arguments = &lattice.x_index[l];
            let (near, far) = (arguments[sign_l], arguments[1 ^ sign_l]);
            let flip = |value: f64| if sign_l ^ sign_m == 1 { -value } else { value };
            // term(dx, dy) of `value`: dx picks the l argument, dy the lattice row.
            *entry = (flip(plus[near]) - flip(minus[near]) - flip(plus[far]) + flip(minus[far])) / self.scale;
        }
    }
}

/// The distinct values of lΔ ± s for 0 ≤ l < n, sorted, and the index of each argument
/// (`[l][0]` for lΔ + s, `[l][1]` for lΔ − s).
fn corner_arguments(n: usize, delta: f64) -> (Vec<f64>, Vec<[usize; 2]>) {
    let s = 0.5 * delta;
    let argument = |l: usize, sign: usize| {
        let x = l as f64 * delta;
        if sign == 0 {
            x + s
        } else {
            x - s
        }
    };
    let mut distinct: Vec<f64> = (0..n).flat_map(|l| [argument(l, 0), argument(l, 1)]).collect();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup_by(|a, b| a.to_bits() == b.to_bits());
    let position = |value: f64| {
        distinct
            .binary_search_by(|probe| probe.total_cmp(&value))
            .expect("every argument is in the list")
    };
    let index = (0..n)
        .map(|l| [position(argument(l, 0)), position(argument(l, 1))])
        .collect();
    (distinct, index)
}

/// Love's primitive Φ at every pair of the arguments (lΔx ± a, mΔy ± b), each distinct
/// argument pair evaluated once. Where (l + 1)Δ − s and lΔ + s round to the same double
/// (always when Δ is a power of two) neighbouring elements share their corners, so the
/// offsets need about a quarter of the evaluations of a direct sum; where they differ,
/// both are kept and the values are those of a direct evaluation anyway (same arguments,
/// same bits).
struct PrimitiveLattice {
    /// Index into the distinct x arguments of lΔx + a (`[l][0]`) and lΔx − a (`[l][1]`).
    x_index: Vec<[usize; 2]>,
    /// Index into the distinct y arguments of mΔy ± b, likewise.
    y_index: Vec<[usize; 2]>,
    /// Φ(x_j, y_i), `[i * x_count + j]`, stored so that a row of the kernel reads it in
    /// order. On a square grid the two argument lists are one: Φ is then evaluated on the
    /// lower triangle and mirrored (it is symmetric bit for bit).
    table: Vec<f64>,
    x_count: usize,
}

impl PrimitiveLattice {
    fn new(counts: (usize, usize), spacing: (f64, f64)) -> Self {
        let (x_arguments, x_index) = corner_arguments(counts.0, spacing.0);
        let (y_arguments, y_index) = corner_arguments(counts.1, spacing.1);
        let (x_count, y_count) = (x_arguments.len(), y_arguments.len());
        let mut table = vec![0.0; x_count * y_count];
        let symmetric = x_arguments.len() == y_arguments.len()
            && x_arguments
                .iter()
                .zip(&y_arguments)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        table.par_chunks_mut(x_count).enumerate().for_each(|(i, row)| {
            let columns = if symmetric { i + 1 } else { x_count };
            for (j, value) in row.iter_mut().enumerate().take(columns) {
                // Φ(x, y) as `love_rectangle` evaluates it; the square's triangle keeps the
                // order it always had (the same bits: Φ is symmetric bitwise).
                *value = if symmetric {
                    love_primitive(y_arguments[i], x_arguments[j])
                } else {
                    love_primitive(x_arguments[j], y_arguments[i])
                };
            }
        });
        if symmetric {
            for i in 0..x_count {
                for j in 0..i {
                    table[j * x_count + i] = table[i * x_count + j];
                }
            }
        }
        Self {
            x_index,
            y_index,
            table,
            x_count,
        }
    }

    /// Φ(lΔx ± a, mΔy ± b), sign index 0 for + and 1 for −.
    #[cfg(test)]
    fn value(&self, l: usize, sign_l: usize, m: usize, sign_m: usize) -> f64 {
        self.table[self.y_index[m][sign_m] * self.x_count + self.x_index[l][sign_l]]
    }
}

/// Non-periodic half-space by discrete convolution and FFT (DC-FFT).
///
/// Liu, Wang & Liu (2000), "A versatile method of discrete convolution and FFT (DC-FFT)
/// for contact analyses", *Wear* 243, 101–111, doi:10.1016/S0043-1648(00)00427-0.
/// Love's exact coefficients K(lΔx, mΔy) of the rectangular element, |l| < Nx, |m| < Ny, are
/// wrapped into a 2Ny×2Nx array and the pressure is zero-padded, so the cyclic convolution
/// equals the exact linear one.
pub struct FreeOperator {
    grid: Grid,
    contact_modulus: f64,
    self_compliance: f64,
    engine: SpectralConvolution,
    /// The same kernel in single precision, for [`ElasticOperator::apply_single`]; made at
    /// the first single-precision application (a solver that only applies the operator in
    /// double precision, such as the final round after a contact-window solve, never
    /// pays for it).
    single: Option<SpectralConvolution<f32>>,
    applications: u64,
}

impl FreeOperator {
    /// Plans the transforms and computes the kernel spectrum for `grid` and `material`.
    pub fn new(grid: Grid, material: ElasticMaterial) -> Self {
        let (nx, ny) = (grid.nx(), grid.ny());
        let modulus = material.contact_modulus();
        // (|offset| in elements, sign index) for a wrapped row index; row ny of the padded
        // array is zero.
        let wrap = |i: usize| -> Option<(usize, usize)> {
            match i {
                i if i < ny => Some((i, 0)),
                i if i == ny => None,
                i => Some((2 * ny - i, 1)),
            }
        };
        let images = LoveImages::new((nx, ny), (grid.dx(), grid.dy()), modulus);
        let engine = SpectralConvolution::new((nx, ny), (2 * nx, 2 * ny), |i, row| match wrap(i) {
            Some((m, sign_m)) => images.fill_row(m, sign_m, row),
            None => row.fill(0.0),
        });
        Self {
            grid,
            contact_modulus: modulus,
            self_compliance: love_rectangle(0.0, 0.0, grid.dx(), grid.dy(), modulus),
            single: None,
            engine,
            applications: 0,
        }
    }
}

impl FreeOperator {
    fn single_engine(&mut self) -> &mut SpectralConvolution<f32> {
        let engine = &self.engine;
        self.single.get_or_insert_with(|| engine.to_single())
    }
}

impl ElasticOperator for FreeOperator {
    fn grid(&self) -> &Grid {
        &self.grid
    }
    fn contact_modulus(&self) -> f64 {
        self.contact_modulus
    }
    fn apply(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        self.engine.convolve(pressure, displacement);
        self.applications += 1;
    }
    fn apply_single(&mut self, pressure: &[f64], displacement: &mut [f64]) {
        self.single_engine().convolve(pressure, displacement);
        self.applications += 1;
    }
    fn apply_single_rows(
        &mut self,
        pressure: &[f64],
        displacement: &mut [f64],
        input_rows: Range<usize>,
        output_rows: Range<usize>,
    ) {
        self.single_engine()
            .convolve_rows(pressure, displacement, input_rows, output_rows);
        self.applications += 1;
    }
    fn self_compliance(&self) -> f64 {
        self.self_compliance
    }
    fn applications(&self) -> u64 {
        self.applications
    }
    fn window_operator(&self, side: usize) -> Option<Box<dyn ElasticOperator + Sync>> {
        let grid = &self.grid;
        if side == 0 || side > grid.nx().min(grid.ny()) {
            return None;
        }
        let size = (side as f64 * grid.dx(), side as f64 * grid.dy());
        let window = Grid::rectangular(side, side, size.0, size.1, Boundary::Free).ok()?;
        let material = ElasticMaterial::new(self.contact_modulus).ok()?;
        Some(Box::new(FreeOperator::new(window, material)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random numbers in [0, 1) (64-bit LCG, top 53 bits).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn below(&mut self, bound: usize) -> usize {
            ((self.next() * bound as f64) as usize).min(bound - 1)
        }
    }

    /// A field that is random on a random set of the rows `rows` (some elements of it
    /// zero, others −0.0 as a mask gives them) and zero (or −0.0) elsewhere.
    fn field_on_rows(random: &mut Lcg, n: usize, rows: &Range<usize>) -> Vec<f64> {
        (0..n * n)
            .map(|k| {
                let sign_of_zero = if random.next() < 0.5 { 0.0 } else { -0.0 };
                if rows.contains(&(k / n)) && random.next() < 0.7 {
                    random.next() - 0.3
                } else {
                    sign_of_zero
                }
            })
            .collect()
    }

    fn random_rows(random: &mut Lcg, n: usize) -> Range<usize> {
        let start = random.below(n);
        start..start + 1 + random.below(n - start)
    }

    #[test]
    fn row_windows_give_the_bits_of_the_full_transform() {
        // Row windows (docs/history.md §2026-11-23: row-window transforms): inside the
        // output window the row-pruned convolution must equal the full one bit for bit (f64
        // and f32, free and periodic), and leave the other output rows untouched. Tolerance:
        // none (to_bits).
        let mut random = Lcg(0x5eed_0014);
        let material = ElasticMaterial::new(1.7).unwrap();
        for n in [16, 17, 24, 31, 32, 48, 64] {
            let free = Grid::new(n, 1.0, crate::grid::Boundary::Free).unwrap();
            let periodic = Grid::new(n, 1.0, crate::grid::Boundary::Periodic).unwrap();
            let mut free_operator = FreeOperator::new(free, material);
            let mut periodic_operator = super::super::PeriodicOperator::new(
                periodic,
                material,
                super::super::PeriodicKernel::ElementConsistent,
            );
            for case in 0..6 {
                let input_rows = if case == 0 { 0..n } else { random_rows(&mut random, n) };
                let output_rows = if case == 1 { 0..n } else { random_rows(&mut random, n) };
                let input = field_on_rows(&mut random, n, &input_rows);
                let sentinel = vec![f64::from_bits(0x7ff8_dead_beef_0001); n * n];
                let check = |full: &[f64], windowed: &[f64], what: &str| {
                    for k in 0..n * n {
                        let expected = if output_rows.contains(&(k / n)) {
                            full[k]
                        } else {
                            sentinel[k]
                        };
                        assert_eq!(
                            windowed[k].to_bits(),
                            expected.to_bits(),
                            "{what} n = {n}, rows {input_rows:?} -> {output_rows:?}, element {k}"
                        );
                    }
                };
                // A dense field applied just before the windowed call leaves spectra in
                // every buffer row: the skipped rows must not pick them up.
                let dense = field_on_rows(&mut random, n, &(0..n));
                let (mut full, mut windowed, mut scratch) = (vec![0.0; n * n], sentinel.clone(), vec![0.0; n * n]);
                free_operator.engine.convolve(&input, &mut full);
                free_operator.engine.convolve(&dense, &mut scratch);
                free_operator
                    .engine
                    .convolve_rows(&input, &mut windowed, input_rows.clone(), output_rows.clone());
                check(&full, &windowed, "free f64");
                let operators: [&mut dyn ElasticOperator; 2] = [&mut free_operator, &mut periodic_operator];
                for operator in operators {
                    let (mut full, mut windowed) = (vec![0.0; n * n], sentinel.clone());
                    operator.apply_single(&input, &mut full);
                    operator.apply_single(&dense, &mut scratch);
                    operator.apply_single_rows(&input, &mut windowed, input_rows.clone(), output_rows.clone());
                    check(&full, &windowed, "f32");
                    assert!(full.iter().any(|&u| u != 0.0), "the case must not be trivial");
                }
            }
        }
    }

    #[test]
    fn a_window_operator_is_the_restriction_of_the_full_one() {
        // A field inside a side × side window (placed off the grid's corner): the window's
        // own operator gives the full operator's displacement on the window. Tolerance
        // 1e-12 of max|u|: the same Love coefficients (a window's element size is side·Δ/side,
        // equal to Δ up to one rounding) through transforms of another length.
        let mut random = Lcg(0x5eed_0044);
        let (n, side, (row, column)) = (48, 20, (9, 23));
        let grid = Grid::rectangular(n, n, 1.3, 1.3, Boundary::Free).unwrap();
        let mut full = FreeOperator::new(grid, ElasticMaterial::new(2.1).unwrap());
        let mut window = full.window_operator(side).expect("a free operator has windows");
        assert!(full.window_operator(n + 1).is_none(), "no window larger than the grid");
        let local: Vec<f64> = (0..side * side).map(|_| random.next() - 0.4).collect();
        let mut field = vec![0.0; n * n];
        for i in 0..side {
            for j in 0..side {
                field[(row + i) * n + column + j] = local[i * side + j];
            }
        }
        let (mut expected, mut windowed) = (vec![0.0; n * n], vec![0.0; side * side]);
        full.apply(&field, &mut expected);
        window.apply(&local, &mut windowed);
        let scale = expected.iter().fold(0.0f64, |m, u| m.max(u.abs()));
        for i in 0..side {
            for j in 0..side {
                let (a, b) = (windowed[i * side + j], expected[(row + i) * n + column + j]);
                assert!((a - b).abs() <= 1e-12 * scale, "({i}, {j}): {a} against {b}");
            }
        }
        let (own, whole) = (window.self_compliance(), full.self_compliance());
        assert!((own - whole).abs() <= 1e-14 * whole, "{own} against {whole}");
    }

    #[test]
    fn octant_images_have_the_bits_of_direct_evaluation() {
        // Every signed offset of the padded kernel, against a direct evaluation: for element
        // sizes whose corner arguments round differently from one element to the next
        // (0.013, 0.3/64) and for a power of two, where neighbours share their corners.
        // Rectangles: a different count and spacing along y (docs/validation.md §12).
        let cases = [
            (12, 12, 0.013, 0.013, 2.5),
            (10, 10, 0.3 / 64.0, 0.3 / 64.0, 1.0),
            (16, 16, 1.0 / 64.0, 1.0 / 64.0, 0.7),
            (12, 7, 0.013, 0.021, 1.3),
            (6, 11, 1.0 / 64.0, 1.0 / 16.0, 0.9),
        ];
        for (n, ny, delta, delta_y, modulus) in cases {
            let images = LoveImages::new((n, ny), (delta, delta_y), modulus);
            for m in -(ny as i64 - 1)..ny as i64 {
                for l in -(n as i64 - 1)..n as i64 {
                    let direct = love_rectangle(l as f64 * delta, m as f64 * delta_y, delta, delta_y, modulus);
                    let (sign_m, sign_l) = (usize::from(m < 0), usize::from(l < 0));
                    let tabulated = images.value(m.unsigned_abs() as usize, sign_m, l.unsigned_abs() as usize, sign_l);
                    assert_eq!(tabulated.to_bits(), direct.to_bits(), "n = {n}, offset ({l}, {m})");
                }
            }
            // The rows of the padded kernel as `FreeOperator::new` fills them.
            let mut row = vec![f64::NAN; 2 * n];
            for (m, sign_m) in (0..ny).map(|m| (m, 0)).chain((1..ny).map(|m| (m, 1))) {
                images.fill_row(m, sign_m, &mut row);
                for (j, &entry) in row.iter().enumerate() {
                    let offset = match j {
                        j if j < n => j as f64,
                        j if j == n => {
                            assert_eq!(entry.to_bits(), 0f64.to_bits(), "row {m}, column {n}");
                            continue;
                        }
                        j => -((2 * n - j) as f64),
                    };
                    let y = if sign_m == 1 { -(m as f64) } else { m as f64 };
                    let direct = love_rectangle(offset * delta, y * delta_y, delta, delta_y, modulus);
                    assert_eq!(
                        entry.to_bits(),
                        direct.to_bits(),
                        "n = {n}, row ({m}, {sign_m}), column {j}"
                    );
                }
            }
            let lattice = PrimitiveLattice::new((n, ny), (delta, delta_y));
            let arguments = lattice.x_index.iter().flatten().max().unwrap() + 1;
            if delta == 1.0 / 64.0 && n == ny {
                assert_eq!(arguments, n + 1, "a power-of-two size shares every corner");
            }
        }
    }
}
