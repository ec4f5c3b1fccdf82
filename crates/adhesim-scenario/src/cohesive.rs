//! `adhesion.law` and its keys checked into an [`AdhesionLaw`], and the cohesive laws': the
//! work of adhesion they need, Maugis' and Tabor's parameters, the cohesive solver they build and
//! their resolution and pinning warnings (docs/cli.md, docs/physics.md §2.6). The sharp
//! JKR-type criterion (`law = "jkr"`, the default) is built in `pipeline.rs`.

use crate::checks::positive;
use crate::error::{ErrorKind, ScenarioError};
use crate::model::{AdhesionLaw, AdhesionSection, LawName, ScenarioFile, ValidScenario};
use crate::results::RunResults;
use adhesim::analysis::reference::{maugis_parameter, MaugisDugdale};
use adhesim::{
    CohesiveLaw, CohesiveParams, CohesiveSolver, Dugdale, ElasticMaterial, Exponential, Grid, Indenter, Profile,
    Trapezoid,
};
use anyhow::{bail, Result};

/// The smallest trapezoid softening fraction s a run takes. The cohesive rounds stop
/// once no traction changes by more than the law's resolution σ0·GAP_RESOLUTION/s
/// (`GAP_RESOLUTION` = 1e-7 of the range, the gap error of the compressive solve, in
/// adhesim's solver/cohesive/trapezoid.rs): at s ≤ 1e-7 that reaches σ0, the largest change
/// there is, so every step stopped after its first round and no element let go within it
/// (s = 1e-9: a dissipated energy of 0 where Dugdale's is 3.23e-6). 1e-6 keeps the stop
/// at σ0/10 at most; below it the law is Dugdale's to one part in a million of its range.
pub(crate) const MIN_SOFTENING_FRACTION: f64 = 1e-6;

/// The law of `section`: each law's own keys required and checked, the other laws'
/// keys refused (an unknown key, naming the law it belongs to).
pub(crate) fn adhesion_law(section: &AdhesionSection) -> Result<AdhesionLaw> {
    let law = section.law.unwrap_or_default();
    let name = law.name();
    let stray = |key: &str, value: Option<f64>| -> Result<()> {
        let Some(value) = value else { return Ok(()) };
        bail!(ScenarioError::new(
            ErrorKind::UnknownKey,
            format!("adhesion.{key} is not a key of adhesion.law = \"{name}\" (got adhesion.{key} = {value}; cohesive_stress belongs to \"dugdale\" and \"trapezoid\", range to \"exponential\", softening_fraction to \"trapezoid\")")
        )
        .with_key(format!("adhesion.{key}"))
        .with_value(value.to_string())
        .with_requirement(format!("absent with adhesion.law = \"{name}\"")))
    };
    let required = |key: &str, value: Option<f64>, what: &str| -> Result<f64> {
        let Some(value) = value else {
            bail!(ScenarioError::missing(
                &format!("adhesion.{key}"),
                format!("with adhesion.law = \"{name}\""),
                format!("adhesion.law = \"{name}\" needs adhesion.{key} ({what})")
            ));
        };
        // A law parameter beyond 1e-150..1e150 degenerates the law: cohesive_stress =
        // 5e-324 gave F_ad = 0, range = 5e-324 NaN tractions (the usable magnitudes of
        // the roughness keys).
        positive(&format!("adhesion.{key}"), value)?;
        crate::guards::usable_positive(&format!("adhesion.{key}"), value)
    };
    Ok(match law {
        LawName::Jkr => {
            stray("cohesive_stress", section.cohesive_stress)?;
            stray("range", section.range)?;
            stray("softening_fraction", section.softening_fraction)?;
            AdhesionLaw::Jkr
        }
        LawName::Dugdale => {
            stray("range", section.range)?;
            stray("softening_fraction", section.softening_fraction)?;
            AdhesionLaw::Dugdale {
                cohesive_stress: required("cohesive_stress", section.cohesive_stress, "σ0 > 0")?,
            }
        }
        LawName::Exponential => {
            stray("cohesive_stress", section.cohesive_stress)?;
            stray("softening_fraction", section.softening_fraction)?;
            AdhesionLaw::Exponential {
                range: required("range", section.range, "ρ > 0")?,
            }
        }
        LawName::Trapezoid => {
            stray("range", section.range)?;
            let cohesive_stress = required("cohesive_stress", section.cohesive_stress, "σ0 > 0")?;
            let softening_fraction = required("softening_fraction", section.softening_fraction, "0 < s ≤ 1")?;
            if softening_fraction > 1.0 {
                bail!(ScenarioError::invalid(
                    "adhesion.softening_fraction",
                    softening_fraction,
                    "in (0, 1] (the fraction of the range over which the traction falls)"
                ));
            }
            check_softening_resolved(softening_fraction)?;
            AdhesionLaw::Trapezoid {
                cohesive_stress,
                softening_fraction,
            }
        }
    })
}

/// Refuses a softening fraction the cohesive rounds cannot resolve ([`MIN_SOFTENING_FRACTION`]).
fn check_softening_resolved(fraction: f64) -> Result<()> {
    if fraction >= MIN_SOFTENING_FRACTION {
        return Ok(());
    }
    bail!(ScenarioError::invalid_as(
        "adhesion.softening_fraction",
        fraction,
        format!("≥ {MIN_SOFTENING_FRACTION:e}"),
        format!(
            "adhesion.softening_fraction = {fraction:e} is below {MIN_SOFTENING_FRACTION:e}: the cohesive rounds resolve the gap to 1e-7 of the range, a traction of σ0·1e-7/s = {:.3e}·σ0 on the softening part, too coarse to let elements go (at s ≤ 1e-7 nothing is released: no dissipation); s → 0 is Maugis–Dugdale: use adhesion.law = \"dugdale\" (or s ≥ {MIN_SOFTENING_FRACTION:e})",
            1e-7 / fraction
        )
    ));
}

impl ScenarioFile {
    /// Checks `adhesion.law` with its keys ([`adhesion_law`]) and the work of
    /// adhesion a cohesive law needs, and returns the law with Maugis' parameter of a
    /// Dugdale or trapezoidal law and Tabor's of an exponential law on a curved indenter
    /// (for `derived`).
    pub(crate) fn validate_law(
        &self,
        indenter: &Indenter,
        contact_modulus: f64,
    ) -> Result<(AdhesionLaw, Option<f64>, Option<f64>)> {
        let law = adhesion_law(&self.adhesion)?;
        if law == AdhesionLaw::Jkr {
            return Ok((law, None, None));
        }
        let gamma = self.adhesion.work_of_adhesion;
        if gamma <= 0.0 {
            let name = law.name().name();
            bail!(ScenarioError::invalid_as(
                "adhesion.work_of_adhesion",
                gamma,
                format!("> 0 with adhesion.law = \"{name}\""),
                format!("adhesion.law = \"{name}\" needs adhesion.work_of_adhesion > 0, got {gamma}")
            ));
        }
        let Some(radius) = indenter.radius_of_curvature() else {
            return Ok((law, None, None));
        };
        Ok(match law {
            AdhesionLaw::Dugdale { cohesive_stress } | AdhesionLaw::Trapezoid { cohesive_stress, .. } => (
                law,
                Some(maugis_parameter(radius, contact_modulus, gamma, cohesive_stress)),
                None,
            ),
            AdhesionLaw::Exponential { range } => {
                (law, None, Some(tabor_parameter(radius, contact_modulus, gamma, range)))
            }
            AdhesionLaw::Jkr => (law, None, None),
        })
    }
}

/// An indentation with a law of unbounded support (exponential) starts the law's
/// negligible separation (ρ·ln 1000 = 6.9ρ, the protocol's `NormalSolver::approach_margin`)
/// above first contact, in depth steps that the step cap of `protocol.steps` /
/// `protocol.step` did not count: `range = 1e3` made about 3.5·10⁸ approach steps.
/// Refused, with the estimate and the keys to change, beyond [`crate::MAX_STEPS`]; `keys`
/// names the inputs that set `depth_step`.
pub(crate) fn check_approach_margin(
    law: &AdhesionLaw,
    start_depth: f64,
    max_depth: f64,
    depth_step: f64,
    keys: &str,
) -> Result<()> {
    let AdhesionLaw::Exponential { range } = *law else {
        return Ok(());
    };
    let margin = Exponential::new(range, Vec::new()).negligible_separation();
    let steps = ((max_depth - (start_depth - margin)) / depth_step).ceil();
    if steps <= crate::MAX_STEPS as f64 {
        return Ok(());
    }
    let show = crate::guards::show;
    bail!(ScenarioError::derived(
        show(steps),
        format!("at most {} approach steps", crate::MAX_STEPS),
        format!(
            "adhesion.law = \"exponential\" with adhesion.range = {} starts the approach {} (ρ·ln 1000) above first contact; in depth steps of {} (from {keys}) that is about {} approach steps, more than the cap of {}: choose a smaller adhesion.range or a larger depth step",
            show(range),
            show(margin),
            show(depth_step),
            show(steps),
            crate::MAX_STEPS
        )
    )
    .with_key("adhesion.range"))
}

/// Tabor's parameter μ = (Rγ0²/(E*²ρ³))^(1/3) of the exponential law of range ρ on a
/// sphere of radius R (Tabor 1977, *J. Colloid Interface Sci.* 58, 2, with ρ for the
/// equilibrium spacing): DMT-like for μ → 0, JKR-like for μ → ∞.
pub(crate) fn tabor_parameter(radius: f64, contact_modulus: f64, work_of_adhesion: f64, range: f64) -> f64 {
    (radius * work_of_adhesion * work_of_adhesion / (contact_modulus * contact_modulus * range.powi(3))).cbrt()
}

/// The cohesive solver of a scenario whose law is not `jkr` (None for `jkr`), with the
/// work of adhesion per element `gamma`.
pub(crate) fn cohesive_solver(
    law: &AdhesionLaw,
    grid: Grid,
    material: ElasticMaterial,
    gamma: &[f64],
) -> Option<CohesiveSolver> {
    let law: Box<dyn CohesiveLaw> = match *law {
        AdhesionLaw::Jkr => return None,
        AdhesionLaw::Dugdale { cohesive_stress } => Box::new(Dugdale::new(cohesive_stress, gamma.to_vec())),
        AdhesionLaw::Exponential { range } => Box::new(Exponential::new(range, gamma.to_vec())),
        AdhesionLaw::Trapezoid {
            cohesive_stress,
            softening_fraction,
        } => Box::new(Trapezoid::new(cohesive_stress, softening_fraction, gamma.to_vec())),
    };
    Some(CohesiveSolver::new(grid, material, law, CohesiveParams::default()))
}

/// Elements across the cohesive zone below which a resolution warning is given: 15 keep
/// the pull-off within about 3 % at λ ≥ 1 (docs/validation.md §10).
pub(crate) const MIN_ZONE_ELEMENTS: f64 = 15.0;

/// A warning when the Dugdale zone at Maugis' pull-off of the indenter's radius of
/// curvature spans fewer than [`MIN_ZONE_ELEMENTS`] elements: the zone's edge is resolved
/// to an element, and the pull-off error is first order in Δ/(c − a), measured
/// ≈ +0.4·Δ/(c − a) at λ = 1 and 2.
///
/// For the exponential law: [`range_resolution_warning`].
pub(crate) fn zone_resolution_warning(
    law: &AdhesionLaw,
    work_of_adhesion: f64,
    grid: &Grid,
    indenter: &Indenter,
    contact_modulus: f64,
) -> Option<String> {
    if let AdhesionLaw::Exponential { range } = *law {
        return range_resolution_warning(range, work_of_adhesion, grid, contact_modulus);
    }
    let (Some(stress), Some(radius)) = (law.cohesive_stress(), indenter.radius_of_curvature()) else {
        return None;
    };
    let model = MaugisDugdale {
        radius,
        contact_modulus,
        work_of_adhesion,
        cohesive_stress: stress,
    };
    let point = model.at_max_adhesive_force();
    let width = point.zone_radius - point.contact_radius;
    // The longer element side: the coarser direction decides the resolution.
    let delta = grid.dx().max(grid.dy());
    let elements = width / delta;
    // The first-order estimate +0.4·Δ/(c − a) was measured down to about one element; below,
    // the zone is not resolved at all and no percentage is meaningful.
    let error = if elements >= 1.0 {
        format!(
            "may be too large by up to about {:.0} % (first order in the element size, docs/validation.md §10)",
            40.0 / elements
        )
    } else {
        "is not Maugis': with the zone inside one element each element detaches at sigma0 like a stress criterion (docs/validation.md §10)"
            .into()
    };
    (elements < MIN_ZONE_ELEMENTS).then(|| {
        format!(
            "the cohesive zone at Maugis' pull-off (c - a = {width:.4e}, adhesion.cohesive_stress = {stress}) spans {elements:.1} elements (grid.size/grid.n = {delta:.4e}), fewer than {MIN_ZONE_ELEMENTS}: the pull-off force {error}; raise grid.n or lower grid.size"
        )
    })
}

/// Elements across the exponential law's cohesive length below which a resolution warning
/// is given (docs/validation.md §11).
pub(crate) const MIN_RANGE_ELEMENTS: f64 = 2.0;

/// A warning when the exponential law's cohesive length ℓ = πE*ρ²/(4γ0) spans fewer than
/// [`MIN_RANGE_ELEMENTS`] elements. ℓ is the length of the zone at a crack tip whose
/// stress intensity √(2E*γ0) is carried by the law's largest traction γ0/ρ (the
/// plane-strain Dugdale zone πE*γ0/(4σ0²) at σ0 = γ0/ρ; Maugis 2000, *Contact, Adhesion
/// and Rupture of Elastic Solids*, §5); it does not depend on the indenter. Measured on
/// the smooth sphere at μ = 2: pull-off +19 % at ℓ = 0.5Δ, +2.1 % at 1Δ, 0.1 % at 2Δ
/// (against N = 128).
pub(crate) fn range_resolution_warning(range: f64, gamma: f64, grid: &Grid, contact_modulus: f64) -> Option<String> {
    if gamma.is_nan() || gamma <= 0.0 {
        return None;
    }
    let length = std::f64::consts::PI * contact_modulus * range * range / (4.0 * gamma);
    let delta = grid.dx().max(grid.dy());
    let elements = length / delta;
    (elements < MIN_RANGE_ELEMENTS).then(|| {
        format!(
            "the exponential law's cohesive length pi*E*rho^2/(4*gamma0) = {length:.4e} (adhesion.range = {}, adhesion.work_of_adhesion = {}) spans {elements:.2} elements (the larger element side {delta:.4e}), fewer than {MIN_RANGE_ELEMENTS}: the range is under-resolved and the pull-off force too large (measured +2 % at 1 element, +19 % at 0.5, docs/validation.md §11); raise grid.n, lower grid.size or widen adhesion.range",
            crate::guards::show(range),
            crate::guards::show(gamma)
        )
    })
}

/// Elements across the trapezoid's softening length s·ℓ (ℓ = πE*γ0/(4σ0²)) below which a
/// roll, slide or translation is warned about: measured on the smooth sphere of
/// `fig6.toml`, the lattice pinning is 0.49, 0.16 and 0.006 of Dugdale's at s·ℓ = 0.4, 0.5
/// and 1 element, and below 1e-7 of it from 1.5 (docs/validation.md §16).
pub(crate) const MIN_SOFTENING_ELEMENTS: f64 = 1.0;

/// The plane-strain Dugdale zone at a crack tip, ℓ = πE*γ0/(4σ0²) (Maugis 2000, *Contact,
/// Adhesion and Rupture of Elastic Solids*, §5): what a cohesive stress σ0 needs to carry
/// the stress intensity √(2E*γ0).
pub(crate) fn dugdale_zone_length(work_of_adhesion: f64, cohesive_stress: f64, contact_modulus: f64) -> f64 {
    std::f64::consts::PI * contact_modulus * work_of_adhesion / (4.0 * cohesive_stress * cohesive_stress)
}

/// Dugdale's lattice pinning per unit contact width, γ0·Δ/ℓ = 4σ0²Δ/(πE*) with
/// ℓ = πE*γ0/(4σ0²): an element carries σ0 or nothing, so under translation the zone's edge
/// moves by whole elements, and a contact 2b wide meets a spurious tangential resistance of
/// about γ0·2b·Δ/ℓ, first order in Δ (measured 0.88–1.11 of it on the smooth sphere of
/// `fig6.toml`, whose true rolling resistance is 0, docs/validation.md §15).
pub(crate) fn dugdale_pinning_per_width(cohesive_stress: f64, element: f64, contact_modulus: f64) -> f64 {
    4.0 * cohesive_stress * cohesive_stress * element / (std::f64::consts::PI * contact_modulus)
}

/// Elements across Dugdale's zone ℓ below which the pinning estimate was not measured
/// (0.78 of it at ℓ = 0.5Δ, 0.88–1.11 from 1Δ, docs/validation.md §15).
const MIN_PINNING_ESTIMATE_ELEMENTS: f64 = 0.5;

/// The caveat appended to the pinning estimate when ℓ spans fewer than
/// [`MIN_PINNING_ESTIMATE_ELEMENTS`] elements.
fn pinning_caveat(zone_elements: f64) -> String {
    if zone_elements < MIN_PINNING_ESTIMATE_ELEMENTS {
        format!(
            " (here l spans {zone_elements:.2e} elements, fewer than {MIN_PINNING_ESTIMATE_ELEMENTS}, where the estimate was not measured: each element then detaches at sigma0 like a stress criterion)"
        )
    } else {
        String::new()
    }
}

/// The ratio of two forces for a message: two decimals, or a power of ten when far from 1.
fn ratio_text(ratio: f64) -> String {
    if (0.01..100.0).contains(&ratio.abs()) {
        format!("{ratio:.2}")
    } else {
        format!("{ratio:.2e}")
    }
}

/// A warning when a translation (roll, slide, translate) runs a law whose zone's edge the
/// grid pins: Dugdale always ([`dugdale_pinning_per_width`]); the trapezoidal law when its
/// softening length s·ℓ spans fewer than [`MIN_SOFTENING_ELEMENTS`] elements.
pub(crate) fn translation_pinning_warning(
    law: &AdhesionLaw,
    gamma: f64,
    grid: &Grid,
    contact_modulus: f64,
    translation: Option<&str>,
) -> Option<String> {
    let kind = translation?;
    let stress = law.cohesive_stress()?;
    let length = dugdale_zone_length(gamma, stress, contact_modulus);
    let delta = grid.dx().max(grid.dy());
    match *law {
        AdhesionLaw::Dugdale { .. } => Some(format!(
            "adhesion.law = \"dugdale\" with protocol.kind = \"{kind}\": an element carries sigma0 or nothing, so the zone's edge moves by whole elements and the grid pins it, a spurious tangential force of about gamma0*2b*delta/l = {:.4e} times the contact width 2b (l = pi*E*gamma0/(4*sigma0^2) = {length:.4e} spans {:.2} elements of {delta:.4e}; first order in the element size, measured 0.88-1.11 of the estimate on a smooth sphere, whose true rolling resistance is 0, docs/validation.md §15){}; it can exceed the resistance of the surface itself: compare summary.json's estimate with the mean tangential force, or use adhesion.law = \"trapezoid\" with a resolved softening length (§16)",
            dugdale_pinning_per_width(stress, delta, contact_modulus),
            length / delta,
            pinning_caveat(length / delta)
        )),
        AdhesionLaw::Trapezoid {
            softening_fraction: fraction,
            ..
        } => {
            let elements = fraction * length / delta;
            (elements < MIN_SOFTENING_ELEMENTS).then(|| {
                format!(
                    "the trapezoidal law's softening length s*pi*E*gamma0/(4*sigma0^2) = {:.4e} (adhesion.softening_fraction = {fraction}, adhesion.cohesive_stress = {stress}) spans {elements:.2} elements (the larger element side {delta:.4e}), fewer than {MIN_SOFTENING_ELEMENTS}: under translation the zone's edge is pinned by the grid, a spurious tangential force of up to about half of Dugdale's gamma0*2b*delta/l (docs/validation.md §16); raise adhesion.softening_fraction or grid.n, or lower adhesion.cohesive_stress",
                    fraction * length
                )
            })
        }
        AdhesionLaw::Jkr | AdhesionLaw::Exponential { .. } => None,
    }
}

/// After a Dugdale roll, slide or translation: the lattice pinning
/// ([`dugdale_pinning_per_width`]) for the run's mean contact width, set beside its mean
/// tangential force, so that a reader sees how much of F_T the grid may have made.
pub(crate) fn dugdale_pinning_estimate(scenario: &ValidScenario, results: &RunResults) -> Option<String> {
    let (
        AdhesionLaw::Dugdale {
            cohesive_stress: stress,
        },
        RunResults::Translation(results),
    ) = (scenario.law, results)
    else {
        return None;
    };
    let delta = scenario.grid.dx().max(scenario.grid.dy());
    let width = 2.0 * results.contact_half_width;
    let modulus = scenario.material.contact_modulus();
    let pinning = width * dugdale_pinning_per_width(stress, delta, modulus);
    let zone = dugdale_zone_length(scenario.gamma0, stress, modulus);
    let against = match results.mean_tangential_force {
        Some(force) if force.is_finite() && pinning > 0.0 => {
            format!(
                "against the mean tangential force {force:.4e} ({} of it)",
                ratio_text(force / pinning)
            )
        }
        _ => "the run has no mean tangential force to set beside it".to_string(),
    };
    Some(format!(
        "Dugdale's lattice pinning for this run's mean contact width 2b = {width:.4e}: gamma0*2b*delta/l = {pinning:.4e}, {against}; the part of the force the grid makes is first order in the element size (docs/validation.md §15){}",
        pinning_caveat(zone / delta)
    ))
}
