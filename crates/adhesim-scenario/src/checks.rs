//! The checks of single values that the sections' and protocols' validators share: a
//! number > 0, >= 0 or finite, the grid as its keys give it, a depth short of a periodic
//! cell's full contact and the depth a roll, slide, translate or shear holds; each error
//! names the key and the value. This module imports no validator, so that sections.rs,
//! roughness.rs, cohesive.rs, translation.rs and shear.rs take these checks without
//! importing validate.rs, which calls them.

use crate::error::ScenarioError;
use adhesim::{Boundary, Grid};
use anyhow::{bail, Result};

/// The grid as its keys give it: `grid.n = 64, grid.size = 0.8` for a square,
/// `grid.n = [96, 64], grid.size = [1.5, 1]` for a rectangle.
pub(crate) fn grid_keys(grid: &Grid) -> String {
    if grid.is_square() {
        format!("grid.n = {}, grid.size = {}", grid.nx(), grid.size_x())
    } else {
        format!(
            "grid.n = [{}, {}], grid.size = [{}, {}]",
            grid.nx(),
            grid.ny(),
            grid.size_x(),
            grid.size_y()
        )
    }
}

pub(crate) fn positive(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ScenarioError::invalid(key, value, "> 0").into())
    }
}

pub(crate) fn non_negative(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ScenarioError::invalid(key, value, ">= 0").into())
    }
}

pub(crate) fn finite(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ScenarioError::invalid(key, value, "finite").into())
    }
}

/// On a periodic grid the surface displacement has zero mean (K̂(0) = 0), so the mean gap
/// is mean(z) − d: the whole cell is in contact at d = mean(z) and no load goes deeper
/// (docs/physics.md §1b). `key` = `raw` (in depth units of `unit` length) is refused
/// beyond that depth, before the run, instead of failing at the step that crosses it.
pub(crate) fn check_periodic_depth(grid: &Grid, heights: &[f64], key: &str, raw: f64, unit: f64) -> Result<()> {
    if grid.boundary() != Boundary::Periodic || heights.iter().any(|z| !z.is_finite()) {
        return Ok(());
    }
    let full_contact_depth = heights.iter().sum::<f64>() / heights.len() as f64;
    let range = heights.iter().copied().fold(f64::NEG_INFINITY, f64::max)
        - heights.iter().copied().fold(f64::INFINITY, f64::min);
    // The solver's own depth tolerance (CcgParams::depth_tolerance) times the scale.
    if raw * unit > full_contact_depth + 1e-10 * range.max((raw * unit).abs()) {
        let requirement = format!(
            "<= {:.6e} (full contact of the periodic cell)",
            full_contact_depth / unit
        );
        bail!(ScenarioError::invalid_as(
            key,
            raw,
            requirement,
            format!(
                "{key} = {raw} lies beyond full contact of the periodic cell: the whole cell touches at depth \
             {:.6e} (in depth_unit; the indenter's mean height over the cell, since the displacement of a \
             periodic half-space has zero mean) and no load goes deeper. Use {key} <= {:.6e}, a larger \
             grid.size, or grid.boundary = \"free\"",
                full_contact_depth / unit,
                full_contact_depth / unit
            )
        ));
    }
    Ok(())
}

/// `protocol.depth` (in depth units of `unit` length) as a length, refused unless it goes
/// deeper than the first contact at `start_depth`: the indentation held by a roll, slide,
/// translate or shear.
pub(crate) fn held_depth(raw_depth: f64, unit: f64, start_depth: f64) -> Result<f64> {
    beyond_first_contact("protocol.depth", raw_depth, unit, start_depth)
}

/// The depth `raw_depth` of `key` (in depth units of `unit` length) as a length, refused
/// unless it goes deeper than the first contact at `start_depth`.
pub(crate) fn beyond_first_contact(key: &str, raw_depth: f64, unit: f64, start_depth: f64) -> Result<f64> {
    let depth = finite(key, raw_depth)? * unit;
    if depth <= start_depth {
        bail!(ScenarioError::invalid_as(
            key,
            raw_depth,
            format!("> {:.6e} (the depth of first contact)", start_depth / unit),
            format!(
                "{key} must exceed the depth of first contact ({:.6e} in depth_unit), got {raw_depth}",
                start_depth / unit
            )
        ));
    }
    Ok(depth)
}
