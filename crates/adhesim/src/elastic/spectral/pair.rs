//! Two fields through a symmetric 2×2 matrix of kernels in one pass: the tangential
//! operator's u_x = K_xx∗q_x + K_xy∗q_y, u_y = K_xy∗q_x + K_yy∗q_y at the cost of two
//! convolutions (each field transformed forward and back once), not four.

use super::{block_len, column_stride, gather_columns, keep_rows, Precision, SpectralConvolution, TILE};
use rayon::prelude::*;

impl<T: Precision> SpectralConvolution<T> {
    /// (out_a, out_b) = (K_a∗a + K_c∗b, K_c∗a + K_b∗b) on the whole data window: `self`
    /// holds K_a and the buffers of the first field, `other` K_b and those of the second,
    /// `cross` the spectrum of K_c laid out as `kernel`. Each product is rounded as a
    /// separate convolution would round it up to the sum of the two spectra.
    ///
    /// # Panics
    /// If the engines' sizes or a slice length differ.
    pub(crate) fn convolve_pair(&mut self, other: &mut Self, cross: &[T], input: [&[f64]; 2], output: [&mut [f64]; 2]) {
        assert!(
            (self.nx, self.ny, self.padded_x, self.padded_y) == (other.nx, other.ny, other.padded_x, other.padded_y),
            "paired engines differ in size"
        );
        assert_eq!(
            cross.len(),
            self.kernel.len(),
            "cross kernel does not match the engines"
        );
        let [a, b] = input;
        let rows_a = self.data_rows(a);
        let rows_b = other.data_rows(b);
        self.forward_rows_of(a, &rows_a);
        other.forward_rows_of(b, &rows_b);
        let all = 0..self.ny;
        let (columns, padded) = (self.spectrum_columns, self.padded_y);
        let stride = column_stride(padded);
        let tiles = columns.div_ceil(TILE);
        let tile_len = all.len() * TILE;
        let blocks = self.blocks.len().min(other.blocks.len());
        let tiles_per_block = block_len(tiles, blocks);
        let (spectra_a, spectra_b) = (&self.row_spectra, &other.row_spectra);
        let (kernel_a, kernel_b) = (&self.kernel, &other.kernel);
        let (forward_columns, inverse_columns) = (&self.forward_columns, &self.inverse_columns);
        self.kept[..tiles * tile_len]
            .par_chunks_mut(tiles_per_block * tile_len)
            .zip(other.kept[..tiles * tile_len].par_chunks_mut(tiles_per_block * tile_len))
            .zip(self.blocks.par_iter_mut().zip(other.blocks.par_iter_mut()))
            .enumerate()
            .for_each(|(block, ((kept_a, kept_b), (scratch_a, scratch_b)))| {
                let block_width = kept_a.len() / all.len();
                for local in 0..block_width / TILE {
                    let first = (block * tiles_per_block + local) * TILE;
                    let width = TILE.min(columns - first);
                    let tile_a = &mut scratch_a.tile[..width * stride];
                    let tile_b = &mut scratch_b.tile[..width * stride];
                    gather_columns(tile_a, spectra_a, &rows_a, (first, width, columns, padded));
                    gather_columns(tile_b, spectra_b, &rows_b, (first, width, columns, padded));
                    for (offset, (column_a, column_b)) in
                        tile_a.chunks_mut(stride).zip(tile_b.chunks_mut(stride)).enumerate()
                    {
                        let (column_a, column_b) = (&mut column_a[..padded], &mut column_b[..padded]);
                        forward_columns.process_with_scratch(column_a, &mut scratch_a.complex_scratch);
                        forward_columns.process_with_scratch(column_b, &mut scratch_a.complex_scratch);
                        let at = (first + offset) * padded;
                        let ka = &kernel_a[at..at + padded];
                        let kb = &kernel_b[at..at + padded];
                        let kc = &cross[at..at + padded];
                        for r in 0..padded {
                            let (va, vb) = (column_a[r], column_b[r]);
                            column_a[r] = va.scale(ka[r]) + vb.scale(kc[r]);
                            column_b[r] = va.scale(kc[r]) + vb.scale(kb[r]);
                        }
                        inverse_columns.process_with_scratch(column_a, &mut scratch_a.complex_scratch);
                        inverse_columns.process_with_scratch(column_b, &mut scratch_a.complex_scratch);
                    }
                    keep_rows(kept_a, tile_a, 0, (local * TILE, block_width), (width, padded));
                    keep_rows(kept_b, tile_b, 0, (local * TILE, block_width), (width, padded));
                }
            });
        (self.kept_tiles_per_block, other.kept_tiles_per_block) = (tiles_per_block, tiles_per_block);
        let [out_a, out_b] = output;
        self.inverse_rows_into(out_a, &all);
        other.inverse_rows_into(out_b, &all);
    }
}
