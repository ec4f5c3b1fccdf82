//! The experiment spec file (TOML) and its validation.

use adhesim_experiment::{Correction, Motion, PhaseParams, Polarity, Roi, ThresholdRule};
use anyhow::{bail, Context, Result};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Arrays of exactly N values: serde's `[T; N]` reads N values and the TOML reader let the
/// rest go, so `contact.roi = [0, 0, 10, 10, 99]` was accepted; now an error with both
/// counts (serde names the key).
mod exact {
    use serde::de::Error;
    use serde::{Deserialize, Deserializer};

    pub fn array<'de, D, T, const N: usize>(deserializer: D) -> Result<[T; N], D::Error>
    where
        D: Deserializer<'de>,
        T: Deserialize<'de>,
    {
        let values = Vec::<T>::deserialize(deserializer)?;
        let count = values.len();
        <[T; N]>::try_from(values).map_err(|_| D::Error::custom(format!("expected {N} values, got {count}")))
    }

    pub fn optional<'de, D, T, const N: usize>(deserializer: D) -> Result<Option<[T; N]>, D::Error>
    where
        D: Deserializer<'de>,
        T: Deserialize<'de>,
    {
        array(deserializer).map(Some)
    }
}

/// Whole spec file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    pub frames: FramesSpec,
    pub forces: Option<ForcesSpec>,
    #[serde(default)]
    pub contact: ContactSpec,
    pub indenter: Option<IndenterSpec>,
    #[serde(default)]
    pub changes: ChangesSpec,
    #[serde(default)]
    pub analysis: AnalysisSpec,
    #[serde(default)]
    pub fits: FitsSpec,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FramesSpec {
    pub path: PathBuf,
    pub pixel_size: f64,
    pub rate: Option<f64>,
    pub timestamps: Option<PathBuf>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForcesSpec {
    pub path: PathBuf,
    pub time: String,
    pub normal: Option<String>,
    pub tangential: Option<String>,
    pub stage_x: Option<String>,
    pub stage_z: Option<String>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(untagged)]
pub enum ThresholdSpec {
    Name(String),
    Fraction(f64),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    #[serde(default = "default_threshold")]
    pub threshold: ThresholdSpec,
    #[serde(default = "default_contact_is")]
    pub contact_is: String,
    /// "none", "fit" or a path to a frame of the free surface.
    #[serde(default = "default_background")]
    pub background: String,
    /// "divide" (flat field, the default) or "subtract"; only with a background.
    pub correction: Option<String>,
    #[serde(default = "one")]
    pub smooth_radius: usize,
    #[serde(default = "one")]
    pub open_radius: usize,
    #[serde(default = "one")]
    pub close_radius: usize,
    /// [x0, y0, width, height] in pixels.
    #[serde(default, deserialize_with = "exact::optional")]
    pub roi: Option<[usize; 4]>,
}

impl Default for ContactSpec {
    fn default() -> Self {
        Self {
            threshold: default_threshold(),
            contact_is: default_contact_is(),
            background: default_background(),
            correction: None,
            smooth_radius: 1,
            open_radius: 1,
            close_radius: 1,
            roi: None,
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IndenterSpec {
    #[serde(deserialize_with = "exact::array")]
    pub centre_px: [f64; 2],
    /// Stage position at which the centre is at `centre_px` (default 0); only with
    /// `forces.stage_x`.
    pub stage_x0: Option<f64>,
    #[serde(default = "default_motion")]
    pub motion: String,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(untagged)]
pub enum ReferenceSpec {
    Name(String),
    Frame(i64),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChangesSpec {
    /// "first", "previous" or a frame number.
    #[serde(default = "default_reference")]
    pub reference: ReferenceSpec,
    /// Write a change map every N-th frame (0: none on a schedule).
    #[serde(default = "default_every")]
    pub every: usize,
    /// Also write a change map at every detected jump.
    #[serde(default = "yes")]
    pub at_jumps: bool,
    /// Upper bound on the number of change maps written.
    #[serde(default = "default_max_changes")]
    pub max: usize,
}

impl Default for ChangesSpec {
    fn default() -> Self {
        Self {
            reference: default_reference(),
            every: default_every(),
            at_jumps: true,
            max: default_max_changes(),
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSpec {
    #[serde(default = "default_jump")]
    pub jump_threshold: f64,
    #[serde(default = "default_area_tolerance")]
    pub area_tolerance: f64,
    #[serde(default = "default_min_r2")]
    pub min_r2: f64,
    #[serde(default = "default_min_frames")]
    pub min_stick_frames: usize,
    #[serde(default)]
    pub force_drop_threshold: f64,
}

impl Default for AnalysisSpec {
    fn default() -> Self {
        Self {
            jump_threshold: default_jump(),
            area_tolerance: default_area_tolerance(),
            min_r2: default_min_r2(),
            min_stick_frames: default_min_frames(),
            force_drop_threshold: 0.0,
        }
    }
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct FitsSpec {
    /// E* for the JKR fit of the normal curve.
    pub contact_modulus: Option<f64>,
    /// Indenter radius R for the JKR fit.
    pub indenter_radius: Option<f64>,
    /// Relative radius tolerance of the pinned phase after reversal.
    pub pinned_tolerance: Option<f64>,
    /// [t0, t1]: frames used for the friction-law fit (default: all with a tangential force).
    #[serde(default, deserialize_with = "exact::optional")]
    pub friction_window: Option<[f64; 2]>,
    /// Adhesive force vs waiting time table for Eq. 15.
    pub power_law: Option<PowerLawSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PowerLawSpec {
    pub path: PathBuf,
    pub time: String,
    pub force: String,
}

fn default_threshold() -> ThresholdSpec {
    ThresholdSpec::Name("otsu".into())
}
fn default_contact_is() -> String {
    "bright".into()
}
fn default_background() -> String {
    "none".into()
}
fn default_motion() -> String {
    "+x".into()
}
fn default_reference() -> ReferenceSpec {
    ReferenceSpec::Name("first".into())
}
fn default_every() -> usize {
    0
}
fn default_max_changes() -> usize {
    50
}
fn default_jump() -> f64 {
    PhaseParams::default().jump_threshold
}
fn default_area_tolerance() -> f64 {
    PhaseParams::default().area_tolerance
}
fn default_min_r2() -> f64 {
    PhaseParams::default().min_r2
}
fn default_min_frames() -> usize {
    PhaseParams::default().min_frames
}
fn one() -> usize {
    1
}
fn yes() -> bool {
    true
}

/// Reference frame of the change maps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reference {
    First,
    Previous,
    Frame(usize),
}

/// Background choice after validation.
#[derive(Debug, Clone, PartialEq)]
pub enum BackgroundChoice {
    None,
    Fit,
    File(PathBuf),
}

/// Validated, resolved settings.
#[derive(Debug)]
pub struct Settings {
    pub frames_dir: PathBuf,
    pub pixel_size: f64,
    pub rate: Option<f64>,
    pub timestamps: Option<PathBuf>,
    pub forces: Option<ForcesSpec>,
    pub polarity: Polarity,
    pub threshold: ThresholdRule,
    pub background: BackgroundChoice,
    pub correction: Correction,
    pub smooth_radius: usize,
    pub open_radius: usize,
    pub close_radius: usize,
    pub roi: Option<Roi>,
    pub indenter: Option<(f64, f64, f64, Motion)>,
    pub reference: Reference,
    pub changes_every: usize,
    pub changes_at_jumps: bool,
    pub changes_max: usize,
    pub phases: PhaseParams,
    pub fits: FitsSpec,
}

fn positive(name: &str, value: f64) -> Result<f64> {
    if !(value.is_finite() && value > 0.0) {
        bail!("{name} must be > 0, got {value}");
    }
    Ok(value)
}

/// Fit keys that would have no effect are errors: the JKR fit needs E* and R together, and
/// the normal force and depth columns; the friction window needs the tangential force.
fn check_fit_keys(fits: &FitsSpec, forces: Option<&ForcesSpec>) -> Result<()> {
    match (fits.contact_modulus.is_some(), fits.indenter_radius.is_some()) {
        (true, false) => bail!("fits.contact_modulus is unused without fits.indenter_radius (the JKR fit needs both)"),
        (false, true) => bail!("fits.indenter_radius is unused without fits.contact_modulus (the JKR fit needs both)"),
        _ => {}
    }
    let mapped = |column: fn(&ForcesSpec) -> &Option<String>| forces.is_some_and(|f| column(f).is_some());
    let normal_curve = mapped(|f| &f.normal) && mapped(|f| &f.stage_z);
    if fits.contact_modulus.is_some() && !normal_curve {
        bail!("fits.contact_modulus and fits.indenter_radius are unused without forces.normal and forces.stage_z (the JKR fit of the normal curve)");
    }
    if fits.pinned_tolerance.is_some() && !mapped(|f| &f.stage_z) {
        bail!("fits.pinned_tolerance is unused without forces.stage_z (the pinned phase is found on the depth)");
    }
    if fits.friction_window.is_some() && !mapped(|f| &f.tangential) {
        bail!("fits.friction_window is unused without forces.tangential (the friction-law fit)");
    }
    Ok(())
}

/// The indenter's centre, stage origin and motion, checked.
fn indenter_settings(spec: &Spec) -> Result<Option<(f64, f64, f64, Motion)>> {
    Ok(match &spec.indenter {
        Some(ind) => {
            let motion = Motion::parse(&ind.motion)
                .with_context(|| format!("indenter.motion must be one of +x, -x, +y, -y, got \"{}\"", ind.motion))?;
            if !ind.centre_px.iter().all(|v| v.is_finite()) {
                bail!("indenter.centre_px must be finite, got {:?}", ind.centre_px);
            }
            let stage_x0 = ind.stage_x0.unwrap_or(0.0);
            if !stage_x0.is_finite() {
                bail!("indenter.stage_x0 must be finite, got {stage_x0}");
            }
            if ind.stage_x0.is_some() && spec.forces.as_ref().is_none_or(|f| f.stage_x.is_none()) {
                bail!("indenter.stage_x0 is unused without forces.stage_x (the centre does not move): remove it or map the stage column");
            }
            Some((ind.centre_px[0], ind.centre_px[1], stage_x0, motion))
        }
        None => None,
    })
}

/// The phase-classification parameters of `[analysis]`, checked.
fn phase_params(a: &AnalysisSpec) -> Result<PhaseParams> {
    positive("analysis.jump_threshold", a.jump_threshold)?;
    if !(a.area_tolerance.is_finite() && a.area_tolerance >= 0.0) {
        bail!("analysis.area_tolerance must be >= 0, got {}", a.area_tolerance);
    }
    if !(a.min_r2.is_finite() && (0.0..=1.0).contains(&a.min_r2)) {
        bail!("analysis.min_r2 must be in 0..1, got {}", a.min_r2);
    }
    if !(a.force_drop_threshold.is_finite() && a.force_drop_threshold >= 0.0) {
        bail!(
            "analysis.force_drop_threshold must be >= 0 (0: off), got {}",
            a.force_drop_threshold
        );
    }
    Ok(PhaseParams {
        jump_threshold: a.jump_threshold,
        area_tolerance: a.area_tolerance,
        min_r2: a.min_r2,
        min_frames: a.min_stick_frames,
        force_drop_threshold: a.force_drop_threshold,
    })
}

/// The values of `[fits]`, checked.
fn check_fit_values(fits: &FitsSpec) -> Result<()> {
    if let Some(e) = fits.contact_modulus {
        positive("fits.contact_modulus", e)?;
    }
    if let Some(r) = fits.indenter_radius {
        positive("fits.indenter_radius", r)?;
    }
    if let Some(t) = fits.pinned_tolerance {
        if !(t.is_finite() && t >= 0.0) {
            bail!("fits.pinned_tolerance must be >= 0, got {t}");
        }
    }
    if let Some([t0, t1]) = fits.friction_window {
        if !(t0.is_finite() && t1.is_finite() && t1 > t0) {
            bail!("fits.friction_window must be [t0, t1] with t1 > t0, got [{t0}, {t1}]");
        }
    }
    Ok(())
}

/// Reads and validates a spec; relative paths are resolved against the spec's folder.
pub fn load(spec_path: &Path) -> Result<Settings> {
    let text = adhesim_scenario::read_input_text(spec_path, "experiment spec")?;
    let spec: Spec = toml::from_str(&text).with_context(|| format!("invalid spec {}", spec_path.display()))?;
    let base = spec_path.parent().unwrap_or(Path::new("."));
    let resolve = |p: &Path| if p.is_absolute() { p.to_path_buf() } else { base.join(p) };

    let pixel_size = positive("frames.pixel_size", spec.frames.pixel_size)?;
    let rate = spec.frames.rate.map(|r| positive("frames.rate", r)).transpose()?;
    if rate.is_some() == spec.frames.timestamps.is_some() {
        bail!("frames: give exactly one of frames.rate and frames.timestamps");
    }
    let polarity = match spec.contact.contact_is.as_str() {
        "bright" => Polarity::Bright,
        "dark" => Polarity::Dark,
        other => bail!("contact.contact_is must be \"bright\" or \"dark\", got \"{other}\""),
    };
    let threshold = match &spec.contact.threshold {
        ThresholdSpec::Name(n) if n == "otsu" => ThresholdRule::Otsu,
        ThresholdSpec::Name(n) => bail!("contact.threshold must be \"otsu\" or a fraction in 0..1, got \"{n}\""),
        ThresholdSpec::Fraction(f) if (0.0..=1.0).contains(f) => ThresholdRule::Fraction(*f as f32),
        ThresholdSpec::Fraction(f) => bail!("contact.threshold must be \"otsu\" or a fraction in 0..1, got {f}"),
    };
    let background = match spec.contact.background.as_str() {
        "none" => BackgroundChoice::None,
        "fit" => BackgroundChoice::Fit,
        "" => bail!("contact.background must be \"none\", \"fit\" or a file path, got \"\""),
        path => BackgroundChoice::File(resolve(Path::new(path))),
    };
    let correction = match spec.contact.correction.as_deref() {
        Some(_) if background == BackgroundChoice::None => {
            bail!("contact.correction is unused with contact.background = \"none\": remove it or give a background")
        }
        None | Some("divide") => Correction::Divide,
        Some("subtract") => Correction::Subtract,
        Some(other) => bail!("contact.correction must be \"divide\" or \"subtract\", got \"{other}\""),
    };
    for (name, r) in [
        ("contact.smooth_radius", spec.contact.smooth_radius),
        ("contact.open_radius", spec.contact.open_radius),
        ("contact.close_radius", spec.contact.close_radius),
    ] {
        if r > 50 {
            bail!("{name} must be <= 50, got {r}");
        }
    }
    let roi = match spec.contact.roi {
        Some([x0, y0, width, height]) => {
            if width == 0 || height == 0 {
                bail!("contact.roi width and height must be > 0, got [{x0}, {y0}, {width}, {height}]");
            }
            Some(Roi { x0, y0, width, height })
        }
        None => None,
    };
    let indenter = indenter_settings(&spec)?;
    let reference = match &spec.changes.reference {
        ReferenceSpec::Name(n) if n == "first" => Reference::First,
        ReferenceSpec::Name(n) if n == "previous" => Reference::Previous,
        ReferenceSpec::Name(n) => {
            bail!("changes.reference must be \"first\", \"previous\" or a frame number, got \"{n}\"")
        }
        ReferenceSpec::Frame(i) if *i >= 0 => Reference::Frame(*i as usize),
        ReferenceSpec::Frame(i) => bail!("changes.reference must be >= 0, got {i}"),
    };
    let phases = phase_params(&spec.analysis)?;
    let mut fits = spec.fits;
    check_fit_values(&fits)?;
    check_fit_keys(&fits, spec.forces.as_ref())?;
    if let Some(p) = fits.power_law.as_mut() {
        p.path = resolve(&p.path);
    }
    let forces = spec.forces.map(|mut f| {
        f.path = resolve(&f.path);
        f
    });
    // A folder or FIFO named as a file failed with a bare "Is a directory" or hung.
    let timestamps = spec.frames.timestamps.as_deref().map(resolve);
    let files = [
        ("forces.path", forces.as_ref().map(|f| &f.path)),
        ("fits.power_law.path", fits.power_law.as_ref().map(|p| &p.path)),
        ("frames.timestamps", timestamps.as_ref()),
        (
            "contact.background",
            match &background {
                BackgroundChoice::File(path) => Some(path),
                _ => None,
            },
        ),
    ];
    for (key, path) in files.into_iter().filter_map(|(key, path)| Some((key, path?))) {
        adhesim_scenario::check_regular_file(path, key)?;
    }
    Ok(Settings {
        frames_dir: resolve(&spec.frames.path),
        pixel_size,
        rate,
        timestamps,
        forces,
        polarity,
        threshold,
        background,
        correction,
        smooth_radius: spec.contact.smooth_radius,
        open_radius: spec.contact.open_radius,
        close_radius: spec.contact.close_radius,
        roi,
        indenter,
        reference,
        changes_every: spec.changes.every,
        changes_at_jumps: spec.changes.at_jumps,
        changes_max: spec.changes.max,
        phases,
        fits,
    })
}
