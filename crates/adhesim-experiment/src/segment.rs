//! Segmentation of camera frames into contact masks: background flattening, one threshold
//! per sequence (Otsu refined to the midpoint of the class levels), cleaning, region of
//! interest.

use crate::background::{BlockGrid, Surface, BLOCK};
use crate::{invalid, ContactMask, ExperimentError, GrayImage, Roi};

thread_local! {
    /// Per-thread float work buffers reused across frames (see the byte buffers in `mask`).
    static FLOAT_WORK: std::cell::RefCell<(Vec<f32>, Vec<f32>)> = const { std::cell::RefCell::new((Vec::new(), Vec::new())) };
}

/// Whether contact appears brighter or darker than the free surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Polarity {
    /// Contact pixels are above the threshold.
    Bright,
    /// Contact pixels are below the threshold.
    Dark,
}

/// How the grey-level threshold is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ThresholdRule {
    /// Otsu's method on the pooled histogram of the calibration frames (after flattening),
    /// refined to the midpoint of the two class means (isodata): removes Otsu's class-size bias.
    Otsu,
    /// A fixed fraction of full scale, in 0..1.
    Fraction(f32),
}

/// Correction of uneven illumination before thresholding. Both corrections are
/// multiplicative (flat field), scaled so that the mean background level is kept.
#[derive(Debug, Clone, PartialEq)]
pub enum BackgroundModel {
    /// No correction.
    None,
    /// Per frame, a quadratic surface fitted by least squares to the free (non-contact)
    /// pixels, away from the contact edge; two passes.
    Fitted,
    /// A frame of the free surface under the same illumination.
    Reference(GrayImage),
}

/// How a background level b(x, y) (fitted, or a reference frame) is removed; b̄ is its mean.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Correction {
    /// Flat field v·b̄/b: for uneven illumination, which scales contact and free surface alike.
    Divide,
    /// v − b + b̄: for an additive background such as stray light or a sensor offset.
    Subtract,
}

/// Parameters of the segmentation.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentationParams {
    /// Contact bright or dark.
    pub polarity: Polarity,
    /// Threshold rule.
    pub threshold: ThresholdRule,
    /// Illumination correction.
    pub background: BackgroundModel,
    /// How the background level b(x, y) is removed.
    pub correction: Correction,
    /// Radius of a (2r+1)² box mean applied to the flattened frame before thresholding
    /// (0 = none). Averaging 9 pixels (r = 1) cuts the noise 3×, so the thresholded edge is
    /// smooth and the cleaning below does not erode it; a symmetric kernel leaves the
    /// half-level of a straight edge in place.
    pub smooth_radius: usize,
    /// Opening radius in pixels (0 = none); removes noise specks.
    pub open_radius: usize,
    /// Closing radius in pixels (0 = none); fills pinholes.
    pub close_radius: usize,
    /// Region of interest; `None` = whole frame.
    pub roi: Option<Roi>,
}

impl Default for SegmentationParams {
    fn default() -> Self {
        Self {
            polarity: Polarity::Bright,
            threshold: ThresholdRule::Otsu,
            background: BackgroundModel::None,
            correction: Correction::Divide,
            smooth_radius: 1,
            open_radius: 1,
            close_radius: 1,
            roi: None,
        }
    }
}

/// A calibrated segmentation: parameters plus the grey-level threshold fixed for a sequence
/// (one threshold for all frames, so that frames without contact stay empty).
#[derive(Debug, Clone)]
pub struct Segmenter {
    params: SegmentationParams,
    threshold: f32,
    /// Mean level of the [`BackgroundModel::Reference`] frame.
    reference_mean: Option<f32>,
    /// Size of the calibration frames; every frame segmented later must have it.
    frame_size: Option<(usize, usize)>,
}

const OTSU_BINS: usize = 1024;

impl Segmenter {
    /// Calibrates the threshold on sample frames (e.g. a few evenly spaced frames of the
    /// sequence). With [`ThresholdRule::Fraction`] the samples may be empty. The samples fix
    /// the frame size: samples of different sizes, a region of interest not inside them, and
    /// later frames of another size are errors.
    pub fn new(params: SegmentationParams, samples: &[GrayImage]) -> Result<Self, ExperimentError> {
        if let ThresholdRule::Fraction(f) = params.threshold {
            if !(0.0..=1.0).contains(&f) {
                return Err(invalid("contact.threshold", "must be in 0..1", f));
            }
        }
        let frame_size = samples.first().map(|s| (s.width(), s.height()));
        if let Some((w, h)) = frame_size {
            for s in samples {
                same_size(w, h, s.width(), s.height())?;
            }
            if let Some(roi) = params.roi {
                roi.check_inside(w, h)?;
            }
        }
        let reference_mean = match &params.background {
            BackgroundModel::Reference(reference) => {
                if let Some(s) = samples.first() {
                    same_size(reference.width(), reference.height(), s.width(), s.height())?;
                }
                let sum: f64 = reference.pixels().iter().map(|&v| f64::from(v)).sum();
                Some((sum / reference.pixels().len() as f64) as f32)
            }
            _ => None,
        };
        let threshold = match params.threshold {
            ThresholdRule::Fraction(f) => f,
            ThresholdRule::Otsu => {
                if samples.is_empty() {
                    return Err(ExperimentError::TooFewPoints {
                        fit: "Otsu threshold",
                        needed: 1,
                        got: 0,
                    });
                }
                let raw = otsu_pooled(samples.iter(), params.roi)?;
                if params.background == BackgroundModel::None {
                    raw
                } else {
                    let provisional = Segmenter {
                        params: params.clone(),
                        threshold: raw,
                        reference_mean,
                        frame_size,
                    };
                    let flat: Vec<GrayImage> = samples
                        .iter()
                        .map(|s| provisional.flatten(s))
                        .collect::<Result<_, _>>()?;
                    otsu_pooled(flat.iter(), params.roi)?
                }
            }
        };
        Ok(Self {
            params,
            threshold,
            reference_mean,
            frame_size,
        })
    }

    /// The grey-level threshold (in the units of the flattened frames).
    pub fn threshold(&self) -> f32 {
        self.threshold
    }

    /// The parameters.
    pub fn params(&self) -> &SegmentationParams {
        &self.params
    }

    /// The frame with the illumination correction applied.
    pub fn flatten(&self, frame: &GrayImage) -> Result<GrayImage, ExperimentError> {
        let gain = self.gain(frame)?;
        let (w, h) = (frame.width(), frame.height());
        let mut pixels = frame.pixels().to_vec();
        let (mut row_gain, mut row_offset) = (vec![1.0f32; w], vec![0.0f32; w]);
        for (y, row) in pixels.chunks_exact_mut(w).enumerate().take(h) {
            gain.fill_row(y, &mut row_gain, &mut row_offset);
            for ((v, g), o) in row.iter_mut().zip(&row_gain).zip(&row_offset) {
                *v = *v * g + o;
            }
        }
        GrayImage::new(w, h, pixels)
    }

    /// Contact mask of one frame: flatten, threshold, open, close, restrict to the ROI.
    pub fn segment(&self, frame: &GrayImage) -> Result<ContactMask, ExperimentError> {
        let gain = self.gain(frame)?;
        let (w, h) = (frame.width(), frame.height());
        let mut mask = if self.params.smooth_radius == 0 {
            self.classify(frame.pixels(), w, h, &gain, None)
        } else {
            FLOAT_WORK.with(|work| {
                let (flat, scratch) = &mut *work.borrow_mut();
                flat.clear();
                flat.extend_from_slice(frame.pixels());
                let (mut row_gain, mut row_offset) = (vec![1.0f32; w], vec![0.0f32; w]);
                for (y, row) in flat.chunks_exact_mut(w).enumerate() {
                    gain.fill_row(y, &mut row_gain, &mut row_offset);
                    row.iter_mut()
                        .zip(&row_gain)
                        .zip(&row_offset)
                        .for_each(|((v, g), o)| *v = *v * g + o);
                }
                box_mean(flat, scratch, w, h, self.params.smooth_radius);
                self.classify(flat, w, h, &Gain::One, None)
            })
        };
        mask.open_in_place(self.params.open_radius);
        mask.close_in_place(self.params.close_radius);
        Ok(mask.restricted(self.roi(frame)))
    }

    fn roi(&self, frame: &GrayImage) -> Roi {
        self.roi_of(frame.width(), frame.height())
    }

    fn roi_of(&self, width: usize, height: usize) -> Roi {
        match self.params.roi {
            Some(r) => r.clipped(width, height).unwrap_or(Roi {
                x0: 0,
                y0: 0,
                width: 0,
                height: 0,
            }),
            None => Roi::full(width, height),
        }
    }

    /// Illumination gain of a frame (flattened = raw × gain); checks the frame's size.
    fn gain(&self, frame: &GrayImage) -> Result<Gain<'_>, ExperimentError> {
        if let Some((w, h)) = self.frame_size {
            same_size(w, h, frame.width(), frame.height())?;
        }
        match &self.params.background {
            BackgroundModel::None => Ok(Gain::One),
            BackgroundModel::Reference(reference) => {
                same_size(reference.width(), reference.height(), frame.width(), frame.height())?;
                let mean = self.reference_mean.unwrap_or(1.0);
                Ok(Gain::Map(reference.pixels(), mean, self.params.correction))
            }
            BackgroundModel::Fitted => {
                let roi = self.roi(frame);
                let blocks = BlockGrid::new(frame, roi);
                let mut gain = Gain::One;
                // Two passes: the first provisional contact comes from the uncorrected frame.
                for _ in 0..2 {
                    let mut contact = vec![false; blocks.nx * blocks.ny];
                    self.classify(
                        frame.pixels(),
                        frame.width(),
                        frame.height(),
                        &gain,
                        Some((&mut contact, blocks.nx)),
                    );
                    match blocks.fit(&contact) {
                        Some(surface) => gain = Gain::Surface(surface, self.params.correction),
                        None => break,
                    }
                }
                Ok(gain)
            }
        }
    }

    /// Thresholds raw × gain; optionally marks the BLOCK×BLOCK blocks holding contact.
    fn classify(
        &self,
        pixels: &[f32],
        w: usize,
        h: usize,
        gain: &Gain,
        mut blocks: Option<(&mut [bool], usize)>,
    ) -> ContactMask {
        let t = self.threshold;
        let bright = self.params.polarity == Polarity::Bright;
        let mut cells = vec![0u8; w * h];
        let (mut row_gain, mut row_offset) = (vec![1.0f32; w], vec![0.0f32; w]);
        for y in 0..h {
            gain.fill_row(y, &mut row_gain, &mut row_offset);
            let src = &pixels[y * w..(y + 1) * w];
            let dst = &mut cells[y * w..(y + 1) * w];
            for (((d, &v), &g), &o) in dst.iter_mut().zip(src).zip(&row_gain).zip(&row_offset) {
                let f = v * g + o;
                *d = u8::from(if bright { f > t } else { f < t });
            }
            if let Some((flags, nx)) = blocks.as_mut() {
                let by = y / BLOCK;
                for (bx, chunk) in dst.chunks(BLOCK).enumerate() {
                    if chunk.iter().any(|&c| c != 0) {
                        flags[by * *nx + bx] = true;
                    }
                }
            }
        }
        ContactMask::from_parts(w, h, cells).restricted(self.roi_of(w, h))
    }
}

/// In-place (2r+1)² box mean with windows clipped at the border; running sums, O(pixels).
fn box_mean(field: &mut [f32], rows: &mut Vec<f32>, w: usize, h: usize, radius: usize) {
    rows.clear();
    rows.resize(w * h, 0.0);
    for (src, dst) in field.chunks_exact(w).zip(rows.chunks_exact_mut(w)) {
        let mut sum: f32 = src[..radius.min(w)].iter().sum();
        for x in 0..w {
            if x + radius < w {
                sum += src[x + radius];
            }
            if x > radius {
                sum -= src[x - radius - 1];
            }
            let len = (x + radius).min(w - 1) + 1 - x.saturating_sub(radius);
            dst[x] = sum / len as f32;
        }
    }
    let mut sums = vec![0.0f32; w];
    for row in rows.chunks_exact(w).take(radius.min(h)) {
        sums.iter_mut().zip(row).for_each(|(s, v)| *s += v);
    }
    for y in 0..h {
        if y + radius < h {
            sums.iter_mut()
                .zip(&rows[(y + radius) * w..(y + radius + 1) * w])
                .for_each(|(s, v)| *s += v);
        }
        if y > radius {
            sums.iter_mut()
                .zip(&rows[(y - radius - 1) * w..(y - radius) * w])
                .for_each(|(s, v)| *s -= v);
        }
        let inv = 1.0 / ((y + radius).min(h - 1) + 1 - y.saturating_sub(radius)) as f32;
        field[y * w..(y + 1) * w]
            .iter_mut()
            .zip(&sums)
            .for_each(|(f, s)| *f = s * inv);
    }
}

/// Background correction per pixel: corrected = raw × gain + offset.
enum Gain<'a> {
    One,
    /// Reference frame levels and their mean.
    Map(&'a [f32], f32, Correction),
    Surface(Surface, Correction),
}

impl Gain<'_> {
    fn fill_row(&self, y: usize, gain: &mut [f32], offset: &mut [f32]) {
        let correct = |level: f32, mean: f32, correction: Correction, g: &mut f32, o: &mut f32| match correction {
            Correction::Divide => (*g, *o) = (mean / level.max(mean * 1e-3).max(1e-6), 0.0),
            Correction::Subtract => (*g, *o) = (1.0, mean - level),
        };
        let w = gain.len();
        match self {
            Gain::One => {
                gain.fill(1.0);
                offset.fill(0.0);
            }
            Gain::Map(levels, mean, correction) => {
                for ((g, o), &level) in gain.iter_mut().zip(offset.iter_mut()).zip(&levels[y * w..(y + 1) * w]) {
                    correct(level, *mean, *correction, g, o);
                }
            }
            Gain::Surface(s, correction) => {
                // Along a row the quadratic is a + b·u + c·u².
                let v = (y as f64 + 0.5) / s.height as f64 - 0.5;
                let [c0, c1, c2, c3, c4, c5] = s.coeffs;
                let (a, b, c) = ((c0 + c2 * v + c5 * v * v) as f32, (c1 + c4 * v) as f32, c3 as f32);
                let mean = s.mean as f32;
                let inv_w = 1.0 / s.width as f32;
                for (x, (g, o)) in gain.iter_mut().zip(offset.iter_mut()).enumerate() {
                    let u = (x as f32 + 0.5) * inv_w - 0.5;
                    correct(a + u * (b + c * u), mean, *correction, g, o);
                }
            }
        }
    }
}

fn same_size(w1: usize, h1: usize, w2: usize, h2: usize) -> Result<(), ExperimentError> {
    if (w1, h1) == (w2, h2) {
        Ok(())
    } else {
        Err(ExperimentError::SizeMismatch(w1, h1, w2, h2))
    }
}

/// Otsu's threshold on the pooled histogram of the ROI pixels of several frames.
fn otsu_pooled<'a>(
    frames: impl Iterator<Item = &'a GrayImage> + Clone,
    roi: Option<Roi>,
) -> Result<f32, ExperimentError> {
    let roi_of = |f: &GrayImage| match roi {
        Some(r) => r.clipped(f.width(), f.height()),
        None => Some(Roi::full(f.width(), f.height())),
    };
    let for_each_value = |visit: &mut dyn FnMut(f32)| {
        for f in frames.clone() {
            if let Some(r) = roi_of(f) {
                for y in r.y0..r.y0 + r.height {
                    for &v in &f.pixels()[y * f.width() + r.x0..y * f.width() + r.x0 + r.width] {
                        visit(v);
                    }
                }
            }
        }
    };
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for_each_value(&mut |v| {
        lo = lo.min(v);
        hi = hi.max(v);
    });
    if !lo.is_finite() || !hi.is_finite() {
        return Err(ExperimentError::TooFewPoints {
            fit: "Otsu threshold",
            needed: 1,
            got: 0,
        });
    }
    if hi <= lo {
        return Ok(lo);
    }
    let scale = OTSU_BINS as f32 / (hi - lo);
    let mut hist = vec![0u64; OTSU_BINS];
    for_each_value(&mut |v| hist[(((v - lo) * scale) as usize).min(OTSU_BINS - 1)] += 1);
    let bin = midpoint_bin(&hist, otsu_bin(&hist));
    Ok(lo + (bin as f32 + 1.0) / scale)
}

/// Refines a split to the midpoint of the two class means (Ridler–Calvard isodata iteration).
/// Otsu's split leans towards the smaller class when the classes differ in size (a small
/// contact in a large frame), which would bias the area; the midpoint of the class levels is
/// the half-height of a blurred contact edge, where the true boundary lies.
pub(crate) fn midpoint_bin(hist: &[u64], start: usize) -> usize {
    let mut bin = start;
    for _ in 0..100 {
        let (mut n0, mut s0, mut n1, mut s1) = (0.0, 0.0, 0.0, 0.0);
        for (i, &c) in hist.iter().enumerate() {
            let (c, x) = (c as f64, i as f64 + 0.5);
            if i <= bin {
                n0 += c;
                s0 += c * x;
            } else {
                n1 += c;
                s1 += c * x;
            }
        }
        if n0 == 0.0 || n1 == 0.0 {
            return bin;
        }
        // Bin whose upper edge is closest to the midpoint of the class means.
        let next = (((s0 / n0 + s1 / n1) / 2.0).round() as usize)
            .saturating_sub(1)
            .min(hist.len() - 1);
        if next == bin {
            break;
        }
        bin = next;
    }
    bin
}

/// Index of the last bin of the lower class maximising the between-class variance.
pub(crate) fn otsu_bin(hist: &[u64]) -> usize {
    let total: f64 = hist.iter().map(|&c| c as f64).sum();
    let sum_all: f64 = hist.iter().enumerate().map(|(i, &c)| i as f64 * c as f64).sum();
    let (mut w0, mut sum0, mut best, mut best_bin) = (0.0, 0.0, -1.0, 0);
    for (i, &c) in hist.iter().enumerate() {
        w0 += c as f64;
        sum0 += i as f64 * c as f64;
        let w1 = total - w0;
        if w0 == 0.0 || w1 == 0.0 {
            continue;
        }
        let diff = sum0 / w0 - (sum_all - sum0) / w1;
        let between = w0 * w1 * diff * diff;
        if between > best {
            best = between;
            best_bin = i;
        }
    }
    best_bin
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The midpoint refinement lands halfway between two equal-width modes of very different
    /// size (exact bins: class means 20.5 and 81.5 → threshold 51, the upper edge of bin 50).
    #[test]
    fn midpoint_of_unequal_classes() {
        let mut hist = vec![0u64; 100];
        hist[20] = 100_000;
        hist[81] = 500;
        assert_eq!(midpoint_bin(&hist, otsu_bin(&hist)), 50);
    }

    /// An additive background gradient (0.1…0.5 across the frame, contrast 0.3) removed by
    /// subtracting a reference frame gives the true disc pixel-exactly (noise-free, no blur,
    /// no cleaning: zero tolerance).
    #[test]
    fn subtract_reference_removes_additive_background() {
        let (w, h) = (120, 90);
        let disc = |x: usize, y: usize| (x as f64 - 80.0).powi(2) + (y as f64 - 40.0).powi(2) <= 400.0;
        let level = |x: usize| 0.1 + 0.4 * x as f32 / w as f32;
        let frame = GrayImage::new(
            w,
            h,
            (0..w * h)
                .map(|i| level(i % w) + if disc(i % w, i / w) { 0.3 } else { 0.0 })
                .collect(),
        )
        .unwrap();
        let reference = GrayImage::new(w, h, (0..w * h).map(|i| level(i % w)).collect()).unwrap();
        let truth = ContactMask::from_fn(w, h, disc).unwrap();
        let segment = |correction| {
            let params = SegmentationParams {
                background: BackgroundModel::Reference(reference.clone()),
                correction,
                open_radius: 0,
                close_radius: 0,
                smooth_radius: 0,
                ..Default::default()
            };
            Segmenter::new(params, std::slice::from_ref(&frame))
                .unwrap()
                .segment(&frame)
                .unwrap()
        };
        let mask = segment(Correction::Subtract);
        assert!(mask == truth, "{} px vs {} true", mask.count(), truth.count());
    }

    /// Otsu separates a bimodal histogram between its modes.
    #[test]
    fn otsu_between_modes() {
        let mut hist = vec![0u64; 100];
        hist[20] = 500;
        hist[21] = 300;
        hist[70] = 200;
        hist[72] = 100;
        let t = otsu_bin(&hist);
        assert!((21..70).contains(&t), "{t}");
    }

    /// A fraction outside 0..1 is a named parameter error, not a panic.
    #[test]
    fn bad_fraction_is_error() {
        let params = SegmentationParams {
            threshold: ThresholdRule::Fraction(1.5),
            ..Default::default()
        };
        let err = Segmenter::new(params, &[]).unwrap_err();
        assert!(err.to_string().contains("contact.threshold"), "{err}");
    }
}
