//! `ScenarioFile::validate`: every value checked, the library objects built. Every error
//! names the dotted key at fault and the value it had (`indenter.radius must be > 0, got
//! -1`); nothing here panics on bad input.

use crate::checks::{check_periodic_depth, finite, grid_keys, non_negative, positive};
use crate::cohesive::{check_approach_margin, translation_pinning_warning, zone_resolution_warning};
use crate::error::ScenarioError;
use crate::guards::{resolution_warnings, step_count};
use crate::model::*;
use crate::parse::read_height_map;
use crate::roughness::{roughness_on_grid, RoughnessMap};
use crate::sections::{validate_adhesion, validate_grid, validate_layer, validate_material};
use crate::validated::ValidatedSections;
use adhesim::analysis::reference::{johnson_parameter, Jkr};
use adhesim::analysis::scale::adhesive_force_scale;
use adhesim::geometry::{EllipticPunch, FlatPunch, RoughProfile, Sphere, Topography, WavySphere};
use adhesim::solver::critical_stress;
use adhesim::{ElasticMaterial, Grid, Indenter, Profile};
use anyhow::{bail, Result};
use std::path::Path;

impl ScenarioFile {
    /// A layer (`material.thickness`) runs every protocol, without adhesion or with the
    /// JKR-type rule: a cohesive law's tractions across gaps are the half-space's
    /// (docs/physics.md §9); friction's limits on a layer are checked with `[friction]`. The
    /// JKR-type solver runs its reference rule there (full solves, no local replays: the
    /// certificates and local rules are derived for the half-space's kernel), so
    /// `solver.predicted_growth` does not apply.
    fn check_layer_pairing(&self) -> Result<()> {
        let law = self.adhesion.law.unwrap_or_default();
        if law != LawName::Jkr {
            bail!(ScenarioError::invalid_as(
                "adhesion.law",
                format!("\"{}\"", law.name()),
                "\"jkr\" with material.thickness",
                format!(
                    "a cohesive law on a layer (material.thickness) is not implemented: adhesion.law = \"jkr\" (the sharp rule) or no adhesion, got \"{}\"",
                    law.name()
                )
            ));
        }
        if let Some((key, value)) = self
            .solver
            .as_ref()
            .and_then(|solver| solver.given().into_iter().next())
        {
            bail!(ScenarioError::invalid_as(
                key,
                value,
                "absent with material.thickness",
                format!("{key} acts on the half-space's kernel; on a layer the adhesive solver runs its reference rule: remove the key")
            ));
        }
        Ok(())
    }

    /// Checks every value and builds the library objects, one section after the other.
    /// `base` resolves relative file paths.
    pub(crate) fn validate_sections(self, base: &Path) -> Result<ValidScenario> {
        let grid = validate_grid(&self.grid)?;
        let material = validate_material(&self.material)?;
        let layer = validate_layer(&self.material, &grid)?;
        if layer.is_some() {
            self.check_layer_pairing()?;
        }
        let (roughness, substrate_roughness) = self.roughness_maps(&grid, base)?;
        let (indenter, heights, start_depth) = validate_indenter(&self.indenter, &grid, base, roughness.as_ref())?;
        self.check_height_span(&heights, start_depth)?;
        let shape = self.indenter.shape();
        let (gamma0, gamma) = validate_adhesion(&self.adhesion, &grid, &indenter, shape, base)?;
        let (jkr, mut derived) = derived_scales(&grid, &material, &indenter, gamma0);
        let law;
        (law, derived.maugis_parameter, derived.tabor_parameter) =
            self.validate_law(&indenter, material.contact_modulus())?;
        self.check_derived(&derived)?;
        self.check_field_stresses(&grid, &gamma)?;
        let mut warnings = resolution_warnings(&grid, &indenter, &derived);
        warnings.extend(zone_resolution_warning(
            &law,
            gamma0,
            &grid,
            &indenter,
            material.contact_modulus(),
        ));
        let kind = self.protocol.kind();
        warnings.extend(translation_pinning_warning(
            &law,
            gamma0,
            &grid,
            material.contact_modulus(),
            kind.is_translation().then(|| kind.name()),
        ));
        for map in roughness.iter().chain(&substrate_roughness) {
            warnings.extend(map.warnings.iter().cloned());
        }
        derived.roughness = roughness.as_ref().map(|map| map.statistics);
        derived.substrate_roughness = substrate_roughness.as_ref().map(|map| map.statistics);
        let unit = depth_unit(&self.protocol, shape, jkr.as_ref(), gamma0)?;
        if !(unit.is_finite() && unit > 0.0) {
            bail!(ScenarioError::invalid_as(
                "protocol.depth_unit",
                "\"jkr\"",
                "a positive unit |d_JKR|",
                format!("protocol.depth_unit = \"jkr\": the unit |d_JKR| = {unit:e} is not a positive number")
            ));
        }
        let inputs = ValidatedSections {
            grid,
            material,
            layer,
            gamma,
            gamma0,
            law,
            indenter,
            unit,
            jkr,
            derived,
            substrate_roughness: substrate_roughness.map(|map| map.heights),
        };
        self.check_friction_pairing()?;
        self.check_aging_pairing()?;
        let first_contact_factor = self.first_contact_factor(inputs.gamma0)?;
        if let Some(solver) = &self.solver {
            solver.check(inputs.gamma0 > 0.0, inputs.law.name(), self.grid.boundary)?;
        }
        let mut valid = match self.protocol.kind() {
            ProtocolKind::Shear => self.validate_shear(inputs, heights, start_depth)?,
            kind if kind.is_translation() => self.validate_translation(inputs)?,
            _ => self.validate_indentation(inputs, heights, start_depth)?,
        };
        warnings.extend(crate::guards::contact_radius_warning(&valid));
        warnings.extend(crate::guards::single_step_warning(&valid));
        valid.warnings = warnings;
        valid.roughness = roughness.map(|map| map.heights);
        valid.first_contact_factor = first_contact_factor;
        Ok(valid)
    }

    /// `[roughness]` (indent_pulloff only) and `[substrate_roughness]` (slide only) on the grid.
    fn roughness_maps(&self, grid: &Grid, base: &Path) -> Result<(Option<RoughnessMap>, Option<RoughnessMap>)> {
        let kind = self.protocol.kind();
        if self.roughness.is_some() && kind.is_translation() {
            bail!(ScenarioError::invalid_as(
                "protocol.kind",
                format!("\"{}\"", kind.name()),
                "\"indent_pulloff\" with [roughness]",
                format!(
                    "[roughness] roughens the indenter of protocol.kind = \"indent_pulloff\" only, got \"{}\" (a slide's substrate takes [substrate_roughness])",
                    kind.name()
                )
            ));
        }
        if self.substrate_roughness.is_some() && kind != ProtocolKind::Slide {
            bail!(ScenarioError::invalid_as(
                "protocol.kind",
                format!("\"{}\"", kind.name()),
                "\"slide\" with [substrate_roughness]",
                format!(
                    "[substrate_roughness] is the substrate of protocol.kind = \"slide\" only, got \"{}\" (an indenter takes [roughness])",
                    kind.name()
                )
            ));
        }
        let roughness = self
            .roughness
            .as_ref()
            .map(|section| roughness_on_grid(section, "roughness", grid, base))
            .transpose()?;
        let substrate = self
            .substrate_roughness
            .as_ref()
            .map(|section| roughness_on_grid(section, "substrate_roughness", grid, base))
            .transpose()?;
        Ok((roughness, substrate))
    }

    /// `[protocol]` of kind indent_pulloff (and `[output]`).
    fn validate_indentation(
        self,
        inputs: ValidatedSections,
        heights: Vec<f64>,
        start_depth: f64,
    ) -> Result<ValidScenario> {
        let ValidatedSections {
            grid,
            material,
            layer,
            gamma,
            gamma0,
            law,
            indenter,
            unit,
            jkr,
            derived,
            ..
        } = inputs;
        let contact_modulus = material.contact_modulus();
        let ProtocolSection::IndentPulloff(p) = &self.protocol else {
            bail!("[protocol]: validate_indentation needs protocol.kind = \"indent_pulloff\"");
        };
        if !self.analysis.is_empty() {
            bail!(ScenarioError::invalid_as(
                "protocol.kind",
                "\"indent_pulloff\"",
                "\"roll\" or \"slide\" with [analysis]",
                "[analysis] (gamma_approach, gamma_pulloff, tau0) is used by protocol.kind = \"roll\" / \"slide\" only, got \"indent_pulloff\""
            ));
        }
        let raw_max_depth = p.max_depth;
        let max_depth = finite("protocol.max_depth", raw_max_depth)? * unit;
        if max_depth <= start_depth {
            let requirement = format!("> {:.6e} (the depth of first contact)", start_depth / unit);
            bail!(ScenarioError::invalid_as(
                "protocol.max_depth",
                raw_max_depth,
                requirement,
                format!(
                    "protocol.max_depth must exceed the depth of first contact ({:.6e} in depth_unit), got {}",
                    start_depth / unit,
                    raw_max_depth
                )
            ));
        }
        check_periodic_depth(&grid, &heights, "protocol.max_depth", raw_max_depth, unit)?;
        let (depth_step, keys) = match (p.steps, p.step) {
            (Some(steps), None) => {
                let steps = step_count("protocol.steps", steps)?;
                (
                    (max_depth - start_depth) / steps as f64,
                    "protocol.steps, protocol.max_depth",
                )
            }
            (None, Some(step)) => (
                positive("protocol.step", step)? * unit,
                "protocol.step, protocol.max_depth",
            ),
            (Some(steps), Some(step)) => bail!(ScenarioError::invalid_as(
                "protocol.step",
                step,
                "absent when protocol.steps is given",
                format!("give either protocol.steps or protocol.step, not both (protocol.steps = {steps}, protocol.step = {step})")
            )),
            (None, None) => bail!(ScenarioError::missing(
                "protocol.steps",
                "protocol.steps or protocol.step",
                "missing key `protocol.steps` (or `protocol.step`)"
            )),
        };
        let approach_steps = self.check_step(start_depth, max_depth, depth_step, keys)?;
        check_approach_margin(&law, start_depth, max_depth, depth_step, keys)?;
        let max_retract_steps = match p.max_retract_steps {
            Some(s) if s < 1 => bail!(ScenarioError::invalid("protocol.max_retract_steps", s, ">= 1")),
            Some(s) => s as usize,
            None => (20 * approach_steps).max(1000),
        };

        let jump_force_threshold = self.output_checks(gamma0, &jkr, &indenter, contact_modulus)?;
        let hold = self.validate_hold(p, gamma0)?;

        Ok(ValidScenario {
            file: self,
            grid,
            material,
            layer,
            gamma,
            gamma0,
            first_contact_factor: None,
            law,
            indenter,
            heights,
            start_depth,
            max_depth,
            depth_step,
            approach_steps,
            max_retract_steps,
            jkr,
            derived,
            jump_force_threshold,
            translation: None,
            shear: None,
            hold,
            warnings: Vec::new(),
            roughness: None,
        })
    }

    /// Checks `[output]` and returns the absolute jump force threshold.
    pub(crate) fn output_checks(
        &self,
        gamma0: f64,
        jkr: &Option<Jkr>,
        indenter: &Indenter,
        contact_modulus: f64,
    ) -> Result<f64> {
        let o = &self.output;
        for &s in &o.snapshot_steps {
            if s < 0 {
                bail!(ScenarioError::invalid_as(
                    "output.snapshot_steps",
                    s,
                    "steps >= 0",
                    format!("output.snapshot_steps must hold steps >= 0, got {s}")
                ));
            }
        }
        if o.snapshot_every < 0 {
            bail!(ScenarioError::invalid(
                "output.snapshot_every",
                o.snapshot_every,
                ">= 0"
            ));
        }
        if o.jump_snapshot_elements < 1 {
            bail!(ScenarioError::invalid(
                "output.jump_snapshot_elements",
                o.jump_snapshot_elements,
                ">= 1"
            ));
        }
        if o.max_snapshots < 0 {
            bail!(ScenarioError::invalid("output.max_snapshots", o.max_snapshots, ">= 0"));
        }
        non_negative("output.jump_force_threshold", o.jump_force_threshold)?;
        if let Some(radius) = o.min_fit_radius {
            non_negative("output.min_fit_radius", radius)?;
        }
        let force_scale = adhesive_force_scale(indenter, jkr.as_ref(), contact_modulus, gamma0);
        Ok(o.jump_force_threshold * force_scale)
    }
}

/// `[indenter]` (with the `[roughness]` on the grid, if any): the profile, its heights on
/// the grid and the depth of first contact.
fn validate_indenter(
    section: &IndenterSection,
    grid: &Grid,
    base: &Path,
    roughness: Option<&RoughnessMap>,
) -> Result<(Indenter, Vec<f64>, f64)> {
    // Which keys each shape takes, and that they are present, serde has checked
    // (`IndenterSection` is tagged by `shape`); the numbers' ranges are checked here.
    let shape = section.shape();
    let angle = |angle: &Option<f64>| finite("indenter.angle", angle.unwrap_or(0.0)).map(f64::to_radians);
    let indenter = match section {
        IndenterSection::Sphere { radius } => Indenter::Sphere(Sphere::new(positive("indenter.radius", *radius)?)?),
        IndenterSection::WavySphere {
            radius,
            amplitude,
            wavelength,
            angle: degrees,
        } => {
            let angle = angle(degrees)?;
            let radius = positive("indenter.radius", *radius)?;
            let amplitude = non_negative("indenter.amplitude", *amplitude)?;
            let wavelength = positive("indenter.wavelength", *wavelength)?;
            Indenter::WavySphere(WavySphere::new(radius, amplitude, wavelength, angle)?)
        }
        IndenterSection::FlatPunch { radius } => {
            Indenter::FlatPunch(FlatPunch::new(positive("indenter.radius", *radius)?)?)
        }
        IndenterSection::EllipticPunch {
            semi_axes,
            angle: degrees,
        } => {
            let angle = angle(degrees)?;
            if semi_axes.len() != 2 {
                bail!(ScenarioError::invalid(
                    "indenter.semi_axes",
                    format!("{semi_axes:?}"),
                    "[a, b]"
                ));
            }
            let a = positive("indenter.semi_axes[0]", semi_axes[0])?;
            let b = positive("indenter.semi_axes[1]", semi_axes[1])?;
            Indenter::EllipticPunch(EllipticPunch::new((a, b), angle)?)
        }
        IndenterSection::Topography { file, spacing } => {
            let spacing = spacing.map(|s| positive("indenter.spacing", s)).transpose()?;
            let (values, rows, columns, spacing) = read_height_map(&base.join(file), spacing)?;
            Indenter::Topography(Topography::new(values, rows, columns, spacing).map_err(|e| {
                ScenarioError::invalid_as(
                    "indenter.file",
                    file.display(),
                    "a usable height map",
                    format!("indenter.file = {}: {e}", file.display()),
                )
            })?)
        }
        IndenterSection::RoughSphere { .. } | IndenterSection::RoughFlat {} => {
            rough_indenter(section, grid, roughness)?
        }
    };
    let (indenter, heights) = with_roughness(indenter, grid, roughness)?;
    let start_depth = heights
        .iter()
        .copied()
        .filter(|h| h.is_finite())
        .fold(f64::INFINITY, f64::min);
    if !start_depth.is_finite() {
        bail!(ScenarioError::invalid_as(
            "grid.size",
            grid.size_x(),
            format!("a domain that holds part of the indenter (indenter.shape = \"{}\")", shape.name()),
            format!(
                "the indenter (indenter.shape = \"{}\") has no surface inside the domain ({}): enlarge grid.size or grid.n",
                shape.name(),
                grid_keys(grid)
            )
        ));
    }
    Ok((indenter, heights, start_depth))
}

/// `rough_sphere` (radius + the `[roughness]`) and `rough_flat`.
fn rough_indenter(section: &IndenterSection, grid: &Grid, roughness: Option<&RoughnessMap>) -> Result<Indenter> {
    let shape = section.shape();
    let Some(map) = roughness else {
        bail!(ScenarioError::missing(
            "roughness",
            format!("a [roughness] section with indenter.shape = \"{}\"", shape.name()),
            format!(
                "indenter.shape = \"{}\" needs a [roughness] section (roughness.file, or roughness.hurst, roughness.seed and roughness.rms_height or roughness.rms_slope)",
                shape.name()
            )
        ));
    };
    let profile = match section.radius() {
        Some(radius) => RoughProfile::rough_sphere(positive("indenter.radius", radius)?, map.heights.clone(), grid),
        None => RoughProfile::rough_flat(map.heights.clone(), grid),
    };
    Ok(Indenter::Rough(profile.map_err(|e| roughness_error(&e))?))
}

/// The indenter and its heights on the grid with the `[roughness]`: a sphere with one is a
/// `rough_sphere`; on the other shapes the roughness is subtracted from the finite heights
/// (peaks towards the half-space) and the heights are shifted to first contact at zero,
/// while the smooth shape keeps giving the scales (JKR, force scale, resolution warnings).
fn with_roughness(indenter: Indenter, grid: &Grid, roughness: Option<&RoughnessMap>) -> Result<(Indenter, Vec<f64>)> {
    let indenter = match (indenter, roughness) {
        (Indenter::Sphere(sphere), Some(map)) => Indenter::Rough(
            RoughProfile::rough_sphere(sphere.radius(), map.heights.clone(), grid).map_err(|e| roughness_error(&e))?,
        ),
        (other, _) => other,
    };
    let mut heights = indenter.heights(grid);
    if let (Some(map), false) = (roughness, matches!(indenter, Indenter::Rough(_))) {
        for (z, h) in heights.iter_mut().zip(&map.heights) {
            *z -= h;
        }
        let lowest = heights
            .iter()
            .copied()
            .filter(|z| z.is_finite())
            .fold(f64::INFINITY, f64::min);
        if lowest.is_finite() {
            heights.iter_mut().for_each(|z| *z -= lowest);
        }
    }
    Ok((indenter, heights))
}

/// The library's refusal of a `[roughness]` map as a scenario error (the section as key).
fn roughness_error(error: &impl std::fmt::Display) -> anyhow::Error {
    ScenarioError::new(crate::error::ErrorKind::InvalidValue, format!("[roughness]: {error}"))
        .with_key("roughness")
        .with_requirement("a roughness map the library accepts")
        .into()
}

/// The JKR scales and the other derived numbers of `summary.json`.
fn derived_scales(grid: &Grid, material: &ElasticMaterial, indenter: &Indenter, gamma0: f64) -> (Option<Jkr>, Derived) {
    let contact_modulus = material.contact_modulus();
    let delta = grid.dx();
    // σ_c of rectangular elements: that of the energy-equivalent square (physics.md §2.2).
    let detachment_size = adhesim::solver::detachment_element_size(grid.dx(), grid.dy());
    let jkr = match (gamma0 > 0.0, indenter.radius_of_curvature()) {
        (true, Some(radius)) => Some(Jkr {
            radius,
            contact_modulus,
            work_of_adhesion: gamma0,
        }),
        _ => None,
    };
    let johnson = match &indenter {
        Indenter::WavySphere(w) if w.waviness().amplitude() > 0.0 => Some(johnson_parameter(
            w.waviness().wavelength(),
            w.waviness().amplitude(),
            gamma0,
            contact_modulus,
        )),
        _ => None,
    };
    let derived = Derived {
        f_jkr: jkr.map(|j| j.critical_force()),
        d_jkr: jkr.map(|j| j.critical_depth()),
        a_jkr: jkr.map(|j| j.critical_radius()),
        johnson_parameter: johnson,
        element_size: delta,
        element_size_y: (grid.dy() != delta).then(|| grid.dy()),
        critical_stress: (gamma0 > 0.0).then(|| critical_stress(contact_modulus, gamma0, detachment_size)),
        maugis_parameter: None,
        tabor_parameter: None,
        roughness: None,
        substrate_roughness: None,
    };
    (jkr, derived)
}

/// The length of one `protocol.depth_unit`.
fn depth_unit(section: &ProtocolSection, shape: ShapeName, jkr: Option<&Jkr>, gamma0: f64) -> Result<f64> {
    let p = section;
    if p.kind().is_translation() && !matches!(shape, ShapeName::Sphere | ShapeName::WavySphere) {
        bail!(ScenarioError::invalid_as(
            "indenter.shape",
            format!("\"{}\"", shape.name()),
            format!(
                "\"wavy_sphere\" or \"sphere\" with protocol.kind = \"{}\"",
                p.kind().name()
            ),
            format!(
                "protocol.kind = \"{}\" needs indenter.shape = \"wavy_sphere\" or \"sphere\", got \"{}\"",
                p.kind().name(),
                shape.name()
            )
        ));
    }
    Ok(match p.depth_unit() {
        DepthUnit::Length => 1.0,
        DepthUnit::Jkr => match jkr {
            Some(j) => j.critical_depth().abs(),
            None => bail!(ScenarioError::invalid_as(
                "protocol.depth_unit",
                "\"jkr\"",
                "adhesion.work_of_adhesion > 0 and a curved indenter",
                format!(
                    "protocol.depth_unit = \"jkr\" needs adhesion.work_of_adhesion > 0 (got {gamma0}) and a curved indenter (indenter.shape = \"{}\")",
                    shape.name()
                )
            )),
        },
    })
}
