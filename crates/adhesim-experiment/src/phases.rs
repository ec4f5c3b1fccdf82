//! Jumps of the contact area and stick/slip phases (paper Figs. 9, 19, 25).

use crate::fit::linear_fit;
use crate::{invalid, ExperimentError};

/// Phase of a frame in a sliding experiment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Area constant and tangential force linear in the stage position: the boundary is pinned.
    Stick,
    /// The area jumped into this frame.
    Slip,
    /// Neither (continuous change, too short a segment, or contact lost).
    Undetermined,
}

impl Phase {
    /// Lower-case name for output files.
    pub fn name(self) -> &'static str {
        match self {
            Phase::Stick => "stick",
            Phase::Slip => "slip",
            Phase::Undetermined => "undetermined",
        }
    }
}

/// Thresholds of the phase classification.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseParams {
    /// A jump is a relative area change |ΔA|/max(A_prev, A) above this between consecutive frames.
    pub jump_threshold: f64,
    /// A stick segment's area range (max − min) must stay below this fraction of its mean.
    pub area_tolerance: f64,
    /// A stick segment's F_x(x) straight-line fit must reach this coefficient of determination.
    pub min_r2: f64,
    /// Minimum frames of a stick segment.
    pub min_frames: usize,
    /// A frame whose logged F_x fell from the previous frame's by more than this share of
    /// it is a slip too, at constant area (a slip event of the whole contact, paper Fig. 19);
    /// 0 (the default) slips at area jumps only.
    pub force_drop_threshold: f64,
}

impl Default for PhaseParams {
    fn default() -> Self {
        Self {
            jump_threshold: 0.02,
            area_tolerance: 0.01,
            min_r2: 0.9,
            min_frames: 3,
            force_drop_threshold: 0.0,
        }
    }
}

/// Frames whose area changed from the previous frame by more than `relative_threshold`
/// (relative to the larger of the two). The first frame is never a jump.
pub fn detect_jumps(areas: &[f64], relative_threshold: f64) -> Result<Vec<bool>, ExperimentError> {
    if !(relative_threshold.is_finite() && relative_threshold > 0.0) {
        return Err(invalid("analysis.jump_threshold", "must be > 0", relative_threshold));
    }
    let mut jumps = vec![false; areas.len()];
    for i in 1..areas.len() {
        let (a0, a1) = (areas[i - 1], areas[i]);
        let scale = a0.max(a1);
        jumps[i] = scale > 0.0 && (a1 - a0).abs() > relative_threshold * scale;
    }
    Ok(jumps)
}

/// Classifies frames: jumps are [`Phase::Slip`], and so, with a `force_drop_threshold`, are
/// drops of the logged F_x; the runs between slips are [`Phase::Stick`] when long enough, of
/// constant area, and, where `motion` = (stage_x, F_x) is given, with F_x linear in stage_x
/// over a moving stage. Non-finite entries of `motion` mean "not logged"; a segment with
/// such entries is judged by its area alone.
pub fn classify_phases(
    areas: &[f64],
    motion: Option<(&[f64], &[f64])>,
    params: &PhaseParams,
) -> Result<Vec<Phase>, ExperimentError> {
    if let Some((x, f)) = motion {
        for len in [x.len(), f.len()] {
            if len != areas.len() {
                return Err(ExperimentError::LengthMismatch(areas.len(), len));
            }
        }
    }
    if !(params.area_tolerance >= 0.0 && params.min_r2.is_finite()) {
        return Err(invalid(
            "analysis.area_tolerance",
            "must be >= 0",
            params.area_tolerance,
        ));
    }
    if !(params.force_drop_threshold.is_finite() && params.force_drop_threshold >= 0.0) {
        return Err(invalid(
            "analysis.force_drop_threshold",
            "must be >= 0",
            params.force_drop_threshold,
        ));
    }
    let mut jumps = detect_jumps(areas, params.jump_threshold)?;
    if let Some((_, force)) = motion.filter(|_| params.force_drop_threshold > 0.0) {
        for i in 1..force.len() {
            let (before, now) = (force[i - 1], force[i]);
            jumps[i] |=
                before.is_finite() && now.is_finite() && before - now > params.force_drop_threshold * before.abs();
        }
    }
    let mut phases: Vec<Phase> = jumps
        .iter()
        .map(|&j| if j { Phase::Slip } else { Phase::Undetermined })
        .collect();
    let mut start = 0;
    while start < areas.len() {
        let mut end = start + 1;
        while end < areas.len() && !jumps[end] {
            end += 1;
        }
        // The segment starts at the jump frame's successor; a jump frame itself is slip.
        let seg_start = if jumps[start] { start + 1 } else { start };
        if end > seg_start
            && is_stick(
                &areas[seg_start..end],
                motion.map(|(x, f)| (&x[seg_start..end], &f[seg_start..end])),
                params,
            )
        {
            phases[seg_start..end].fill(Phase::Stick);
        }
        start = end;
    }
    Ok(phases)
}

fn is_stick(areas: &[f64], motion: Option<(&[f64], &[f64])>, params: &PhaseParams) -> bool {
    if areas.len() < params.min_frames.max(2) {
        return false;
    }
    let (lo, hi) = areas.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &a| {
        (lo.min(a), hi.max(a))
    });
    let mean = areas.iter().sum::<f64>() / areas.len() as f64;
    if !(mean > 0.0 && hi - lo <= params.area_tolerance * mean) {
        return false;
    }
    match motion {
        Some((x, f)) if x.iter().chain(f).all(|v| v.is_finite()) => match linear_fit(x, f) {
            Ok(line) => line.r2 >= params.min_r2,
            Err(_) => false, // stage not moving: no stick-slip to speak of
        },
        _ => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A saw-tooth sequence: constant area with F_x rising linearly, then a 10 % area jump.
    /// The jump frames are slip, the plateaus stick (exact classification; thresholds are far
    /// from the data: 10 % jumps vs a 2 % threshold).
    #[test]
    fn sawtooth_stick_slip() {
        let mut areas = Vec::new();
        let mut x = Vec::new();
        let mut f = Vec::new();
        for k in 0..20usize {
            let cycle = (k / 5) as i32;
            areas.push(100.0 * 1.1f64.powi(cycle));
            x.push(k as f64);
            f.push((k % 5) as f64 + 1.0);
        }
        let phases = classify_phases(&areas, Some((&x, &f)), &PhaseParams::default()).unwrap();
        for (k, p) in phases.iter().enumerate() {
            let expected = if k % 5 == 0 && k > 0 { Phase::Slip } else { Phase::Stick };
            assert_eq!(*p, expected, "frame {k}");
        }
        // Without the jumps but F_x erratic, nothing is stick.
        let erratic: Vec<f64> = (0..20).map(|k| ((k * 7919) % 13) as f64).collect();
        let phases = classify_phases(&[5.0; 20], Some((&x, &erratic)), &PhaseParams::default()).unwrap();
        assert!(phases.iter().all(|&p| p == Phase::Undetermined));
    }

    /// A sawtooth at constant area (the whole contact slipping, paper Fig. 19): with a force
    /// drop threshold the drop frames are slip and the rises between them stick (exact: 20 %
    /// drops against a 1 % threshold); without one nothing splits the run and nothing is
    /// stick, as before.
    #[test]
    fn force_drops_at_constant_area_are_slips() {
        let x: Vec<f64> = (0..20).map(|k| k as f64).collect();
        let f: Vec<f64> = (0..20).map(|k| 1.0 + 0.05 * (k % 5) as f64).collect();
        let drops = PhaseParams {
            force_drop_threshold: 0.01,
            ..PhaseParams::default()
        };
        let phases = classify_phases(&[5.0; 20], Some((&x, &f)), &drops).unwrap();
        for (k, p) in phases.iter().enumerate() {
            let expected = if k % 5 == 0 && k > 0 { Phase::Slip } else { Phase::Stick };
            assert_eq!(*p, expected, "frame {k}");
        }
        let phases = classify_phases(&[5.0; 20], Some((&x, &f)), &PhaseParams::default()).unwrap();
        assert!(phases.iter().all(|&p| p == Phase::Undetermined));
        let bad = PhaseParams {
            force_drop_threshold: -1.0,
            ..PhaseParams::default()
        };
        assert!(classify_phases(&[5.0; 20], Some((&x, &f)), &bad).is_err());
    }

    /// Zero-area frames never produce NaN-driven jumps; bad thresholds are errors.
    #[test]
    fn zero_area_and_bad_threshold() {
        assert_eq!(detect_jumps(&[0.0, 0.0, 1.0], 0.1).unwrap(), vec![false, false, true]);
        assert!(detect_jumps(&[1.0], -1.0).is_err());
    }
}
