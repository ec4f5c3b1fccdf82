//! The sections checked on their own: `[grid]`, `[material]` and `[adhesion]` (γ0 and γ per
//! element). Every error names the key at fault, its value and what it must satisfy.

use crate::checks::{grid_keys, non_negative, positive};
use crate::error::ScenarioError;
use crate::guards::{check_field, MAX_GRID_N};
use crate::model::*;
use crate::parse::read_npy_2d;
use adhesim::{Axis, Boundary, ElasticLayer, ElasticMaterial, Grid, GridError, Indenter, LayerBase, WorkOfAdhesion};
use anyhow::{bail, Result};
use std::path::Path;

/// `[grid]`.
pub(crate) fn validate_grid(section: &GridSection) -> Result<Grid> {
    let count = |key: &str, n: i64| -> Result<usize> {
        if n < 2 {
            return Err(ScenarioError::invalid(key, n, ">= 2").into());
        }
        if n > MAX_GRID_N {
            return Err(ScenarioError::invalid(key, n, &format!("<= {MAX_GRID_N}")).into());
        }
        Ok(n as usize)
    };
    let boundary = match section.boundary {
        BoundaryName::Free => Boundary::Free,
        BoundaryName::Periodic => Boundary::Periodic,
    };
    let grid = match (section.n, section.size) {
        // The square of every scenario before rectangular grids, built as it always was.
        (PerAxis::Both(n), PerAxis::Both(size)) => {
            Grid::new(count("grid.n", n)?, positive("grid.size", size)?, boundary)
        }
        (n, size) => {
            let keys = |key: &str, per_axis: bool| match per_axis {
                false => [key.to_string(), key.to_string()],
                true => [format!("{key}[0]"), format!("{key}[1]")],
            };
            let ([nx_key, ny_key], [sx_key, sy_key]) = (
                keys("grid.n", matches!(n, PerAxis::Axes(..))),
                keys("grid.size", matches!(size, PerAxis::Axes(..))),
            );
            let ((nx, ny), (sx, sy)) = (n.pair(), size.pair());
            Grid::rectangular(
                count(&nx_key, nx)?,
                count(&ny_key, ny)?,
                positive(&sx_key, sx)?,
                positive(&sy_key, sy)?,
                boundary,
            )
        }
    };
    grid.map_err(|e| {
        // The counts and sizes are checked above: what remains is their combination.
        let show = crate::guards::show;
        let (key, value, requirement, message) = match &e {
            // Named as every other message names its key, numbers as a person writes them
            // (it said "[grid]: grid element size size/n … Δ² = 0e0").
            GridError::ElementOutOfRange { size, n, area } => (
                "grid.size",
                show(*size),
                "an element size grid.size/grid.n in the floating-point range",
                format!(
                    "grid.size = {} with grid.n = {n} makes elements of side {} and area {}, outside the floating-point range (the area must be a normal number, 2.2e-308 to 1.8e308): choose a grid.size commensurate with grid.n",
                    show(*size),
                    show(size / *n as f64),
                    show(*area)
                ),
            ),
            _ => (
                "grid.n",
                section.n.to_string(),
                "an element count the index range holds",
                format!("grid.n = {}: {e}", section.n),
            ),
        };
        ScenarioError::invalid_as(key, value, requirement, message).into()
    })
}

/// `[material]`: E* directly, or E and ν.
pub(crate) fn validate_material(section: &MaterialSection) -> Result<ElasticMaterial> {
    let m = section;
    let material = match (m.contact_modulus, m.youngs_modulus, m.poisson_ratio) {
        (Some(e), None, None) => ElasticMaterial::new(positive("material.contact_modulus", e)?)?,
        (None, Some(e), Some(nu)) => {
            positive("material.youngs_modulus", e)?;
            if !(nu > -1.0 && nu <= 0.5) {
                bail!(ScenarioError::invalid_as(
                    "material.poisson_ratio",
                    nu,
                    "in (-1, 0.5]",
                    format!("material.poisson_ratio must lie in (-1, 0.5], got {nu}")
                ));
            }
            ElasticMaterial::from_youngs_modulus(e, nu)?
        }
        (None, Some(_), None) => bail!(ScenarioError::missing(
            "material.poisson_ratio",
            "with material.youngs_modulus",
            "material.poisson_ratio is required with material.youngs_modulus"
        )),
        (None, None, Some(_)) => bail!(ScenarioError::missing(
            "material.youngs_modulus",
            "with material.poisson_ratio",
            "material.youngs_modulus is required with material.poisson_ratio"
        )),
        (None, None, None) => bail!(ScenarioError::missing(
            "material.contact_modulus",
            "material.contact_modulus, or material.youngs_modulus and material.poisson_ratio",
            "[material] needs contact_modulus, or youngs_modulus and poisson_ratio"
        )),
        (Some(e), _, _) => bail!(ScenarioError::invalid_as(
            "material.contact_modulus",
            e,
            "absent when material.youngs_modulus or material.poisson_ratio is given",
            format!(
                "material.contact_modulus cannot be combined with material.youngs_modulus/poisson_ratio; give one form (material.contact_modulus = {e})"
            )
        )),
    };
    Ok(material)
}

/// `material.thickness` and `material.base`: an elastic layer on a rigid base, or `None`
/// for the half-space. The layer's compliance depends on ν on its own, so it needs the
/// youngs_modulus/poisson_ratio form; t ≥ Δ/16 (what a free grid resolves; a thinner
/// incompressible layer is nearly rigid and its pressures unbounded on any grid).
pub(crate) fn validate_layer(section: &MaterialSection, grid: &Grid) -> Result<Option<ElasticLayer>> {
    let Some(thickness) = section.thickness else {
        if let Some(base) = section.base {
            bail!(ScenarioError::missing(
                "material.thickness",
                "with material.base",
                format!(
                    "material.base = \"{}\" needs material.thickness (the layer's thickness); without it the body is a half-space",
                    base_name(base)
                )
            ));
        }
        return Ok(None);
    };
    positive("material.thickness", thickness)?;
    let Some(poisson_ratio) = section.poisson_ratio else {
        bail!(ScenarioError::missing(
            "material.poisson_ratio",
            "with material.thickness",
            "material.thickness needs material.youngs_modulus and material.poisson_ratio: a layer's compliance depends on ν, not on E* alone"
        ));
    };
    let element = grid.dx().max(grid.dy());
    if thickness < element / 16.0 {
        bail!(ScenarioError::invalid_as(
            "material.thickness",
            thickness,
            format!(">= {:e} (1/16 of an element)", element / 16.0),
            format!(
                "material.thickness = {thickness} is below 1/16 of the element size {element}: the grid cannot resolve the layer; refine the grid"
            )
        ));
    }
    let base = match section.base.unwrap_or_default() {
        LayerBaseName::Bonded => LayerBase::Bonded,
        LayerBaseName::Frictionless => LayerBase::Frictionless,
    };
    Ok(Some(ElasticLayer::new(thickness, poisson_ratio, base)?))
}

/// The scenario-file spelling of a base.
pub(crate) fn base_name(base: LayerBaseName) -> &'static str {
    match base {
        LayerBaseName::Bonded => "bonded",
        LayerBaseName::Frictionless => "frictionless",
    }
}

/// `[adhesion]`: the reference γ0 and γ per element.
pub(crate) fn validate_adhesion(
    section: &AdhesionSection,
    grid: &Grid,
    indenter: &Indenter,
    shape: ShapeName,
    base: &Path,
) -> Result<(f64, Vec<f64>)> {
    let gamma0 = non_negative("adhesion.work_of_adhesion", section.work_of_adhesion)?;
    let adhesion = match &section.field {
        None => WorkOfAdhesion::Uniform(gamma0),
        Some(FieldSpec::Quadratic {
            ratio_edge_to_centre,
            axis,
            half_length,
        }) => {
            let ratio = positive("adhesion.field.ratio_edge_to_centre", *ratio_edge_to_centre)?;
            let default_half_length = match (indenter, axis) {
                (Indenter::EllipticPunch(p), AxisName::X) => Some(p.semi_axes().0),
                (Indenter::EllipticPunch(p), AxisName::Y) => Some(p.semi_axes().1),
                (Indenter::FlatPunch(p), _) => Some(p.radius()),
                _ => None,
            };
            let half_length = match half_length {
                Some(h) => positive("adhesion.field.half_length", *h)?,
                None => default_half_length.ok_or_else(|| {
                    ScenarioError::missing(
                        "adhesion.field.half_length",
                        "for indenter.shapes other than punches",
                        format!(
                            "adhesion.field.half_length is required for indenter.shape = \"{}\" (defaults exist only for punches)",
                            shape.name()
                        ),
                    )
                })?,
            };
            WorkOfAdhesion::Quadratic {
                middle: gamma0,
                ratio_end_to_middle: ratio,
                half_length,
                axis: match axis {
                    AxisName::X => Axis::X,
                    AxisName::Y => Axis::Y,
                },
            }
        }
        Some(FieldSpec::Map { file }) => {
            let (values, rows, columns) = read_npy_2d(&base.join(file), "adhesion.field.file")?;
            if rows != grid.ny() || columns != grid.nx() {
                bail!(ScenarioError::invalid_as(
                    "adhesion.field.file",
                    file.display(),
                    format!("a {}×{} map (the grid's rows × columns)", grid.ny(), grid.nx()),
                    format!(
                        "adhesion.field.file = {}: the map is {rows}×{columns}, the grid is {}×{} (rows × columns; {})",
                        file.display(),
                        grid.ny(),
                        grid.nx(),
                        grid_keys(grid)
                    )
                ));
            }
            if let Some(bad) = values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
                bail!(ScenarioError::invalid_as(
                    "adhesion.field.file",
                    file.display(),
                    "a map of finite values >= 0",
                    format!(
                        "adhesion.field.file = {}: values must be finite and >= 0, found {bad}",
                        file.display()
                    )
                ));
            }
            WorkOfAdhesion::Map(values.into_iter().map(|v| v * gamma0).collect())
        }
    };
    let gamma = match adhesion.on_grid(grid) {
        Ok(gamma) => gamma,
        Err(e) => bail!(
            ScenarioError::new(crate::error::ErrorKind::InvalidValue, format!("[adhesion]: {e}"))
                .with_key("adhesion.field")
                .with_requirement("a field the library accepts")
        ),
    };
    check_field(section, grid, &gamma)?;
    if gamma0 == 0.0 && section.field.is_some() {
        bail!(ScenarioError::invalid_as(
            "adhesion.work_of_adhesion",
            0,
            "> 0 with adhesion.field",
            "adhesion.field needs adhesion.work_of_adhesion > 0, got 0"
        ));
    }
    Ok((gamma0, gamma))
}
