use super::influence::{love_coefficient, love_primitive};
use super::spectral::SpectralConvolution;
use super::ElasticOperator;
use crate::grid::Grid;
use crate::material::ElasticMaterial;
use rayon::prelude::*;
use std::ops::Range;

/// K(±lΔ, ±mΔ) for 0 ≤ m, l < N, bit for bit what [`love_coefficient`] gives at each
/// signed offset, from Love's primitive evaluated once per distinct corner pair
/// ([`PrimitiveLattice`]). Φ is odd in each argument and symmetric under exchange, bitwise
/// ([`love_primitive`]), so each of the eight images of an offset is the same four values
/// with signs, summed in the order `love_coefficient` sums them. Nothing of size N² is
/// stored but the lattice: the padded kernel is filled straight from [`Self::value`].
struct LoveImages {
    lattice: PrimitiveLattice,
    /// πE*.
    scale: f64,
}

impl LoveImages {
    fn new(n: usize, delta: f64, modulus: f64) -> Self {
        Self {
            lattice: PrimitiveLattice::new(n, delta, 0.5 * delta),
            scale: std::f64::consts::PI * modulus,
        }
    }

    /// K at offset (σ_l·lΔ, σ_m·mΔ), sign index 0 for + and 1 for − (the reference
    /// [`Self::fill_row`] is tested against, entry by entry).
    #[cfg(test)]
    fn value(&self, m: usize, sign_m: usize, l: usize, sign_l: usize) -> f64 {
        // Φ(σ_l·lΔ ± s, σ_m·mΔ ± s): for σ = −1, ±s turns into ∓s and the sign comes out.
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

    /// Row (σ_m·mΔ) of the 2N-periodic padded kernel: entry j < N is offset jΔ, entry N
    /// zero, entry j > N offset −(2N − j)Δ; the bits of [`Self::value`], read from the two
    /// lattice rows of mΔ ± s.
    fn fill_row(&self, m: usize, sign_m: usize, row: &mut [f64]) {
        let n = self.lattice.argument_index.len();
        let lattice = &self.lattice;
        let lattice_row = |dy: usize| {
            let start = lattice.argument_index[m][dy ^ sign_m] * lattice.count;
            &lattice.table[start..start + lattice.count]
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
            let arguments = &lattice.argument_index[l];
            let (near, far) = (arguments[sign_l], arguments[1 ^ sign_l]);
            let flip = |value: f64| if sign_l ^ sign_m == 1 { -value } else { value };
            // term(dx, dy) of `value`: dx picks the l argument, dy the lattice row.
            *entry = (flip(plus[near]) - flip(minus[near]) - flip(plus[far]) + flip(minus[far])) / self.scale;
        }
    }
}

/// Love's primitive Φ at every pair of the arguments lΔ ± s (0 ≤ l < N), each distinct
/// argument pair evaluated once. Where (l + 1)Δ − s and lΔ + s round to the same double
/// (always when Δ is a power of two) neighbouring elements share their corners, so the
/// N² offsets need about N²/2 evaluations instead of 2N²; where they differ, both are
/// kept and the values are those of a direct evaluation anyway (same arguments, same bits).
struct PrimitiveLattice {
    /// Index into the distinct arguments of lΔ + s (`[l][0]`) and lΔ − s (`[l][1]`).
    argument_index: Vec<[usize; 2]>,
    /// Φ(a_i, a_j), `[i * count + j]`: evaluated on the lower triangle and mirrored (Φ is
    /// symmetric bit for bit), stored square so that a row of the kernel reads it in order.
    table: Vec<f64>,
    count: usize,
}

impl PrimitiveLattice {
    fn new(n: usize, delta: f64, s: f64) -> Self {
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
        let argument_index = (0..n)
            .map(|l| [position(argument(l, 0)), position(argument(l, 1))])
            .collect();
        let count = distinct.len();
        let mut table = vec![0.0; count * count];
        table.par_chunks_mut(count).enumerate().for_each(|(i, row)| {
            for (j, value) in row.iter_mut().enumerate().take(i + 1) {
                *value = love_primitive(distinct[i], distinct[j]);
            }
        });
        for i in 0..count {
            for j in 0..i {
                table[j * count + i] = table[i * count + j];
            }
        }
        Self {
            argument_index,
            table,
            count,
        }
    }

    /// Φ(lΔ ± s, mΔ ± s), sign index 0 for + and 1 for −.
    #[cfg(test)]
    fn value(&self, l: usize, sign_l: usize, m: usize, sign_m: usize) -> f64 {
        self.table[self.argument_index[m][sign_m] * self.count + self.argument_index[l][sign_l]]
    }
}

/// Non-periodic half-space by discrete convolution and FFT (DC-FFT).
///
/// Liu, Wang & Liu (2000), "A versatile method of discrete convolution and FFT (DC-FFT)
/// for contact analyses", *Wear* 243, 101–111, doi:10.1016/S0043-1648(00)00427-0.
/// Love's exact coefficients K(mΔ, nΔ), |m|,|n| < N, are wrapped into a 2N×2N array and
/// the pressure is zero-padded, so the cyclic convolution equals the exact linear one.
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
        let n = grid.n();
        let padded = 2 * n;
        let delta = grid.element_size();
        let modulus = material.contact_modulus();
        // (|offset| in elements, sign index) for a wrapped index; row n of the padded array
        // is zero.
        let wrap = |i: usize| -> Option<(usize, usize)> {
            match i {
                i if i < n => Some((i, 0)),
                i if i == n => None,
                i => Some((padded - i, 1)),
            }
        };
        let images = LoveImages::new(n, delta, modulus);
        let engine = SpectralConvolution::new(n, padded, |i, row| match wrap(i) {
            Some((m, sign_m)) => images.fill_row(m, sign_m, row),
            None => row.fill(0.0),
        });
        Self {
            grid,
            contact_modulus: modulus,
            self_compliance: love_coefficient(0.0, 0.0, delta, modulus),
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
        // Issue #14 item 5: inside the output window the row-pruned convolution must equal
        // the full one bit for bit (f64 and f32, free and periodic), and leave the other
        // output rows untouched. Tolerance: none (to_bits).
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
    fn octant_images_have_the_bits_of_direct_evaluation() {
        // Every signed offset of the padded kernel, against a direct evaluation: for element
        // sizes whose corner arguments round differently from one element to the next
        // (0.013, 0.3/64) and for a power of two, where neighbours share their corners.
        for (n, delta, modulus) in [(12, 0.013, 2.5), (10, 0.3 / 64.0, 1.0), (16, 1.0 / 64.0, 0.7)] {
            let images = LoveImages::new(n, delta, modulus);
            for m in -(n as i64 - 1)..n as i64 {
                for l in -(n as i64 - 1)..n as i64 {
                    let direct = love_coefficient(l as f64 * delta, m as f64 * delta, delta, modulus);
                    let (sign_m, sign_l) = (usize::from(m < 0), usize::from(l < 0));
                    let tabulated = images.value(m.unsigned_abs() as usize, sign_m, l.unsigned_abs() as usize, sign_l);
                    assert_eq!(tabulated.to_bits(), direct.to_bits(), "n = {n}, offset ({l}, {m})");
                }
            }
            // The rows of the padded kernel as `FreeOperator::new` fills them.
            let mut row = vec![f64::NAN; 2 * n];
            for (m, sign_m) in (0..n).map(|m| (m, 0)).chain((1..n).map(|m| (m, 1))) {
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
                    let direct = love_coefficient(offset * delta, y * delta, delta, modulus);
                    assert_eq!(
                        entry.to_bits(),
                        direct.to_bits(),
                        "n = {n}, row ({m}, {sign_m}), column {j}"
                    );
                }
            }
            let lattice = PrimitiveLattice::new(n, delta, 0.5 * delta);
            let arguments = lattice.argument_index.iter().flatten().max().unwrap() + 1;
            if delta == 1.0 / 64.0 {
                assert_eq!(arguments, n + 1, "a power-of-two size shares every corner");
            }
        }
    }
}
