//! Real-to-complex 2-D convolution with a real, even kernel spectrum.
//!
//! Shared engine of the free (zero-padded) and periodic operators. Only the rows that
//! carry data are transformed forward and only the rows that are kept are transformed
//! back: for the free operator half of the 2N row transforms are skipped in each
//! direction, which puts one application below the cost of a bare 2N×2N FFT pair.
//! Plans and buffers are made once; `convolve` does not allocate. Work is split into a
//! fixed number of row and column blocks run by rayon; every row or column transform is
//! independent of the split, so results are bit-identical for any thread count.
//!
//! The engine is generic over its working precision: fields are f64 at the interface and
//! converted on the way in and out, so a single-precision engine (half the memory traffic,
//! twice the SIMD width) can stand in where its ~1e-7 relative error is harmless.

use super::planner::{self, Planned};
use num_complex::Complex;
use rayon::prelude::*;
use realfft::{ComplexToReal, RealToComplex};
use rustfft::{Fft, FftNum};
use std::ops::Range;
use std::sync::Arc;

mod pair;

/// Working precision of a [`SpectralConvolution`].
pub(crate) trait Precision: FftNum + Planned + Default {
    /// Rounds an f64 to this precision.
    fn narrow(value: f64) -> Self;
    /// Widens back to f64 (exact).
    fn widen(self) -> f64;
}

impl Precision for f64 {
    fn narrow(value: f64) -> Self {
        value
    }
    fn widen(self) -> f64 {
        self
    }
}

impl Precision for f32 {
    fn narrow(value: f64) -> Self {
        value as f32
    }
    fn widen(self) -> f64 {
        f64::from(self)
    }
}

pub(crate) struct SpectralConvolution<T: Precision = f64> {
    /// Data columns (row length) of input and output (Nx).
    nx: usize,
    /// Data rows of input and output (Ny).
    ny: usize,
    /// Padded row length (2Nx free, Nx periodic).
    padded_x: usize,
    /// Padded column length (2Ny free, Ny periodic).
    padded_y: usize,
    /// Complex columns after the row transform: padded_x/2 + 1.
    spectrum_columns: usize,
    /// Kernel spectrum, real, transposed: `[column * padded_y + row]`, normalised.
    kernel: Vec<T>,
    forward_rows: Arc<dyn RealToComplex<T>>,
    inverse_rows: Arc<dyn ComplexToReal<T>>,
    forward_columns: Arc<dyn Fft<T>>,
    inverse_columns: Arc<dyn Fft<T>>,
    /// Row spectra, `[row * spectrum_columns + column]` for the Ny data rows.
    row_spectra: Vec<Complex<T>>,
    /// The convolved spectrum on the kept output rows, in one piece per block of
    /// `kept_tiles_per_block` tiles: the piece of block b (columns from b·W, W its tiles
    /// times TILE) holds `[row * W + column − b·W]`, so that an output row is gathered
    /// from a few long runs (one per block) instead of one short run per tile.
    kept: Vec<Complex<T>>,
    /// Tiles per block of the last write of `kept`.
    kept_tiles_per_block: usize,
    blocks: Vec<BlockScratch<T>>,
}

struct BlockScratch<T> {
    real_row: Vec<T>,
    real_scratch: Vec<Complex<T>>,
    complex_scratch: Vec<Complex<T>>,
    /// TILE full-length columns, `[column * column_stride(padded_y) + row]`: small enough to
    /// stay in cache from the gather through both column transforms to the scatter.
    tile: Vec<Complex<T>>,
    /// One spectrum row gathered from the tiles for the inverse row transform.
    spectrum: Vec<Complex<T>>,
}

/// Columns transformed together (16 complex values = 4 cache lines per row of a tile).
const TILE: usize = 16;

/// Distance between the starts of a tile's columns: the column length and 8 values more.
/// A power-of-two column length alone puts row i of all TILE columns in one cache set (a
/// 4 KiB stride at 512 complex f32), so the transposing gather and scatter, which touch
/// row i of every column in turn, evict each other's lines; the gap spreads them over sets.
/// The transforms see the same values, so the bits do not change.
fn column_stride(padded_y: usize) -> usize {
    padded_y + 8
}

fn block_len(total: usize, blocks: usize) -> usize {
    total.div_ceil(blocks).max(1)
}

impl<T: Precision> SpectralConvolution<T> {
    /// Plans the transforms and allocates the buffers for Ny data rows of Nx values in a
    /// padded_y × padded_x transform (`data` = (Nx, Ny), `padded` = (padded_x, padded_y));
    /// the kernel spectrum is zero until set.
    pub(crate) fn planned(data: (usize, usize), padded: (usize, usize)) -> Self {
        let ((nx, ny), (padded_x, padded_y)) = (data, padded);
        let forward_rows = planner::real_forward::<T>(padded_x);
        let inverse_rows = planner::real_inverse::<T>(padded_x);
        let forward_columns = planner::complex_forward::<T>(padded_y);
        let inverse_columns = planner::complex_inverse::<T>(padded_y);
        let spectrum_columns = padded_x / 2 + 1;
        let threads = rayon::current_num_threads().max(1);
        let scratch_len = forward_rows.get_scratch_len().max(inverse_rows.get_scratch_len());
        let complex_scratch_len = forward_columns
            .get_inplace_scratch_len()
            .max(inverse_columns.get_inplace_scratch_len());
        let blocks = (0..threads)
            .map(|_| BlockScratch {
                real_row: vec![T::zero(); padded_x],
                real_scratch: vec![Complex::default(); scratch_len],
                complex_scratch: vec![Complex::default(); complex_scratch_len],
                tile: vec![Complex::default(); TILE * column_stride(padded_y)],
                spectrum: vec![Complex::default(); spectrum_columns],
            })
            .collect();
        Self {
            nx,
            ny,
            padded_x,
            padded_y,
            spectrum_columns,
            kernel: vec![T::zero(); spectrum_columns * padded_y],
            forward_rows,
            inverse_rows,
            forward_columns,
            inverse_columns,
            row_spectra: vec![Complex::default(); ny * spectrum_columns],
            kept: vec![Complex::default(); spectrum_columns.div_ceil(TILE) * ny * TILE],
            kept_tiles_per_block: 1,
            blocks,
        }
    }

    /// A single-precision engine with the same sizes and this engine's kernel spectrum
    /// (rounded once from the f64 values).
    pub(crate) fn to_single(&self) -> SpectralConvolution<f32> {
        let mut single = SpectralConvolution::<f32>::planned((self.nx, self.ny), (self.padded_x, self.padded_y));
        for (target, &value) in single.kernel.iter_mut().zip(&self.kernel) {
            *target = f32::narrow(value.widen());
        }
        single
    }

    /// The kernel spectrum, laid out as [`convolve_pair`](Self::convolve_pair)'s `cross`.
    pub(crate) fn into_kernel(self) -> Vec<T> {
        self.kernel
    }

    /// Overwrites the kernel spectrum with `value(row_frequency, column_frequency)`
    /// (already normalised by padded_x·padded_y).
    pub(crate) fn set_kernel_spectrum(&mut self, value: impl Fn(usize, usize) -> f64 + Sync) {
        let padded = self.padded_y;
        self.kernel.par_chunks_mut(padded).enumerate().for_each(|(c, out)| {
            for (r, o) in out.iter_mut().enumerate() {
                *o = T::narrow(value(r, c));
            }
        });
    }

    /// output = kernel ∗ input on the Nx×Ny data window.
    pub(crate) fn convolve(&mut self, input: &[f64], output: &mut [f64]) {
        let input_rows = self.data_rows(input);
        self.convolve_rows(input, output, input_rows, 0..self.ny);
    }

    /// Rows holding a nonzero value, first to last: the transforms of the others are
    /// skipped with the bits unchanged ([`convolve_rows`](Self::convolve_rows)). An
    /// all-zero input keeps every row, so that even the signs of its zeros stay.
    fn data_rows(&self, input: &[f64]) -> Range<usize> {
        let n = self.nx;
        let first = input.iter().position(|&v| v != 0.0).map(|k| k / n);
        let last = input.iter().rposition(|&v| v != 0.0).map(|k| k / n + 1);
        match (first, last) {
            (Some(first), Some(last)) => first..last,
            _ => 0..self.ny,
        }
    }

    /// output = kernel ∗ input on the output rows `output_rows`, for an input that is zero
    /// outside the rows `input_rows` (its values there are not read). Output rows outside
    /// `output_rows` are left untouched.
    ///
    /// Bit-identical to [`convolve`](Self::convolve) on the output rows: the forward row
    /// transform of a zero row is exactly zero, so skipping it and zeroing its spectrum
    /// changes no value (at most the sign of an exact zero, which no output inherits
    /// unless the whole output is zero), and every row and column transform is computed
    /// independently of which others are computed. The c2c column transforms are not
    /// pruned: a column whose input is nonzero in few rows still needs a full-length
    /// transform to stay bit-identical (a pruned FFT rounds differently).
    pub(crate) fn convolve_rows(
        &mut self,
        input: &[f64],
        output: &mut [f64],
        input_rows: Range<usize>,
        output_rows: Range<usize>,
    ) {
        let (n, rows, columns) = (self.nx, self.ny, self.spectrum_columns);
        let padded = self.padded_y;
        assert_eq!(input.len(), n * rows, "input field does not match the grid");
        assert_eq!(output.len(), n * rows, "output field does not match the grid");
        assert!(
            input_rows.start <= input_rows.end && input_rows.end <= rows,
            "input rows {input_rows:?} outside 0..{rows}"
        );
        assert!(
            output_rows.start <= output_rows.end && output_rows.end <= rows,
            "output rows {output_rows:?} outside 0..{rows}"
        );
        let blocks = self.blocks.len();

        self.forward_rows_of(input, &input_rows);
        if output_rows.is_empty() {
            return;
        }
        // 2. Per tile of TILE columns: gather the input rows, column transforms, kernel
        // product, inverse column transforms, and keep the output rows, while the tile stays
        // in cache (a transpose of the whole spectrum and back is memory-bound at large N).
        let tiles = columns.div_ceil(TILE);
        let tile_len = output_rows.len() * TILE;
        let tiles_per_block = block_len(tiles, blocks);
        let row_spectra = &self.row_spectra;
        let input_rows = &input_rows;
        let kernel = &self.kernel;
        let (forward_columns, inverse_columns) = (&self.forward_columns, &self.inverse_columns);
        let first_output = output_rows.start;
        let stride = column_stride(padded);
        self.kept_tiles_per_block = tiles_per_block;
        self.kept[..tiles * tile_len]
            .par_chunks_mut(tiles_per_block * tile_len)
            .zip(self.blocks.par_iter_mut())
            .enumerate()
            .for_each(|(block, (kept, scratch))| {
                let block_width = kept.len() / output_rows.len();
                for local in 0..block_width / TILE {
                    let first = (block * tiles_per_block + local) * TILE;
                    let width = TILE.min(columns - first);
                    let tile = &mut scratch.tile[..width * stride];
                    gather_columns(tile, row_spectra, input_rows, (first, width, columns, padded));
                    for (offset, column) in tile.chunks_mut(stride).enumerate() {
                        let column = &mut column[..padded];
                        forward_columns.process_with_scratch(column, &mut scratch.complex_scratch);
                        let kernel_column = &kernel[(first + offset) * padded..][..padded];
                        // re and im scaled apart (the bits of `Complex::scale`): equal-length
                        // slices and plain products let the loop vectorise.
                        for (value, &k) in column.iter_mut().zip(kernel_column) {
                            value.re = value.re * k;
                            value.im = value.im * k;
                        }
                        inverse_columns.process_with_scratch(column, &mut scratch.complex_scratch);
                    }
                    keep_rows(kept, tile, first_output, (local * TILE, block_width), (width, padded));
                }
            });

        self.inverse_rows_into(output, &output_rows);
    }

    /// Forward row transforms of the input's rows `input_rows` into `row_spectra` (zero
    /// rows and the padded rows: skipped).
    fn forward_rows_of(&mut self, input: &[f64], input_rows: &Range<usize>) {
        let (n, columns) = (self.nx, self.spectrum_columns);
        let blocks = self.blocks.len();
        let forward_rows = &self.forward_rows;
        let input_window = &input[input_rows.start * n..input_rows.end * n];
        let rows_per_block = block_len(input_rows.len(), blocks);
        self.row_spectra[input_rows.start * columns..input_rows.end * columns]
            .par_chunks_mut(rows_per_block * columns)
            .zip(input_window.par_chunks(rows_per_block * n))
            .zip(self.blocks.par_iter_mut())
            .for_each(|((spectra, data), scratch)| {
                for (spectrum, row) in spectra.chunks_mut(columns).zip(data.chunks(n)) {
                    for (target, &value) in scratch.real_row[..n].iter_mut().zip(row) {
                        *target = T::narrow(value);
                    }
                    scratch.real_row[n..].fill(T::zero());
                    forward_rows
                        .process_with_scratch(&mut scratch.real_row, spectrum, &mut scratch.real_scratch)
                        .expect("forward row transform");
                }
            });
    }

    /// Gathers each kept output row (`output_rows`) from the tiles of `kept` and transforms
    /// it to real space.
    fn inverse_rows_into(&mut self, output: &mut [f64], output_rows: &Range<usize>) {
        let (n, columns, padded_x) = (self.nx, self.spectrum_columns, self.padded_x);
        let blocks = self.blocks.len();
        let block_len_kept = self.kept_tiles_per_block * TILE * output_rows.len();
        let kept = &self.kept[..columns.div_ceil(TILE) * TILE * output_rows.len()];
        let inverse_rows = &self.inverse_rows;
        let rows_per_block = block_len(output_rows.len(), blocks);
        output[output_rows.start * n..output_rows.end * n]
            .par_chunks_mut(rows_per_block * n)
            .zip(self.blocks.par_iter_mut())
            .enumerate()
            .for_each(|(block, (out, scratch))| {
                for (local, row_out) in out.chunks_mut(n).enumerate() {
                    let row = block * rows_per_block + local;
                    let spectrum = &mut scratch.spectrum[..columns];
                    for (piece, values) in kept
                        .chunks(block_len_kept)
                        .zip(spectrum.chunks_mut(block_len_kept / output_rows.len()))
                    {
                        let block_width = piece.len() / output_rows.len();
                        values.copy_from_slice(&piece[row * block_width..][..values.len()]);
                    }
                    // Exactly real in exact arithmetic; drop round-off so c2r accepts it.
                    spectrum[0].im = T::zero();
                    if padded_x % 2 == 0 {
                        spectrum[columns - 1].im = T::zero();
                    }
                    inverse_rows
                        .process_with_scratch(spectrum, &mut scratch.real_row, &mut scratch.real_scratch)
                        .expect("inverse row transform");
                    for (target, &value) in row_out.iter_mut().zip(&scratch.real_row[..n]) {
                        *target = value.widen();
                    }
                }
            });
    }
}

/// Fills `width` columns of a tile (`[column * column_stride(padded) + row]`) with the
/// column values `first..first + width` of the row spectra (`columns` per row), zero
/// outside the data rows `rows`. Four rows at a time, so that each column receives a run
/// of four values instead of one (the same values: only the order of the stores differs).
fn gather_columns<T: Precision>(
    tile: &mut [Complex<T>],
    spectra: &[Complex<T>],
    rows: &Range<usize>,
    (first, width, columns, padded): (usize, usize, usize, usize),
) {
    let stride = column_stride(padded);
    for column in tile.chunks_mut(stride) {
        column[..rows.start].fill(Complex::default());
        column[rows.end..padded].fill(Complex::default());
    }
    let row_of = |i: usize| &spectra[i * columns + first..][..width];
    let mut i = rows.start;
    while i + 4 <= rows.end {
        let (a, b, c, d) = (row_of(i), row_of(i + 1), row_of(i + 2), row_of(i + 3));
        for ((((column, &a), &b), &c), &d) in tile.chunks_mut(stride).zip(a).zip(b).zip(c).zip(d) {
            column[i..i + 4].copy_from_slice(&[a, b, c, d]);
        }
        i += 4;
    }
    for i in i..rows.end {
        for (column, &value) in tile.chunks_mut(stride).zip(row_of(i)) {
            column[i] = value;
        }
    }
}

/// Copies the tile's rows `first_row..` (as many as `kept` holds, `row_stride` values a
/// row) into `kept` at columns `column..column + width`, four rows at a time.
fn keep_rows<T: Precision>(
    kept: &mut [Complex<T>],
    tile: &[Complex<T>],
    first_row: usize,
    (column, row_stride): (usize, usize),
    (width, padded): (usize, usize),
) {
    let stride = column_stride(padded);
    let count = kept.len() / row_stride;
    let mut rows = kept.chunks_mut(row_stride).map(|row| &mut row[column..column + width]);
    let mut row = 0;
    while row + 4 <= count {
        let (a, b, c, d) = (
            rows.next().expect("row"),
            rows.next().expect("row"),
            rows.next().expect("row"),
            rows.next().expect("row"),
        );
        let i = first_row + row;
        for ((((source, a), b), c), d) in tile.chunks(stride).zip(a).zip(b).zip(c).zip(d) {
            let values = &source[i..i + 4];
            (*a, *b, *c, *d) = (values[0], values[1], values[2], values[3]);
        }
        row += 4;
    }
    for (offset, target) in rows.enumerate() {
        let i = first_row + row + offset;
        for (source, target) in tile.chunks(stride).zip(target) {
            *target = source[i];
        }
    }
}

impl SpectralConvolution<f64> {
    /// `kernel_row(i, row)` writes row i of the padded_y × padded_x kernel (already
    /// wrapped) into `row`; its spectrum is computed here once.
    pub(crate) fn new(
        data: (usize, usize),
        padded: (usize, usize),
        kernel_row: impl Fn(usize, &mut [f64]) + Sync,
    ) -> Self {
        let mut engine = Self::planned(data, padded);
        engine.kernel = engine.kernel_spectrum(kernel_row);
        engine
    }

    /// Full 2-D forward transform of the padded kernel; keeps the real part (the kernel
    /// is even in both directions, so its spectrum is real) divided by padded_x·padded_y.
    fn kernel_spectrum(&mut self, kernel_row: impl Fn(usize, &mut [f64]) + Sync) -> Vec<f64> {
        let (padded_x, padded) = (self.padded_x, self.padded_y);
        let columns = self.spectrum_columns;
        let forward_rows = &self.forward_rows;
        let mut rows: Vec<Complex<f64>> = vec![Complex::default(); padded * columns];
        rows.par_chunks_mut(columns).enumerate().for_each(|(i, spectrum)| {
            let mut real = vec![0.0; padded_x];
            kernel_row(i, &mut real);
            forward_rows
                .process(&mut real, spectrum)
                .expect("row transform of the kernel");
        });
        let forward_columns = &self.forward_columns;
        let normalisation = 1.0 / (padded_x as f64 * padded as f64);
        let mut spectrum = vec![0.0; columns * padded];
        spectrum.par_chunks_mut(padded).enumerate().for_each(|(c, out)| {
            let mut column: Vec<Complex<f64>> = (0..padded).map(|i| rows[i * columns + c]).collect();
            forward_columns.process(&mut column);
            for (o, value) in out.iter_mut().zip(&column) {
                *o = value.re * normalisation;
            }
        });
        spectrum
    }
}
