//! Synthetic contact experiments: camera-like frames rendered from a known contact sequence,
//! plus the matching force/stage log. Deterministic for a given seed; each frame is rendered
//! independently (its noise stream is derived from the seed and the frame index), so frames
//! can be produced in parallel.

use crate::camera::Camera;
use crate::{invalid, ContactMask, ExperimentError, GrayImage};
use adhesim::rng::SplitMix64;
use std::f64::consts::PI;

/// A synthetic sliding experiment. The indenter centre moves at constant speed along +x;
/// the contact (an egg shape: half-ellipses of semi-axes `front_radius_px` and
/// `rear_radius_px` along the motion, `half_width_px` across, plus satellite spots) sticks for
/// `stick_frames` frames, then slips to re-centre on the indenter, shrinking or growing by
/// `size_change_per_slip` at each slip. So the area is constant in stick phases and jumps at
/// slips, as in the paper's Fig. 19.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticSpec {
    /// Frame width in pixels.
    pub width: usize,
    /// Frame height in pixels.
    pub height: usize,
    /// Number of frames.
    pub frames: usize,
    /// Length per pixel.
    pub pixel_size: f64,
    /// Frames per second.
    pub frame_rate: f64,
    /// Seed of all random streams.
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
    /// Indenter centre (column, row) at frame 0.
    pub start_centre_px: [f64; 2],
    /// Semi-axis of the contact ahead of its centre, pixels.
    pub front_radius_px: f64,
    /// Semi-axis behind its centre, pixels.
    pub rear_radius_px: f64,
    /// Semi-axis across the motion, pixels.
    pub half_width_px: f64,
    /// Indenter displacement per frame, pixels.
    pub speed_px_per_frame: f64,
    /// Frames per stick phase (≥ 1).
    pub stick_frames: usize,
    /// Relative size change of the contact at each slip (negative shrinks, as in Fig. 21).
    pub size_change_per_slip: f64,
    /// Satellite contact spots around the main contact.
    pub spots: usize,
    /// Area contribution to friction τ0 used for the force log (stress).
    pub tau0: f64,
    /// Boundary friction q used for the force log (force per length).
    pub boundary_friction: f64,
    /// Mean pressure F_N/A used for the force log.
    pub mean_pressure: f64,
    /// Relative Gaussian noise of the logged forces.
    pub force_noise: f64,
}

impl Default for SyntheticSpec {
    /// A 1600×1200 sequence of a R ≈ 22 mm sphere contact in mm/N units (pixel 5 µm).
    fn default() -> Self {
        Self {
            width: 1600,
            height: 1200,
            frames: 100,
            pixel_size: 0.005,
            frame_rate: 1.0,
            seed: 1,
            snr: 10.0,
            blur_sigma_px: 1.5,
            illumination: 0.2,
            background_level: 0.2,
            contact_level: 0.7,
            start_centre_px: [700.0, 600.0],
            front_radius_px: 260.0,
            rear_radius_px: 300.0,
            half_width_px: 280.0,
            speed_px_per_frame: 1.0,
            stick_frames: 12,
            size_change_per_slip: -0.03,
            spots: 6,
            tau0: 0.036,
            boundary_friction: 0.005,
            mean_pressure: 0.01,
            force_noise: 0.002,
        }
    }
}

/// One rendered frame with its ground truth and log entry.
#[derive(Debug, Clone)]
pub struct SyntheticFrame {
    /// The camera-like image.
    pub image: GrayImage,
    /// The contact that was rendered.
    pub truth: ContactMask,
    /// Log entry of this frame.
    pub log: LogEntry,
}

/// A line of the force/stage log.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogEntry {
    /// Time, seconds.
    pub time: f64,
    /// Normal force (> 0 compressive).
    pub force_normal: f64,
    /// Tangential force (> 0 resists the motion).
    pub force_tangential: f64,
    /// Stage position along the motion; 0 at frame 0.
    pub stage_x: f64,
    /// Stage height (indentation depth), constant here.
    pub stage_z: f64,
    /// True contact area, pixels × pixel_size².
    pub true_area: f64,
}

struct Spot {
    dx: f64,
    dy: f64,
    radius: f64,
}

impl SyntheticSpec {
    /// Checks the parameters; errors name the field and value.
    pub fn validate(&self) -> Result<(), ExperimentError> {
        let positive = [
            ("synth.pixel_size", self.pixel_size),
            ("synth.frame_rate", self.frame_rate),
            ("synth.snr", self.snr),
            ("synth.front_radius_px", self.front_radius_px),
            ("synth.rear_radius_px", self.rear_radius_px),
            ("synth.half_width_px", self.half_width_px),
        ];
        for (name, v) in positive {
            if v.is_nan() || v <= 0.0 {
                return Err(invalid(name, "must be > 0", v));
            }
        }
        let finite = [
            ("synth.blur_sigma_px", self.blur_sigma_px),
            ("synth.illumination", self.illumination),
            ("synth.speed_px_per_frame", self.speed_px_per_frame),
            ("synth.size_change_per_slip", self.size_change_per_slip),
            ("synth.tau0", self.tau0),
            ("synth.boundary_friction", self.boundary_friction),
            ("synth.mean_pressure", self.mean_pressure),
            ("synth.force_noise", self.force_noise),
        ];
        for (name, v) in finite {
            if !v.is_finite() {
                return Err(invalid(name, "must be finite", v));
            }
        }
        if self.blur_sigma_px < 0.0 || self.blur_sigma_px > 20.0 {
            return Err(invalid("synth.blur_sigma_px", "must be in 0..20", self.blur_sigma_px));
        }
        if self.width == 0 || self.height == 0 || self.width.saturating_mul(self.height) > 1 << 28 {
            return Err(invalid(
                "synth.width×height",
                "must be between 1 and 2^28 pixels",
                format!("{}×{}", self.width, self.height),
            ));
        }
        if self.stick_frames == 0 {
            return Err(invalid("synth.stick_frames", "must be >= 1", 0));
        }
        if self.illumination.abs() >= 1.0 {
            return Err(invalid("synth.illumination", "must be in (-1, 1)", self.illumination));
        }
        for (name, v) in [
            ("synth.background_level", self.background_level),
            ("synth.contact_level", self.contact_level),
        ] {
            if !(0.0..=1.0).contains(&v) {
                return Err(invalid(name, "must be in 0..1", v));
            }
        }
        if self.contact_level == self.background_level {
            return Err(invalid(
                "synth.contact_level",
                "must differ from background_level",
                self.contact_level,
            ));
        }
        Ok(())
    }

    /// Stage position at frame k (length units).
    pub fn stage_x(&self, k: usize) -> f64 {
        k as f64 * self.speed_px_per_frame * self.pixel_size
    }

    /// Indenter centre (column, row) at frame k.
    pub fn indenter_centre(&self, k: usize) -> [f64; 2] {
        [
            self.start_centre_px[0] + k as f64 * self.speed_px_per_frame,
            self.start_centre_px[1],
        ]
    }

    /// Contact centre and size scale at frame k: fixed during a stick phase, re-centred on the
    /// indenter at each slip.
    fn contact_state(&self, k: usize) -> ([f64; 2], f64) {
        let slips = k / self.stick_frames;
        let centre = self.indenter_centre(slips * self.stick_frames);
        let scale = (1.0 + self.size_change_per_slip).max(0.0).powi(slips as i32);
        (centre, scale)
    }

    fn spots(&self) -> Vec<Spot> {
        let mut rng = SplitMix64::new(self.seed ^ 0x5EED_5B07);
        (0..self.spots)
            .map(|_| {
                let angle = 2.0 * PI * rng.next_f64();
                let reach = 1.08 + 0.1 * rng.next_f64();
                let (c, s) = (angle.cos(), angle.sin());
                let semi = if c >= 0.0 {
                    self.front_radius_px
                } else {
                    self.rear_radius_px
                };
                Spot {
                    dx: reach * semi * c,
                    dy: reach * self.half_width_px * s,
                    radius: 3.0 + 5.0 * rng.next_f64(),
                }
            })
            .collect()
    }

    /// The true contact mask at frame k (pixel centres inside the shape).
    pub fn truth(&self, k: usize) -> Result<ContactMask, ExperimentError> {
        self.validate()?;
        let ([cx, cy], scale) = self.contact_state(k);
        let spots = self.spots();
        let (af, ar, b) = (
            self.front_radius_px * scale,
            self.rear_radius_px * scale,
            self.half_width_px * scale,
        );
        ContactMask::from_fn(self.width, self.height, |x, y| {
            let (dx, dy) = (x as f64 - cx, y as f64 - cy);
            let a = if dx >= 0.0 { af } else { ar };
            if a > 0.0 && b > 0.0 && (dx / a).powi(2) + (dy / b).powi(2) <= 1.0 {
                return true;
            }
            spots
                .iter()
                .any(|s| (dx - s.dx * scale).powi(2) + (dy - s.dy * scale).powi(2) <= (s.radius * scale).powi(2))
        })
    }

    /// Renders frame k: truth → blur → illumination → noise, clamped to 0..1.
    pub fn render(&self, k: usize) -> Result<SyntheticFrame, ExperimentError> {
        let truth = self.truth(k)?;
        let image = self.camera().expose(&truth, k)?;
        Ok(SyntheticFrame {
            image,
            log: self.log_entry(k, truth.count()),
            truth,
        })
    }

    /// The camera of this sequence.
    pub fn camera(&self) -> Camera {
        Camera {
            seed: self.seed,
            snr: self.snr,
            blur_sigma_px: self.blur_sigma_px,
            illumination: self.illumination,
            background_level: self.background_level,
            contact_level: self.contact_level,
        }
    }

    /// The log entry of frame k for a contact of `pixels` true pixels. F_x rises linearly from
    /// 80 % to 120 % of (τ0A + 2q√(A/π)) during each stick phase, so the mean over a phase
    /// follows Eq. 18.
    pub fn log_entry(&self, k: usize, pixels: usize) -> LogEntry {
        let area = pixels as f64 * self.pixel_size * self.pixel_size;
        let mut rng = SplitMix64::new(self.seed ^ 0xF0_4CE5 ^ (k as u64).wrapping_mul(0x9E37_79B9));
        let progress = if self.stick_frames > 1 {
            (k % self.stick_frames) as f64 / (self.stick_frames - 1) as f64
        } else {
            0.5
        };
        let friction = self.tau0 * area + 2.0 * self.boundary_friction * (area / PI).sqrt();
        LogEntry {
            time: k as f64 / self.frame_rate,
            force_normal: self.mean_pressure * area * (1.0 + self.force_noise * rng.gaussian()),
            force_tangential: friction * (0.8 + 0.4 * progress) * (1.0 + self.force_noise * rng.gaussian()),
            stage_x: self.stage_x(k),
            stage_z: 0.0,
            true_area: area,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        change_map, measure, BackgroundModel, Correction, Motion, Polarity, SegmentationParams, Segmenter,
        ThresholdRule,
    };

    fn small_spec() -> SyntheticSpec {
        SyntheticSpec {
            width: 320,
            height: 240,
            frames: 40,
            pixel_size: 0.01,
            start_centre_px: [140.0, 120.0],
            front_radius_px: 40.0,
            rear_radius_px: 48.0,
            half_width_px: 44.0,
            speed_px_per_frame: 1.5,
            stick_frames: 5,
            size_change_per_slip: -0.06,
            spots: 4,
            ..SyntheticSpec::default()
        }
    }

    fn params(background: BackgroundModel) -> SegmentationParams {
        SegmentationParams {
            polarity: Polarity::Bright,
            threshold: ThresholdRule::Otsu,
            background,
            correction: Correction::Divide,
            smooth_radius: 1,
            open_radius: 1,
            close_radius: 1,
            roi: None,
        }
    }

    /// Same seed, same frame; different seeds differ (determinism of the generator).
    #[test]
    fn deterministic() {
        let spec = small_spec();
        assert_eq!(spec.render(3).unwrap().image, spec.render(3).unwrap().image);
        let other = SyntheticSpec {
            seed: 2,
            ..small_spec()
        };
        assert_ne!(spec.render(3).unwrap().image, other.render(3).unwrap().image);
    }

    /// At SNR 10 with σ_blur = 1.5 px and ±20 % uneven illumination (flattened by the fitted
    /// background), the measured area is within 1 % of the true area for every frame of a
    /// shrinking contact whose true area stays above 2,000 pixels (checked: the sequence goes
    /// from ≈ 6,000 down to ≈ 2,300 pixels). 1 % is the target: the edge-blur bias is
    /// ≈ σ²/(2a) px per unit length and the pixel-count noise a few pixels, both far below.
    #[test]
    fn area_within_one_percent_at_snr10() {
        let spec = small_spec();
        let samples: Vec<GrayImage> = [0, 20, 39].iter().map(|&k| spec.render(k).unwrap().image).collect();
        let segmenter = Segmenter::new(params(BackgroundModel::Fitted), &samples).unwrap();
        let mut smallest = usize::MAX;
        for k in 0..spec.frames {
            let frame = spec.render(k).unwrap();
            let truth = frame.truth.count();
            smallest = smallest.min(truth);
            assert!(truth > 2000, "test contact must stay above 2000 px, frame {k}: {truth}");
            let m = measure(&segmenter.segment(&frame.image).unwrap(), spec.pixel_size, None).unwrap();
            let rel = m.pixels as f64 / truth as f64 - 1.0;
            assert!(
                rel.abs() < 0.01,
                "frame {k}: {} px measured vs {truth} true ({rel:+.4})",
                m.pixels
            );
        }
        assert!(
            smallest < 3000,
            "sequence should reach small contacts, smallest {smallest}"
        );
    }

    /// With stronger uneven illumination (g = 0.35) and the contact on the bright side,
    /// segmentation without flattening misses the 1 % target (global threshold too low for the
    /// locally brighter edge; seeded, measured 1.1 %), with the fitted background it stays
    /// within 1 % (measured 0.06 %): the correction is what makes the target reachable.
    #[test]
    fn uneven_illumination_needs_flattening() {
        let spec = SyntheticSpec {
            illumination: 0.35,
            start_centre_px: [210.0, 150.0],
            ..small_spec()
        };
        let samples: Vec<GrayImage> = [0, 20, 39].iter().map(|&k| spec.render(k).unwrap().image).collect();
        let raw = Segmenter::new(params(BackgroundModel::None), &samples).unwrap();
        let fitted = Segmenter::new(params(BackgroundModel::Fitted), &samples).unwrap();
        let frame = spec.render(30).unwrap();
        let truth = frame.truth.count() as f64;
        let err = |s: &Segmenter| (s.segment(&frame.image).unwrap().count() as f64 / truth - 1.0).abs();
        assert!(err(&fitted) < 0.01, "fitted {}", err(&fitted));
        assert!(err(&raw) > 0.01, "raw {}", err(&raw));
    }

    /// On noise-free, unblurred frames (uneven illumination kept) the segmentation without
    /// smoothing and morphological cleaning (which by design round one-pixel tips of the
    /// pixelated outline)
    /// reproduces the true masks, so change maps against the first frame and against the
    /// previous frame are pixel-exact (zero tolerance).
    #[test]
    fn change_maps_pixel_exact_noise_free() {
        let spec = SyntheticSpec {
            snr: f64::INFINITY,
            blur_sigma_px: 0.0,
            ..small_spec()
        };
        let samples = vec![spec.render(0).unwrap().image];
        let uncleaned = SegmentationParams {
            smooth_radius: 0,
            open_radius: 0,
            close_radius: 0,
            ..params(BackgroundModel::Fitted)
        };
        let segmenter = Segmenter::new(uncleaned, &samples).unwrap();
        let frames: Vec<SyntheticFrame> = (0..12).map(|k| spec.render(k).unwrap()).collect();
        let masks: Vec<ContactMask> = frames.iter().map(|f| segmenter.segment(&f.image).unwrap()).collect();
        for k in 1..frames.len() {
            for reference in [0, k - 1] {
                let measured = change_map(&masks[reference], &masks[k]).unwrap();
                let expected = change_map(&frames[reference].truth, &frames[k].truth).unwrap();
                assert_eq!(measured, expected, "frame {k} vs {reference}");
            }
        }
        // The slip at frame 5 changes the contact: the comparison is not vacuous.
        let slip = change_map(&frames[4].truth, &frames[5].truth).unwrap();
        assert!(slip.new_pixels() > 0 && slip.vanished_pixels() > 0);
    }

    /// The generator's front/rear geometry: at a slip frame the contact is centred on the
    /// indenter, so the split of the truth mask about the indenter centre gives the front
    /// part of the egg (semi-axis 40 px) smaller than the rear part (48 px).
    #[test]
    fn egg_front_smaller_than_rear() {
        let spec = small_spec();
        let truth = spec.truth(5).unwrap();
        let m = measure(&truth, 1.0, Some((spec.indenter_centre(5), Motion::PosX))).unwrap();
        assert!(m.area_front < m.area_rear, "{m:?}");
    }

    /// Invalid specs are errors naming the field.
    #[test]
    fn validation_names_field() {
        let spec = SyntheticSpec {
            pixel_size: -1.0,
            ..small_spec()
        };
        assert!(spec
            .validate()
            .unwrap_err()
            .to_string()
            .contains("synth.pixel_size must be > 0, got -1"));
    }
}
