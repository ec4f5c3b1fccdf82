//! The camera under the rubber: a contact mask exposed as a grey frame through the optics'
//! blur, an uneven illumination and sensor noise. Shared by the synthetic sequences and by
//! films of simulated runs ([`crate::film`]).

use crate::{invalid, ContactMask, ExperimentError, GrayImage};
use adhesim::rng::SplitMix64;

/// How the camera images a contact: grey levels, optics and noise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Seed of the noise (each frame's stream is derived from it and the frame index).
    pub seed: u64,
    /// Signal-to-noise ratio |contact_level − background_level| / σ_noise; infinite = no noise.
    pub snr: f64,
    /// Gaussian blur of the optics, σ in pixels (0 = sharp).
    pub blur_sigma_px: f64,
    /// Strength g of the uneven illumination 1 + g(0.6u + 0.4v − 0.5(u² + v²)), u, v ∈ [−1, 1].
    pub illumination: f64,
    /// Grey level of the free surface (fraction of full scale).
    pub background_level: f64,
    /// Grey level of the contact.
    pub contact_level: f64,
}

impl Camera {
    /// Exposes `truth` as frame `frame`: blur → illumination → noise, clamped to 0..1.
    /// Deterministic for a seed and frame index.
    pub fn expose(&self, truth: &ContactMask, frame: usize) -> Result<GrayImage, ExperimentError> {
        let (w, h) = (truth.width(), truth.height());
        let mut field = frame_buffer(w, h)?;
        field.extend(truth.cells().iter().map(|&c| f32::from(c)));
        if self.blur_sigma_px > 0.0 {
            gaussian_blur(&mut field, w, h, self.blur_sigma_px)?;
        }
        let contrast = self.contact_level - self.background_level;
        let sigma = if self.snr.is_finite() {
            contrast.abs() / self.snr
        } else {
            0.0
        };
        let mut rng = SplitMix64::new(self.seed ^ (frame as u64).wrapping_mul(0xD1B5_4A32_D192_ED03).wrapping_add(1));
        for y in 0..h {
            let v = 2.0 * (y as f64 + 0.5) / h as f64 - 1.0;
            for x in 0..w {
                let u = 2.0 * (x as f64 + 0.5) / w as f64 - 1.0;
                let light = 1.0 + self.illumination * (0.6 * u + 0.4 * v - 0.5 * (u * u + v * v));
                let i = y * w + x;
                let clean = light * (self.background_level + contrast * f64::from(field[i]));
                let noise = if sigma > 0.0 { sigma * rng.gaussian() } else { 0.0 };
                field[i] = (clean + noise).clamp(0.0, 1.0) as f32;
            }
        }
        GrayImage::new(w, h, field)
    }
}

/// An empty buffer with room for a frame of w × h values: an error naming the size where
/// the memory is not there, not an abort (sizes up to 2^28 pixels pass `validate`).
fn frame_buffer(w: usize, h: usize) -> Result<Vec<f32>, ExperimentError> {
    let mut buffer = Vec::new();
    buffer.try_reserve_exact(w * h).map_err(|_| {
        invalid(
            "synth.width×height",
            "must fit in the memory available",
            format!("{w}×{h}"),
        )
    })?;
    Ok(buffer)
}

/// Separable Gaussian blur, kernel truncated at 3σ, edges clamped.
fn gaussian_blur(field: &mut [f32], w: usize, h: usize, sigma: f64) -> Result<(), ExperimentError> {
    let radius = (3.0 * sigma).ceil() as usize;
    let kernel: Vec<f32> = {
        let raw: Vec<f64> = (0..=2 * radius)
            .map(|i| (-((i as f64 - radius as f64).powi(2)) / (2.0 * sigma * sigma)).exp())
            .collect();
        let sum: f64 = raw.iter().sum();
        raw.iter().map(|v| (v / sum) as f32).collect()
    };
    let mut tmp = frame_buffer(w, h)?;
    tmp.resize(w * h, 0.0);
    for y in 0..h {
        let row = &field[y * w..(y + 1) * w];
        for x in 0..w {
            let mut s = 0.0;
            for (j, &k) in kernel.iter().enumerate() {
                let xx = (x + j).saturating_sub(radius).min(w - 1);
                s += k * row[xx];
            }
            tmp[y * w + x] = s;
        }
    }
    for y in 0..h {
        for x in 0..w {
            let mut s = 0.0;
            for (j, &k) in kernel.iter().enumerate() {
                let yy = (y + j).saturating_sub(radius).min(h - 1);
                s += k * tmp[yy * w + x];
            }
            field[y * w + x] = s;
        }
    }
    Ok(())
}
