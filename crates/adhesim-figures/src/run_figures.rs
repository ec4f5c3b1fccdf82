//! The pictures of a run folder (a [`RunPictures`] handed to the scenario crate's run
//! pipeline, `adhesim_scenario::output::run`): contact and slip maps, and the figures of
//! the protocol. The command line's runs and sweeps and the Python package's sweep cases
//! all draw with [`RunFigures`], so that their folders are the same.

use crate::{plots, tangential_plots};
use adhesim::analysis::reference::Hertz;
use adhesim::{Grid, Profile, RunSummary, SlipStatus, StepRecord, TranslationSummary};
use adhesim_scenario::output::observer::{CapturedStep, RunPictures};
use adhesim_scenario::{ProtocolSetup, RunOutcome, RunResults, TranslationSetup, ValidScenario};
use anyhow::Result;
use std::path::Path;

/// Colours of the contact maps (paper Fig. 16 style).
const STAYING: [u8; 3] = [70, 70, 70];
const ATTACHED: [u8; 3] = [215, 25, 28];
const DETACHED: [u8; 3] = [30, 90, 220];
const FREE: [u8; 3] = [255, 255, 255];
const SLIPPING: [u8; 3] = [240, 140, 20];

/// The pictures of a run folder: contact maps and the protocol's
/// figures (also those of the Python package's sweep cases, so that their folders equal
/// the command line's).
pub struct RunFigures;

impl RunPictures for RunFigures {
    fn contact_map(&self, path: &Path, grid: &Grid, contact: &[bool], previous: &[bool]) -> Result<()> {
        write_contact_map(path, grid, contact, previous)
    }

    fn slip_map(&self, path: &Path, grid: &Grid, status: &[SlipStatus]) -> Result<()> {
        write_slip_map(path, grid, status)
    }

    fn figures(
        &self,
        scenario: &ValidScenario,
        outcome: &RunOutcome,
        captured: &[CapturedStep],
        dir: &Path,
    ) -> Result<Vec<String>> {
        match (&outcome.report, scenario.protocol_setup()) {
            (RunSummary::Translation(summary), ProtocolSetup::Translation(setup)) => {
                translation_plots(scenario, setup, summary, &outcome.records, captured, dir)
            }
            _ => indentation_plots(scenario, outcome, dir),
        }
    }
}

/// Pixel scale so that small grids give pictures of about 512 pixels.
fn pixel_scale(n: usize) -> usize {
    (512 / n).clamp(1, 16)
}

/// A PNG contact map: staying contact dark grey, newly attached red, just detached blue,
/// free white; one block of pixels per element, y upwards. The blocks are square on
/// square elements and keep the elements' aspect ratio Δy/Δx (to the pixel) otherwise.
fn write_contact_map(path: &Path, grid: &Grid, contact: &[bool], previous: &[bool]) -> Result<()> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let scale = pixel_scale(nx.max(ny));
    let scale_y = ((scale as f64 * grid.dy() / grid.dx()).round() as usize).max(1);
    let mut image = image::RgbImage::new((nx * scale) as u32, (ny * scale_y) as u32);
    for (px, py, pixel) in image.enumerate_pixels_mut() {
        let column = px as usize / scale;
        let row = ny - 1 - py as usize / scale_y;
        let k = row * nx + column;
        pixel.0 = match (previous[k], contact[k]) {
            (true, true) => STAYING,
            (false, true) => ATTACHED,
            (true, false) => DETACHED,
            (false, false) => FREE,
        };
    }
    let legend = [(STAYING, "in contact"), (ATTACHED, "attached"), (DETACHED, "detached")];
    let pixels_per_length = scale as f64 / grid.dx();
    let keyed = crate::map_key::with_key(&image, pixels_per_length, crate::map_key::Legend::Categories(&legend))?;
    crate::figure::files::save_image(&keyed, path)
}

/// A PNG map of a shear step: sticking elements dark grey, slipping ones orange, open white,
/// with a key; blocks as in [`write_contact_map`].
fn write_slip_map(path: &Path, grid: &Grid, status: &[SlipStatus]) -> Result<()> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let scale = pixel_scale(nx.max(ny));
    let scale_y = ((scale as f64 * grid.dy() / grid.dx()).round() as usize).max(1);
    let mut image = image::RgbImage::new((nx * scale) as u32, (ny * scale_y) as u32);
    for (px, py, pixel) in image.enumerate_pixels_mut() {
        let row = ny - 1 - py as usize / scale_y;
        pixel.0 = match status[row * nx + px as usize / scale] {
            SlipStatus::Stick => STAYING,
            SlipStatus::Slip => SLIPPING,
            SlipStatus::Open => FREE,
        };
    }
    let legend = [(STAYING, "stick"), (SLIPPING, "slip")];
    let pixels_per_length = scale as f64 / grid.dx();
    let keyed = crate::map_key::with_key(&image, pixels_per_length, crate::map_key::Legend::Categories(&legend))?;
    crate::figure::files::save_image(&keyed, path)
}

/// The force–depth and force–radius figures of an indentation (with Hertz or JKR
/// references and the fitted JKR curves of γ1, γ2).
fn indentation_plots(scenario: &ValidScenario, outcome: &RunOutcome, dir: &Path) -> Result<Vec<String>> {
    let hertz = match (scenario.gamma0 > 0.0, scenario.indenter.radius_of_curvature()) {
        (false, Some(radius)) => Some(Hertz {
            radius,
            contact_modulus: scenario.material.contact_modulus(),
        }),
        _ => None,
    };
    let figures = plots::figures(
        &outcome.records,
        &plots::PlotContext {
            jkr: scenario.jkr,
            hertz,
            max_depth: scenario.max_depth,
        },
    );
    let overlays = match (scenario.jkr, &outcome.results) {
        (Some(jkr), RunResults::Indentation(results)) => vec![(
            "force_radius",
            plots::fitted_jkr_overlays(
                &jkr,
                &outcome.records,
                results.fits.gamma_approach,
                results.fits.gamma_pulloff,
            ),
        )],
        _ => Vec::new(),
    };
    plots::write_all_with_overlays(dir, &figures, &overlays)
}

/// The force–distance figure of a translation (Fig. 6a) and the strip of consecutive
/// contact maps (Figs. 6b, 9).
fn translation_plots(
    scenario: &ValidScenario,
    setup: &TranslationSetup,
    summary: &TranslationSummary,
    records: &[StepRecord],
    captured: &[CapturedStep],
    dir: &Path,
) -> Result<Vec<String>> {
    let protocol = &setup.protocol;
    let charts = tangential_plots::force_distance(
        records,
        scenario.jkr,
        setup.wavelength,
        (summary.mean_tangential_force, summary.mean_tangential_force_work),
        protocol.stationary_from * protocol.distance,
    );
    let mut plot_files = tangential_plots::write_panels(dir, "force_distance", &charts)?;
    if !captured.is_empty() {
        let frames: Vec<(Vec<bool>, Vec<bool>, f64)> = captured
            .iter()
            .map(|(step, contact, previous)| {
                let offset = records.get(*step).map_or(0.0, |r| r.offset);
                (contact.clone(), previous.clone(), offset)
            })
            .collect();
        tangential_plots::write_snapshot_strip(&dir.join("contact_snapshots.png"), &scenario.grid, &frames)?;
        plot_files.push("plots/contact_snapshots.png".into());
    }
    Ok(plot_files)
}

/// Runs one sweep case into its folder as `adhesim run --quiet` does, figures included
/// ([`adhesim_scenario::output::run::run_case`] with [`RunFigures`], warnings on stderr):
/// the runner of Python's `adhesim.sweep`, so that its case folders are the command line's.
pub fn run_sweep_case(
    scenario: &ValidScenario,
    folder: &Path,
    checkpoint: Option<&adhesim_scenario::output::checkpoint::CheckpointPolicy>,
) -> Result<()> {
    let options = adhesim_scenario::output::run::FolderRunOptions {
        pictures: Some(&RunFigures),
        netcdf: false,
        checkpoint,
    };
    let mut progress = adhesim_scenario::output::observer::WarningsOnStderr;
    adhesim_scenario::output::run::run_case(scenario, folder, options, &mut progress).map(|_| ())
}
