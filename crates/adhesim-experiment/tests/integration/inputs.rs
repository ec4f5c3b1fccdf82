//! The library's own guards on experiment inputs: frame size fixed by the calibration frames,
//! region of interest and indenter centre inside the frames. Each is an error naming the
//! spec key (or the two sizes), never a silently clipped or misplaced measurement.

use adhesim_experiment::{
    ExperimentError, GrayImage, IndenterTrack, Motion, Roi, SegmentationParams, Segmenter, ThresholdRule,
};

fn frame(width: usize, height: usize) -> GrayImage {
    // A bright square on a dark ground, so that Otsu has two classes.
    let pixels = (0..width * height)
        .map(|i| {
            if (i % width) < width / 2 && (i / width) < height / 2 {
                0.9
            } else {
                0.1
            }
        })
        .collect();
    GrayImage::new(width, height, pixels).unwrap()
}

/// Frames of another size than the calibration frames are refused by `segment` and
/// `flatten` (they would be thresholded and measured as if they matched); calibration frames
/// of different sizes are refused by `Segmenter::new`.
#[test]
fn frames_must_keep_the_calibration_size() {
    let segmenter = Segmenter::new(SegmentationParams::default(), &[frame(40, 30)]).unwrap();
    assert!(segmenter.segment(&frame(40, 30)).is_ok());
    let mismatch = ExperimentError::SizeMismatch(40, 30, 30, 40);
    assert_eq!(segmenter.segment(&frame(30, 40)).unwrap_err(), mismatch);
    assert_eq!(segmenter.flatten(&frame(30, 40)).unwrap_err(), mismatch);
    let err = Segmenter::new(SegmentationParams::default(), &[frame(40, 30), frame(41, 30)]).unwrap_err();
    assert_eq!(err, ExperimentError::SizeMismatch(40, 30, 41, 30));
    // A fixed threshold needs no calibration frames: then no size is fixed.
    let params = SegmentationParams {
        threshold: ThresholdRule::Fraction(0.5),
        ..SegmentationParams::default()
    };
    let free = Segmenter::new(params, &[]).unwrap();
    assert!(free.segment(&frame(30, 40)).is_ok() && free.segment(&frame(40, 30)).is_ok());
}

/// A region of interest must lie wholly inside the frames: the last column and row may be
/// included, one more may not, and an empty region is refused.
#[test]
fn region_of_interest_inside_the_frames() {
    let roi = |x0, y0, width, height| Roi { x0, y0, width, height };
    assert!(roi(0, 0, 40, 30).check_inside(40, 30).is_ok());
    assert!(roi(39, 29, 1, 1).check_inside(40, 30).is_ok());
    for bad in [
        roi(0, 0, 41, 30),
        roi(0, 1, 40, 30),
        roi(40, 0, 1, 1),
        roi(0, 0, 0, 30),
        roi(usize::MAX, 0, 2, 1),
    ] {
        let err = bad.check_inside(40, 30).unwrap_err();
        assert!(matches!(
            err,
            ExperimentError::OutsideImage {
                name: "contact.roi",
                width: 40,
                height: 30,
                ..
            }
        ));
        assert!(err.to_string().contains("contact.roi"), "{err}");
    }
    let params = SegmentationParams {
        roi: Some(roi(30, 0, 20, 10)),
        ..SegmentationParams::default()
    };
    let err = Segmenter::new(params, &[frame(40, 30)]).unwrap_err();
    assert!(
        matches!(
            err,
            ExperimentError::OutsideImage {
                name: "contact.roi",
                ..
            }
        ),
        "{err}"
    );
}

/// The indenter centre must lie on a pixel of the frames (pixel centres 0 … size − 1).
#[test]
fn indenter_centre_inside_the_frames() {
    let track = |cx, cy| IndenterTrack::new([cx, cy], 0.0, Motion::PosX, 1.0).unwrap();
    assert!(track(0.0, 0.0).check_inside(40, 30).is_ok());
    assert!(track(39.0, 29.0).check_inside(40, 30).is_ok());
    for (cx, cy) in [(-0.5, 10.0), (39.5, 10.0), (10.0, 29.5), (10.0, -1.0)] {
        let err = track(cx, cy).check_inside(40, 30).unwrap_err();
        assert!(
            matches!(
                err,
                ExperimentError::OutsideImage {
                    name: "indenter.centre_px",
                    width: 40,
                    height: 30,
                    ..
                }
            ),
            "{err}"
        );
    }
}
