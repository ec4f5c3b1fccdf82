//! `[roughness]` and `[substrate_roughness]`: a random self-affine surface drawn by
//! `adhesim::surface::SelfAffine` (generator keys) or a measured map read by
//! `adhesim_topography` (`file` keys), sampled on the simulation grid. Every error names
//! the dotted key (`roughness.hurst must lie in (0, 1], got 1.5`).

use crate::checks::{grid_keys, positive};
use crate::error::{ErrorKind, ScenarioError};
use crate::guards::usable_positive;
use crate::model::{InvalidPoints, InvalidPointsReport, RoughnessMode, RoughnessSection, RoughnessStatistics};
use adhesim::surface::{fill_invalid_harmonic, statistics, Amplitudes, RmsTarget, SelfAffine, SurfaceError};
use adhesim::Grid;
use adhesim_topography::{read_topography, ReadOptions, Topography, TopographyError};
use anyhow::{bail, Result};
use std::path::Path;

/// Keys of the generator form.
const GENERATOR_KEYS: [&str; 7] = [
    "hurst",
    "rms_height",
    "rms_slope",
    "rolloff_wavelength",
    "cutoff_wavelength",
    "seed",
    "mode",
];
/// Keys of the file form.
const FILE_KEYS: [&str; 7] = [
    "file",
    "detrend",
    "spacing",
    "channel",
    "height_unit",
    "lateral_unit",
    "invalid_points",
];

/// A roughness sampled on the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughnessMap {
    /// Heights at the element centres, row-major, peaks positive (towards the other body).
    pub heights: Vec<f64>,
    /// rms height, slope and curvature of `heights` on the grid.
    pub statistics: RoughnessStatistics,
    /// Warnings (a grid that undersamples a measured map), for stderr and `summary.json`.
    pub warnings: Vec<String>,
}

/// A measured map on the grid, before its statistics.
struct SampledFile {
    heights: Vec<f64>,
    warnings: Vec<String>,
    invalid_points: Option<InvalidPointsReport>,
}

/// Which keys of the section are set, in the order of the two lists above.
fn present(section: &RoughnessSection) -> (Vec<&'static str>, Vec<&'static str>) {
    let s = section;
    let generator = [
        s.hurst.is_some(),
        s.rms_height.is_some(),
        s.rms_slope.is_some(),
        s.rolloff_wavelength.is_some(),
        s.cutoff_wavelength.is_some(),
        s.seed.is_some(),
        s.mode.is_some(),
    ];
    let file = [
        s.file.is_some(),
        s.detrend.is_some(),
        s.spacing.is_some(),
        s.channel.is_some(),
        s.height_unit.is_some(),
        s.lateral_unit.is_some(),
        s.invalid_points.is_some(),
    ];
    let pick = |keys: &[&'static str], set: &[bool]| -> Vec<&'static str> {
        keys.iter().zip(set).filter(|(_, &on)| on).map(|(k, _)| *k).collect()
    };
    (pick(&GENERATOR_KEYS, &generator), pick(&FILE_KEYS, &file))
}

/// Samples the section named `name` (`roughness` or `substrate_roughness`) on `grid`;
/// relative file paths are resolved against `base`.
pub fn roughness_on_grid(section: &RoughnessSection, name: &str, grid: &Grid, base: &Path) -> Result<RoughnessMap> {
    let (generator, file) = present(section);
    let sampled = match (generator.is_empty(), file.is_empty()) {
        (true, true) => bail!(ScenarioError::missing(
            &format!("{name}.file"),
            format!("{name}.file, or {name}.hurst, {name}.seed and {name}.rms_height or {name}.rms_slope"),
            format!(
                "[{name}] is empty: give {name}.file, or the generator keys {name}.hurst, {name}.seed and one of {name}.rms_height / {name}.rms_slope"
            )
        )),
        (false, false) => bail!(ScenarioError::new(
            ErrorKind::InvalidValue,
            format!(
                "[{name}] mixes the generator key {name}.{} with the file key {name}.{}: give a random surface ({}) or a measured one ({}), not both",
                generator[0],
                file[0],
                GENERATOR_KEYS.join(", "),
                FILE_KEYS.join(", ")
            )
        )
        .with_key(format!("{name}.{}", file[0]))
        .with_requirement(format!("absent when {name}.{} is given", generator[0]))),
        (false, true) => SampledFile {
            heights: generate(section, name, grid)?,
            warnings: Vec::new(),
            invalid_points: None,
        },
        (true, false) => from_file(section, name, grid, base)?,
    };
    let stats = statistics(grid, &sampled.heights).map_err(|e| {
        ScenarioError::new(
            ErrorKind::InvalidValue,
            format!("[{name}]: the statistics of the map: {e}"),
        )
        .with_key(name)
        .with_requirement("a map whose statistics exist")
    })?;
    Ok(RoughnessMap {
        heights: sampled.heights,
        statistics: RoughnessStatistics {
            rms_height: stats.rms_height,
            rms_slope: stats.rms_slope,
            rms_curvature: stats.rms_curvature,
            invalid_points: sampled.invalid_points,
        },
        warnings: sampled.warnings,
    })
}

/// The generator form: `adhesim::surface::SelfAffine` on the grid.
fn generate(section: &RoughnessSection, name: &str, grid: &Grid) -> Result<Vec<f64>> {
    let s = section;
    let hurst = s.hurst.ok_or_else(|| {
        ScenarioError::missing(
            &format!("{name}.hurst"),
            "for a random surface",
            format!("missing key `{name}.hurst` (the Hurst exponent of a random surface)"),
        )
    })?;
    if !(hurst.is_finite() && hurst > 0.0 && hurst <= 1.0) {
        bail!(ScenarioError::invalid_as(
            &format!("{name}.hurst"),
            hurst,
            "in (0, 1]",
            format!("{name}.hurst must lie in (0, 1], got {hurst}")
        ));
    }
    let target = match (s.rms_height, s.rms_slope) {
        (Some(h), None) => RmsTarget::Height(usable_positive(&format!("{name}.rms_height"), h)?),
        (None, Some(slope)) => RmsTarget::Slope(usable_positive(&format!("{name}.rms_slope"), slope)?),
        (Some(h), Some(slope)) => bail!(ScenarioError::invalid_as(
            &format!("{name}.rms_slope"),
            slope,
            format!("absent when {name}.rms_height is given"),
            format!(
                "give exactly one of {name}.rms_height and {name}.rms_slope, got both ({name}.rms_height = {h}, {name}.rms_slope = {slope})"
            )
        )),
        (None, None) => bail!(ScenarioError::missing(
            &format!("{name}.rms_height"),
            format!("{name}.rms_height or {name}.rms_slope"),
            format!("give exactly one of {name}.rms_height and {name}.rms_slope, got neither")
        )),
    };
    let seed = s.seed.ok_or_else(|| {
        ScenarioError::missing(
            &format!("{name}.seed"),
            "for a random surface",
            format!("missing key `{name}.seed` (an integer >= 0 that fixes the random surface)"),
        )
    })?;
    if seed < 0 {
        bail!(ScenarioError::invalid(&format!("{name}.seed"), seed, ">= 0"));
    }
    let mut generator = SelfAffine::new(hurst, target).with_amplitudes(match s.mode.unwrap_or_default() {
        RoughnessMode::RandomPhase => Amplitudes::RandomPhase,
        RoughnessMode::Filtered => Amplitudes::Filtered,
    });
    if let Some(wavelength) = s.rolloff_wavelength {
        generator = generator.with_rolloff_wavelength(positive(&format!("{name}.rolloff_wavelength"), wavelength)?);
    }
    if let Some(wavelength) = s.cutoff_wavelength {
        generator = generator.with_cutoff_wavelength(positive(&format!("{name}.cutoff_wavelength"), wavelength)?);
    }
    let surface = generator.generate(grid, seed as u64).map_err(|e| match e {
        SurfaceError::RolloffNotBelowCutoff { rolloff, cutoff } => ScenarioError::invalid_as(
            &format!("{name}.rolloff_wavelength"),
            rolloff,
            format!("> {cutoff:e} (the cutoff wavelength)"),
            format!(
                "{name}.rolloff_wavelength must be longer than the cutoff wavelength {cutoff:e} ({name}.cutoff_wavelength, default 2·grid element), got {rolloff}"
            ),
        ),
        SurfaceError::CutoffBelowNyquist { cutoff, nyquist } => ScenarioError::invalid_as(
            &format!("{name}.cutoff_wavelength"),
            cutoff,
            format!(">= {nyquist:e} (two elements)"),
            format!(
                "{name}.cutoff_wavelength must be at least two elements ({nyquist:e}: grid.size / grid.n × 2), got {cutoff}"
            ),
        ),
        SurfaceError::EmptyBand { cutoff, patch } => ScenarioError::invalid_as(
            &format!("{name}.cutoff_wavelength"),
            cutoff,
            format!("longer than the shortest Fourier wavelength of the {patch:e}-wide patch"),
            format!(
                "{name}.cutoff_wavelength = {cutoff}: no Fourier mode of the {patch:e}-wide patch lies below it; shorten it or enlarge grid.size"
            ),
        ),
        other => ScenarioError::new(ErrorKind::InvalidValue, format!("[{name}]: {other}"))
            .with_key(name)
            .with_requirement("a surface the generator can make"),
    })?;
    Ok(surface.heights)
}

/// The file form: read, fill or refuse invalid points as `invalid_points` says, detrend on
/// request, resample onto the grid (bilinear, or spectral when the grid is finer), warn
/// when the grid undersamples the measurement.
fn from_file(section: &RoughnessSection, name: &str, grid: &Grid, base: &Path) -> Result<SampledFile> {
    let s = section;
    let file = s.file.as_ref().ok_or_else(|| {
        let file_keys = FILE_KEYS[1..]
            .iter()
            .map(|k| format!("{name}.{k}"))
            .collect::<Vec<_>>()
            .join(", ");
        ScenarioError::missing(
            &format!("{name}.file"),
            format!("with {file_keys}"),
            format!("missing key `{name}.file` (the file keys {file_keys} need a file)"),
        )
    })?;
    let key = format!("{name}.file");
    let spacing = s
        .spacing
        .map(|value| positive(&format!("{name}.spacing"), value))
        .transpose()?;
    let options = ReadOptions {
        channel: s.channel.clone(),
        spacing: spacing.map(|value| (value, value)),
        height_unit: s.height_unit.clone(),
        lateral_unit: s.lateral_unit.clone(),
    };
    let path = base.join(file);
    crate::files::check_regular_file(&path, &key)?;
    let mut map = read_topography(&path, &options).map_err(|e| read_error(&e, name, &key, file))?;
    if let Some(given) = spacing {
        if (given - map.dx).abs() > 1e-9 * given || (given - map.dy).abs() > 1e-9 * given {
            bail!(ScenarioError::invalid_as(
                &format!("{name}.spacing"),
                given,
                format!("absent, or the file's spacing {:e} × {:e} m", map.dx, map.dy),
                format!(
                    "{name}.spacing = {given} but {key} = {} records a spacing of {:e} × {:e} m: leave {name}.spacing out",
                    file.display(),
                    map.dx,
                    map.dy
                )
            ));
        }
    }
    let invalid_points = handle_invalid_points(&mut map, s.invalid_points, name, &key, file)?;
    if s.detrend.unwrap_or(false) {
        map.detrend_mean_plane().map_err(|e| {
            ScenarioError::invalid_as(
                &key,
                file.display(),
                "a map whose mean plane can be removed",
                format!("{key} = {}: detrending: {e}", file.display()),
            )
        })?;
    }
    let resampled = map
        .resample_to(grid.nx(), grid.ny(), grid.dx(), grid.dy())
        .map_err(|e| {
            ScenarioError::invalid_as(
                &key,
                file.display(),
                format!("a map that covers the grid ({})", grid_keys(grid)),
                format!(
                    "{key} = {}: the grid ({}) does not fit in the {}×{} map of spacing {:e} × {:e}: {e}",
                    file.display(),
                    grid_keys(grid),
                    map.nx,
                    map.ny,
                    map.dx,
                    map.dy
                ),
            )
        })?;
    let warnings = resampled
        .undersampling
        .map(|u| format!("{key} = {}: {u}", file.display()))
        .into_iter()
        .collect();
    Ok(SampledFile {
        heights: resampled.topography.heights,
        warnings,
        invalid_points,
    })
}

/// A reading error with the scenario key that supplies what the file lacks.
fn read_error(error: &TopographyError, name: &str, key: &str, file: &Path) -> anyhow::Error {
    let (hint, requirement) = match error {
        TopographyError::MissingOption { option, .. } => {
            (format!("; set {name}.{option}"), format!("{name}.{option} set"))
        }
        _ => (String::new(), "a height map file adhesim reads".to_string()),
    };
    ScenarioError::new(ErrorKind::File, format!("{key}: {error}{hint}"))
        .with_key(key)
        .with_value(file.display().to_string())
        .with_requirement(requirement)
        .into()
}

/// Applies the section's choice for the points the file marks invalid: an error naming the
/// key without a choice or with `"refuse"`; the harmonic filling with `"interpolate"`.
fn handle_invalid_points(
    map: &mut Topography,
    choice: Option<InvalidPoints>,
    name: &str,
    key: &str,
    file: &Path,
) -> Result<Option<InvalidPointsReport>> {
    let Some(valid) = map.mask.take() else {
        return Ok(None);
    };
    let count = valid.iter().filter(|v| !**v).count();
    let report = InvalidPointsReport {
        count,
        of: valid.len(),
        handling: InvalidPoints::Interpolate,
    };
    match choice {
        None | Some(InvalidPoints::Refuse) => {
            let how = if choice.is_none() {
                format!(
                    "set {name}.invalid_points = \"interpolate\" to fill them by harmonic interpolation, or \"refuse\""
                )
            } else {
                format!("{name}.invalid_points = \"refuse\"")
            };
            bail!(ScenarioError::invalid_as(
                key,
                file.display(),
                format!("a map without invalid points, or {name}.invalid_points = \"interpolate\""),
                format!(
                    "{key} = {}: {count} of {} points are invalid (NaN or masked in the file); {how}",
                    file.display(),
                    valid.len()
                )
            ))
        }
        Some(InvalidPoints::Interpolate) => {
            map.heights = fill_invalid_harmonic((map.nx, map.ny), &map.heights, &valid, false).map_err(|e| {
                ScenarioError::invalid_as(
                    key,
                    file.display(),
                    "a map whose invalid points can be filled",
                    format!("{key} = {}: filling the invalid points: {e}", file.display()),
                )
            })?;
            Ok(Some(report))
        }
    }
}
