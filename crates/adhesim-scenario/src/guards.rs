//! Checks of what the inputs imply, not only of each value (`docs/reliability.md`,
//! "Scenario inputs and resources"): the derived scales must be usable numbers, every
//! field must be finite and ≥ 0 on the whole grid, the step counts are capped, and the
//! memory a grid needs is estimated before anything of that size is allocated. Errors name
//! the input keys responsible; resolution problems are warnings.

use crate::error::ScenarioError;
use crate::memory::{gibibytes, MemoryLimit};
use crate::model::*;
use adhesim::{Grid, Indenter};
use anyhow::{bail, Result};

/// Most steps a protocol may take (`protocol.steps`, `protocol.approach_steps`, or the
/// approach steps implied by `protocol.step`): beyond it a run takes days and its
/// `curve.csv` grows past what the analysis is meant for.
pub const MAX_STEPS: usize = 1_000_000;

/// A derived scale must have a magnitude in [1e-150, 1e150]: the solver multiplies two such
/// numbers (a stress by an area, a modulus by a displacement), which then stays finite.
const USABLE_MAGNITUDE: f64 = 1e150;

/// [`USABLE_MAGNITUDE`] as a requirement.
const USABLE_RANGE: &str = "finite, magnitude in 1e-150..1e150";

/// Resolution warnings fire below this many elements across a feature (a waviness
/// wavelength, a punch diameter, the JKR radius a_JKR): with fewer, the discrete contact
/// cannot represent the feature and the results are a property of the grid.
pub const MIN_ELEMENTS_PER_FEATURE: f64 = 4.0;

/// `material.contact_modulus = 2` or `material.youngs_modulus = .., material.poisson_ratio = ..`.
fn material_keys(m: &MaterialSection) -> String {
    match (m.contact_modulus, m.youngs_modulus, m.poisson_ratio) {
        (Some(e), _, _) => format!("material.contact_modulus = {}", show(e)),
        (None, Some(e), Some(nu)) => format!("material.youngs_modulus = {}, material.poisson_ratio = {nu}", show(e)),
        _ => "[material]".to_string(),
    }
}

/// A number as a user would write it: `1e300` rather than 301 digits.
pub(crate) fn show(value: f64) -> String {
    if value != 0.0 && !(1e-4..1e6).contains(&value.abs()) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

/// `value` if it is > 0 and of a magnitude the solver can use ([1e-150, 1e150]: its square
/// stays a normal number), else an error naming `key` and the value. An rms height of
/// 1e300 overflowed the generated surface and failed later with a message about another key.
pub(crate) fn usable_positive(key: &str, value: f64) -> Result<f64> {
    if !(value.is_finite() && value > 0.0) {
        bail!(ScenarioError::invalid(key, value, "> 0"));
    }
    if !usable(value) {
        bail!(ScenarioError::invalid_as(
            key,
            show(value),
            USABLE_RANGE,
            format!(
                "{key} = {} lies outside the magnitudes 1e-150..1e150 the solver can use: bring it to commensurate units",
                show(value)
            )
        ));
    }
    Ok(value)
}

/// Whether `value` is finite, non-zero and of a magnitude the solver can use.
fn usable(value: f64) -> bool {
    value.is_finite() && value.abs() >= 1.0 / USABLE_MAGNITUDE && value.abs() <= USABLE_MAGNITUDE
}

impl ScenarioFile {
    /// The derived scales of `summary.json` (F_JKR, d_JKR, a_JKR, σ_c, the Johnson
    /// parameter): each one that is defined must be finite, non-zero and within
    /// [1e-150, 1e150] in magnitude; the error names the scale and the keys it comes from.
    pub(crate) fn check_derived(&self, derived: &Derived) -> Result<()> {
        let material = material_keys(&self.material);
        let gamma = format!("adhesion.work_of_adhesion = {}", show(self.adhesion.work_of_adhesion));
        let radius = format!("indenter.radius = {}", show(self.indenter.radius().unwrap_or(f64::NAN)));
        let element = format!("grid.size = {}, grid.n = {}", self.grid.size.show(show), self.grid.n);
        let waviness = format!(
            "indenter.wavelength = {}, indenter.amplitude = {}",
            show(self.indenter.waviness().map_or(f64::NAN, |(_, wavelength)| wavelength)),
            show(self.indenter.waviness().map_or(f64::NAN, |(amplitude, _)| amplitude))
        );
        let scales = [
            ("F_JKR", derived.f_jkr, format!("{gamma}, {radius}")),
            ("d_JKR", derived.d_jkr, format!("{material}, {gamma}, {radius}")),
            ("a_JKR", derived.a_jkr, format!("{material}, {gamma}, {radius}")),
            (
                "the critical stress σ_c",
                derived.critical_stress,
                format!("{material}, {gamma}, {element}"),
            ),
            (
                "the Johnson parameter",
                derived.johnson_parameter,
                format!("{waviness}, {material}, {gamma}"),
            ),
        ];
        for (name, value, keys) in scales {
            if let Some(value) = value {
                // α = 0 without adhesion is a legitimate value (a non-adhesive wavy contact).
                let zero_without_adhesion = value == 0.0 && self.adhesion.work_of_adhesion == 0.0;
                if !usable(value) && !zero_without_adhesion {
                    bail!(ScenarioError::derived(
                        format!("{value:e}"),
                        USABLE_RANGE,
                        format!(
                            "{name} = {value:e} is not a usable number (finite, magnitude in 1e-150..1e150); it comes from {keys}: bring these inputs to commensurate units"
                        )
                    ));
                }
            }
        }
        if !usable(derived.element_size) {
            bail!(ScenarioError::derived(
                format!("{:e}", derived.element_size),
                USABLE_RANGE,
                format!(
                    "the element size grid.size/grid.n = {:e} is not a usable number (magnitude in 1e-150..1e150); {element}",
                    derived.element_size
                )
            ));
        }
        self.check_single_precision(derived)
    }

    /// The scales the single-precision engines hold (see [`SINGLE_PRECISION_MAGNITUDE`]):
    /// the stiffness E*/Δ of the preconditioner (its reciprocal is the compliance), σ_c,
    /// the element size and the JKR lengths.
    fn check_single_precision(&self, derived: &Derived) -> Result<()> {
        let material = material_keys(&self.material);
        let gamma = format!("adhesion.work_of_adhesion = {}", show(self.adhesion.work_of_adhesion));
        let radius = format!("indenter.radius = {}", show(self.indenter.radius().unwrap_or(f64::NAN)));
        let element = format!("grid.size = {}, grid.n = {}", self.grid.size.show(show), self.grid.n);
        let delta = derived.element_size;
        let scales = [
            (
                "the stiffness E*/Δ",
                Some(contact_modulus(&self.material) / delta),
                format!("{material}, {element}"),
            ),
            ("the element size Δ", Some(delta), element.clone()),
            (
                "the critical stress σ_c",
                derived.critical_stress,
                format!("{material}, {gamma}, {element}"),
            ),
            ("d_JKR", derived.d_jkr, format!("{material}, {gamma}, {radius}")),
            ("a_JKR", derived.a_jkr, format!("{material}, {gamma}, {radius}")),
        ];
        for (name, value, keys) in scales {
            if let Some(value) = value {
                single_precision_scale(name, value, &keys)?;
            }
        }
        Ok(())
    }

    /// The heights of the indenter above its lowest point must span at most
    /// [`SINGLE_PRECISION_MAGNITUDE`]: the solver's single-precision engines hold the gaps
    /// and the pressures they imply. A sphere of radius 1e-300 (heights 1e298 at the grid's
    /// edge) failed mid-run with "no stable contact set"; heights of 1e300 from a file or an
    /// rms height of 1e30 likewise. The error names the keys that set the heights.
    pub(crate) fn check_height_span(&self, heights: &[f64], start_depth: f64) -> Result<()> {
        let span = heights
            .iter()
            .filter(|h| h.is_finite())
            .map(|h| h - start_depth)
            .fold(0.0, f64::max);
        if span <= SINGLE_PRECISION_MAGNITUDE {
            return Ok(());
        }
        let mut keys = vec![format!("indenter.shape = \"{}\"", self.indenter.shape().name())];
        if let Some(radius) = self.indenter.radius() {
            keys.push(format!("indenter.radius = {}", show(radius)));
        }
        if let IndenterSection::Topography { file, .. } = &self.indenter {
            keys.push(format!("indenter.file = {}", file.display()));
        }
        if let Some(amplitude) = self.indenter.waviness().map(|(amplitude, _)| amplitude) {
            keys.push(format!("indenter.amplitude = {}", show(amplitude)));
        }
        if let Some(roughness) = &self.roughness {
            match (&roughness.file, roughness.rms_height, roughness.rms_slope) {
                (Some(file), _, _) => keys.push(format!("roughness.file = {}", file.display())),
                (None, Some(h), _) => keys.push(format!("roughness.rms_height = {}", show(h))),
                (None, None, Some(s)) => keys.push(format!("roughness.rms_slope = {}", show(s))),
                _ => {}
            }
        }
        keys.push(format!("grid.size = {}", self.grid.size.show(show)));
        bail!(ScenarioError::derived(
            format!("{span:e}"),
            format!("a height span <= {SINGLE_PRECISION_MAGNITUDE:e}"),
            format!(
                "the indenter's heights span {span:e} above its lowest point on the grid, beyond the {SINGLE_PRECISION_MAGNITUDE:e} the solver's single-precision FFTs hold; it comes from {}: bring these inputs to commensurate units",
                keys.join(", ")
            )
        ))
    }

    /// The depth step of a run: finite, positive, and large enough to move the depth at all
    /// (`start + step != start` in floating point); the implied approach steps at most
    /// [`MAX_STEPS`]. `keys` names the inputs that set the step.
    pub(crate) fn check_step(&self, start_depth: f64, end_depth: f64, depth_step: f64, keys: &str) -> Result<usize> {
        let moves = start_depth + depth_step != start_depth && end_depth - depth_step != end_depth;
        // The step's own key (protocol.steps or protocol.step) comes first in `keys`.
        let step_key = keys.split(", ").next().unwrap_or(keys);
        if !(depth_step.is_finite() && depth_step > 0.0 && moves) {
            bail!(ScenarioError::derived(
                format!("{depth_step:e}"),
                "a depth step that moves the depth",
                format!(
                    "the depth step {depth_step:e} (from {keys}) does not move the depth between {start_depth:e} and {end_depth:e}: choose fewer steps or commensurate units"
                )
            )
            .with_key(step_key));
        }
        // The largest pressure of the run is at most that of one element pushed through the
        // whole depth range, E*·(range)/Δ.
        let range = (end_depth - start_depth).abs();
        // The shorter element side (the larger pressure): size/n on a square.
        let ((nx, ny), (sx, sy)) = (self.grid.n.pair(), self.grid.size.pair());
        let element_size = (sx / nx as f64).min(sy / ny as f64);
        let depth_keys = format!("{keys}, {}", material_keys(&self.material));
        single_precision_scale("the depth range", range, keys)?;
        single_precision_scale(
            "the pressure bound E*·(depth range)/Δ",
            contact_modulus(&self.material) * range / element_size,
            &format!(
                "{depth_keys}, grid.size = {}, grid.n = {}",
                self.grid.size.show(show),
                self.grid.n
            ),
        )?;
        let steps = ((end_depth - start_depth) / depth_step).ceil();
        if steps.is_nan() || steps > MAX_STEPS as f64 {
            bail!(ScenarioError::derived(
                format!("{steps:e}"),
                format!("at most {MAX_STEPS} approach steps"),
                format!("{keys} imply {steps:e} approach steps, more than the cap of {MAX_STEPS}")
            )
            .with_key(step_key));
        }
        Ok(steps as usize)
    }
}

/// The FFT engines of the CG directions and of the preconditioner work in single precision
/// (docs/fast-step.md): the pressures, displacements, the stiffness E*/Δ and the compliance
/// Δ/E* they hold must stay well inside f32's range (1.2e-38 .. 3.4e38), or they overflow
/// to ∞ and the run fails mid-way with "solver produced a non-finite value". Magnitudes in
/// [1e-30, 1e30] leave a factor 1e8 for the sums of a transform over up to 16384² elements
/// and its 1/N² normalisation; every physical unit system (SI, nm–GPa, cgs) lies far inside.
pub const SINGLE_PRECISION_MAGNITUDE: f64 = 1e30;

/// [`SINGLE_PRECISION_MAGNITUDE`] as a requirement.
const SINGLE_PRECISION_RANGE: &str = "magnitude in 1e-30..1e30";

/// Refuses a scale outside ±[1/[`SINGLE_PRECISION_MAGNITUDE`], [`SINGLE_PRECISION_MAGNITUDE`]],
/// naming the keys it comes from.
fn single_precision_scale(name: &str, value: f64, keys: &str) -> Result<()> {
    let magnitude = value.abs();
    if !(1.0 / SINGLE_PRECISION_MAGNITUDE..=SINGLE_PRECISION_MAGNITUDE).contains(&magnitude) {
        bail!(ScenarioError::derived(
            format!("{value:e}"),
            SINGLE_PRECISION_RANGE,
            format!(
                "{name} = {value:e} is outside the range the solver's single-precision FFTs hold (magnitude 1e-30..1e30); it comes from {keys}: bring these inputs to commensurate units"
            )
        ));
    }
    Ok(())
}

/// E* of `[material]` (E/(1 − ν²) from Young's modulus), NaN where validation refuses it.
fn contact_modulus(m: &MaterialSection) -> f64 {
    match (m.contact_modulus, m.youngs_modulus, m.poisson_ratio) {
        (Some(e), _, _) => e,
        (None, Some(e), Some(nu)) => e / (1.0 - nu * nu),
        _ => f64::NAN,
    }
}

/// A step count from the scenario (`protocol.steps`, `protocol.approach_steps`): 1 to
/// [`MAX_STEPS`].
pub(crate) fn step_count(key: &str, value: i64) -> Result<usize> {
    if value < 1 || value as u64 > MAX_STEPS as u64 {
        bail!(ScenarioError::invalid(key, value, &format!("in 1..={MAX_STEPS}")));
    }
    Ok(value as usize)
}

/// Every γ on the grid finite and ≥ 0; the error names the field's keys and the first
/// element at fault.
pub(crate) fn check_field(section: &AdhesionSection, grid: &Grid, gamma: &[f64]) -> Result<()> {
    let Some(bad) = gamma.iter().position(|g| !(g.is_finite() && *g >= 0.0)) else {
        return Ok(());
    };
    let (x, y) = grid.centre(bad);
    bail!(ScenarioError::derived(
        format!("{:e}", gamma[bad]),
        "a work of adhesion finite and >= 0 on every element",
        format!(
            "the work of adhesion must be finite and >= 0 on every element, got {:e} at x = {x:e}, y = {y:e} (element {bad}); it comes from {}",
            gamma[bad],
            field_keys(section)
        )
    )
    .with_key(field_key(section)))
}

/// The key that sets the shape of γ on the grid.
fn field_key(section: &AdhesionSection) -> &'static str {
    match &section.field {
        Some(FieldSpec::Quadratic { .. }) => "adhesion.field.ratio_edge_to_centre",
        Some(FieldSpec::Map { .. }) => "adhesion.field.file",
        None => "adhesion.work_of_adhesion",
    }
}

/// The keys that set γ per element, with their values.
fn field_keys(section: &AdhesionSection) -> String {
    match &section.field {
        Some(FieldSpec::Quadratic {
            ratio_edge_to_centre,
            half_length,
            ..
        }) => format!(
            "adhesion.field.ratio_edge_to_centre = {}, adhesion.field.half_length = {}, adhesion.work_of_adhesion = {}",
            show(*ratio_edge_to_centre),
            half_length.map_or("default".to_string(), show),
            show(section.work_of_adhesion)
        ),
        Some(FieldSpec::Map { file }) => format!(
            "adhesion.field.file = {}, adhesion.work_of_adhesion = {}",
            file.display(),
            show(section.work_of_adhesion)
        ),
        None => format!("adhesion.work_of_adhesion = {}", show(section.work_of_adhesion)),
    }
}

impl ScenarioFile {
    /// The critical stress σ_c of every adhesive element (γ > 0) within the range of the
    /// solver's single-precision engines ([`SINGLE_PRECISION_MAGNITUDE`]), as
    /// [`ScenarioFile::check_derived`] checks that of γ0: a field or map reaching γ = 1e296
    /// overflowed mid-run, one reaching 1e-303 ended in a "did not converge" whose residual
    /// (3.9e-34) was below its tolerance (the single-precision search directions underflow).
    pub(crate) fn check_field_stresses(&self, grid: &Grid, gamma: &[f64]) -> Result<()> {
        let contact_modulus = contact_modulus(&self.material);
        let delta = adhesim::solver::detachment_element_size(grid.dx(), grid.dy());
        let window = 1.0 / SINGLE_PRECISION_MAGNITUDE..=SINGLE_PRECISION_MAGNITUDE;
        let stress = |g: f64| adhesim::solver::critical_stress(contact_modulus, g, delta);
        let Some(bad) = gamma.iter().position(|&g| g > 0.0 && !window.contains(&stress(g))) else {
            return Ok(());
        };
        let (x, y) = grid.centre(bad);
        bail!(ScenarioError::derived(
            format!("{:e}", stress(gamma[bad])),
            SINGLE_PRECISION_RANGE,
            format!(
                "the critical stress σ_c = {:e} of the element at x = {x:e}, y = {y:e} (element {bad}, γ = {:e}) is outside the range the solver's single-precision FFTs hold (magnitude 1e-30..1e30); it comes from {}, {}, grid.size = {}, grid.n = {}: bring these inputs to commensurate values",
                stress(gamma[bad]),
                gamma[bad],
                field_keys(&self.adhesion),
                material_keys(&self.material),
                self.grid.size.show(show),
                self.grid.n
            )
        )
        .with_key(field_key(&self.adhesion)))
    }
}

/// Resolution warnings: fewer than [`MIN_ELEMENTS_PER_FEATURE`] elements per waviness
/// wavelength, across a punch, or per JKR radius a_JKR.
pub(crate) fn resolution_warnings(grid: &Grid, indenter: &Indenter, derived: &Derived) -> Vec<String> {
    // The longer element side: the coarser direction decides the resolution.
    let delta = grid.dx().max(grid.dy());
    let mut features = Vec::new();
    match indenter {
        Indenter::WavySphere(w) if w.waviness().amplitude() > 0.0 => {
            features.push((
                "the waviness wavelength (indenter.wavelength)",
                w.waviness().wavelength(),
            ));
        }
        Indenter::FlatPunch(p) => features.push(("the punch diameter (2 indenter.radius)", 2.0 * p.radius())),
        Indenter::EllipticPunch(p) => {
            let (a, b) = p.semi_axes();
            features.push(("the punch's smaller diameter (2 indenter.semi_axes)", 2.0 * a.min(b)));
        }
        _ => {}
    }
    if let Some(a_jkr) = derived.a_jkr {
        features.push(("the JKR radius a_JKR", a_jkr));
    }
    features
        .into_iter()
        .filter(|(_, length)| length / delta < MIN_ELEMENTS_PER_FEATURE)
        .map(|(name, length)| {
            format!(
                "{name} = {length:.4e} spans {:.2} elements (grid.size/grid.n = {delta:.4e}), fewer than {MIN_ELEMENTS_PER_FEATURE}: the grid does not resolve it; raise grid.n or lower grid.size",
                length / delta
            )
        })
        .collect()
}

/// Elements across the contact radius at the largest depth below which a sphere's
/// indentation gets a warning: with fewer, the contact is one or a few elements and the
/// force was measured 63× to 1981× the Hertz force (second robustness audit, docs/reliability.md), without a word.
pub const MIN_CONTACT_RADIUS_ELEMENTS: f64 = 2.0;

/// The warning for a sphere (smooth, wavy or rough) whose contact radius at the largest
/// depth spans fewer than [`MIN_CONTACT_RADIUS_ELEMENTS`] elements: the JKR radius of the
/// stable branch with adhesion, the Hertz radius √(R·d) without, at the depth below first
/// contact. `None` for other indenters, translations and resolved contacts.
pub(crate) fn contact_radius_warning(valid: &ValidScenario) -> Option<String> {
    let sphere = matches!(
        valid.file.indenter,
        IndenterSection::Sphere { .. } | IndenterSection::WavySphere { .. } | IndenterSection::RoughSphere { .. }
    );
    if !sphere || valid.translation.is_some() {
        return None;
    }
    let radius = valid.file.indenter.radius()?;
    let depth = valid.max_depth - valid.start_depth;
    let (a, model) = match &valid.jkr {
        Some(jkr) if valid.gamma0 > 0.0 => (jkr.radius_at_depth(depth)?, "JKR"),
        _ => ((radius * depth).sqrt(), "Hertz"),
    };
    // The longer element side: the coarser direction decides the resolution.
    let delta = valid.grid.dx().max(valid.grid.dy());
    let elements = a / delta;
    (elements < MIN_CONTACT_RADIUS_ELEMENTS).then(|| {
        format!(
            "the {model} contact radius at the largest depth (protocol.max_depth) is a = {a:.4e}, {elements:.2} elements (grid.size/grid.n = {delta:.4e}), fewer than {MIN_CONTACT_RADIUS_ELEMENTS}: the grid does not resolve the contact and its forces can be many times the closed form; raise grid.n, lower grid.size or press deeper"
        )
    })
}

/// A warning when an indentation approaches in a single depth step: its retraction then
/// moves in steps as large, and the jumps and the dissipated energy of such a run are not
/// results (a sphere with `protocol.step = 1e6` |d_JKR| "ran" one step each way and
/// reported a dissipated energy of 57,198).
/// A shear has no retraction: its one approach step matters only with adhesion (the
/// contact's attachment follows the approach), and the warning names its key.
pub(crate) fn single_step_warning(valid: &ValidScenario) -> Option<String> {
    if valid.translation.is_some() || valid.approach_steps > 1 {
        return None;
    }
    if valid.shear.is_some() {
        return (valid.gamma0 > 0.0).then(|| {
            format!(
                "the adhesive contact is pressed to protocol.depth in 1 approach step of {}: the attachment of its edge follows the approach, which one step cannot resolve; choose more protocol.approach_steps",
                show(valid.depth_step)
            )
        });
    }
    let keys = match &valid.file.protocol {
        crate::model::ProtocolSection::IndentPulloff(p) if p.step.is_some() => "protocol.step",
        _ => "protocol.steps",
    };
    Some(format!(
        "the indentation reaches protocol.max_depth in {} approach step of {} (from {keys}): one step per branch cannot resolve the force curve, its jumps or the dissipated energy; choose a smaller protocol.step or more protocol.steps",
        valid.approach_steps,
        show(valid.depth_step)
    ))
}

/// A warning when a run's contact never spanned more than one element: its forces are
/// those of one element, not of the body (a topography indenter smaller than one element
/// ran without a word; spheres are warned about before the run by
/// [`contact_radius_warning`]).
pub fn unresolved_contact_warning(records: &[adhesim::StepRecord]) -> Option<String> {
    let largest = records.iter().map(|r| r.contact_elements).max()?;
    (largest == 1).then(|| {
        format!(
            "the contact never spanned more than 1 element in {} steps: the grid does not resolve it and its forces are those of one element; raise grid.n or lower grid.size",
            records.len()
        )
    })
}

/// Bytes a run on an `n`×`n` grid needs, an upper estimate: the FFT buffers of the elastic
/// operator on the padded grid (2n per side for a free boundary, n for a periodic one: the
/// kernel spectrum and two work spectra of complex f64, two real padded buffers) and about
/// 32 f64 fields of n² (heights, γ, pressure, displacement, gap, the conjugate-gradient
/// vectors and the observer's copies).
pub fn memory_estimate(n: u64, boundary: BoundaryName) -> u64 {
    memory_estimate_rectangle(n, n, boundary)
}

/// [`memory_estimate`] of an `nx` × `ny` grid.
pub fn memory_estimate_rectangle(nx: u64, ny: u64, boundary: BoundaryName) -> u64 {
    let (padded_x, padded_y) = match boundary {
        BoundaryName::Free => (2 * nx, 2 * ny),
        BoundaryName::Periodic => (nx, ny),
    };
    let spectrum = padded_y * (padded_x / 2 + 1) * 16;
    let real = padded_x * padded_y * 8;
    3 * spectrum + 2 * real + 32 * nx * ny * 8
}

impl ScenarioFile {
    /// [`memory_estimate`] of this scenario's grid (0 for a `grid.n` that validation refuses).
    pub fn memory_estimate(&self) -> u64 {
        let (nx, ny) = self.grid.n.pair();
        if (2..=MAX_GRID_N).contains(&nx) && (2..=MAX_GRID_N).contains(&ny) {
            memory_estimate_rectangle(nx as u64, ny as u64, self.grid.boundary)
        } else {
            0
        }
    }

    /// Refuses, naming `grid.n`, the estimate and the limit, a scenario of which `runs`
    /// concurrent runs need more than `limit` allows. Call it before
    /// [`ScenarioFile::validate`], which allocates the grid's fields.
    pub(crate) fn check_memory_of_runs(&self, limit: &MemoryLimit, runs: u64) -> Result<()> {
        let need = self.memory_estimate().saturating_mul(runs.max(1));
        if need > limit.bytes {
            let each = if runs > 1 {
                format!(
                    " ({runs} concurrent runs of {} each)",
                    gibibytes(self.memory_estimate())
                )
            } else {
                String::new()
            };
            let hint = if limit.survives_lifting {
                "lower grid.n or raise the limit"
            } else {
                "lower grid.n (or override this check where the estimate is known to be too high)"
            };
            let message = format!(
                "grid.n = {} needs about {}{each}, more than the {limit}: {hint}",
                self.grid.n,
                gibibytes(need),
            );
            return Err(
                crate::error::ScenarioError::new(crate::error::ErrorKind::Resources, message)
                    .with_key("grid.n")
                    .with_value(self.grid.n.to_string())
                    .with_requirement(format!("at most {limit}"))
                    .into(),
            );
        }
        Ok(())
    }
}

/// Largest `grid.n` validation accepts.
pub const MAX_GRID_N: i64 = 16_384;
