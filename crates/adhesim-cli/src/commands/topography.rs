//! `adhesim topography FILE|SCENARIO`: the statistics of a measured topography (any format
//! of `adhesim_topography::read_topography`) or of a scenario's `[roughness]` as sampled on
//! its grid: size, spacing, units, rms height, slope and curvature
//! (`adhesim::surface::statistics`), a Hurst estimate from a power-law fit of the isotropic
//! PSD (Jacobs, Junge & Pastewka 2017, *Surf. Topogr.: Metrol. Prop.* 5, 013001,
//! doi:10.1088/2051-672X/aa51f8: C(q) ∝ q^(−2−2H)); writes `psd.csv`, the log–log PSD
//! plot, a height-map picture and `statistics.json` into `--out`.

use crate::figure::{Figure, Mark, Panel, Series, PALETTE};
use adhesim::analysis::fit::fit_power_law;
use adhesim::surface::{isotropic_psd, statistics, PsdBin};
use adhesim::{Boundary, Grid};
use adhesim_scenario::RoughnessSection;
use adhesim_topography::{read_topography, ReadOptions};
use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use plotters::chart::SeriesLabelPosition;
use serde::Serialize;
use std::f64::consts::{PI, TAU};
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct TopographyArgs {
    /// An instrument file (x3p, gwy, sur, txt/asc/dat/csv, xyz, npy, npz) or a scenario
    /// (`.toml`) with a `[roughness]` or `[substrate_roughness]`.
    input: PathBuf,
    /// Output folder [default: out/topography/<file stem>/].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Sample spacing of a file that records none (npy, npz, bare ASCII).
    #[arg(long)]
    spacing: Option<f64>,
    /// Channel of a multi-channel file (Gwyddion title, npz member, ASCII "Channel").
    #[arg(long)]
    channel: Option<String>,
    /// Subtract the least-squares mean plane of a file's map first.
    #[arg(long)]
    detrend: bool,
    /// Scenario: analyse `[substrate_roughness]` instead of `[roughness]`.
    #[arg(long)]
    substrate: bool,
    /// Logarithmic bins of the isotropic PSD.
    #[arg(long, default_value_t = 30)]
    bins: usize,
}

/// A square height map on a grid, with where it came from.
struct Surface {
    grid: Grid,
    heights: Vec<f64>,
    /// Description lines (format, size, units) printed and written to statistics.json.
    source: Vec<String>,
    /// Wavevector band of the power law (q_r, q_s) where the generator keys give it.
    band: (Option<f64>, Option<f64>),
}

/// What `statistics.json` holds.
#[derive(Serialize)]
struct Report {
    input: String,
    source: Vec<String>,
    n: usize,
    size: f64,
    spacing: f64,
    boundary: &'static str,
    rms_height: f64,
    rms_slope: f64,
    rms_curvature: f64,
    hurst_estimate: Option<f64>,
    hurst_fit_range: Option<(f64, f64)>,
}

/// `adhesim topography`.
pub fn command(args: &TopographyArgs) -> Result<()> {
    if args.bins < 2 {
        bail!("--bins must be >= 2, got {}", args.bins);
    }
    if let Some(spacing) = args.spacing {
        if !(spacing.is_finite() && spacing > 0.0) {
            bail!("--spacing must be > 0, got {spacing}");
        }
    }
    let is_scenario = args.input.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let surface = if is_scenario {
        from_scenario(args)?
    } else {
        from_file(args)?
    };
    let out = match &args.out {
        Some(out) => out.clone(),
        None => {
            let stem = args
                .input
                .file_stem()
                .ok_or_else(|| anyhow!("{} has no file name", args.input.display()))?;
            Path::new("out").join("topography").join(stem)
        }
    };
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    let stats = statistics(&surface.grid, &surface.heights).map_err(|e| anyhow!("{}: {e}", args.input.display()))?;
    let psd = isotropic_psd(&surface.grid, &surface.heights, args.bins)
        .map_err(|e| anyhow!("{}: {e}", args.input.display()))?;
    let fit = hurst_estimate(&surface, &psd);
    let grid = &surface.grid;
    let report = Report {
        input: args.input.display().to_string(),
        source: surface.source.clone(),
        n: grid.n(),
        size: grid.size(),
        spacing: grid.element_size(),
        boundary: match grid.boundary() {
            Boundary::Free => "free",
            Boundary::Periodic => "periodic",
        },
        rms_height: stats.rms_height,
        rms_slope: stats.rms_slope,
        rms_curvature: stats.rms_curvature,
        hurst_estimate: fit.map(|f| f.hurst),
        hurst_fit_range: fit.map(|f| f.range),
    };
    let mut written = vec![write_psd_csv(&out, &psd)?];
    written.extend(psd_figure(&psd, fit)?.save(&out, "psd", (800, 600))?);
    written.push(write_height_map(&out.join("heights.png"), grid.n(), &surface.heights)?);
    let json = serde_json::to_string_pretty(&report)?;
    std::fs::write(out.join("statistics.json"), json + "\n")
        .with_context(|| format!("cannot write {}", out.join("statistics.json").display()))?;
    written.push("statistics.json".into());
    print_report(&report);
    println!("outputs in {}/: {}", out.display(), written.join(", "));
    Ok(())
}

fn print_report(report: &Report) {
    println!("topography {}", report.input);
    for line in &report.source {
        println!("  {line}");
    }
    println!(
        "  analysed: {n} × {n} samples, spacing {:e}, side {:e}, {} boundary",
        report.spacing,
        report.size,
        report.boundary,
        n = report.n
    );
    println!("  rms height    {:.6e}", report.rms_height);
    println!("  rms slope     {:.6e}", report.rms_slope);
    println!("  rms curvature {:.6e}", report.rms_curvature);
    match (report.hurst_estimate, report.hurst_fit_range) {
        (Some(h), Some((low, high))) => println!(
            "  Hurst estimate H = {h:.3} (power-law fit C ∝ q^(−2−2H) of the PSD for q in [{low:.4e}, {high:.4e}])"
        ),
        _ => println!("  Hurst estimate: none (fewer than 3 PSD bins inside the fit range)"),
    }
}

/// A measured file: read, detrend on request, the largest square at the file's spacing.
fn from_file(args: &TopographyArgs) -> Result<Surface> {
    let path = &args.input;
    let options = ReadOptions {
        channel: args.channel.clone(),
        spacing: args.spacing.map(|s| (s, s)),
        height_unit: Some("m".to_string()),
        lateral_unit: Some("m".to_string()),
    };
    adhesim_scenario::check_regular_file(path, "topography file")?;
    let mut map = read_topography(path, &options).map_err(|e| {
        let hint = if args.spacing.is_none() {
            " (files that record no spacing need --spacing)"
        } else {
            ""
        };
        anyhow!("{e}{hint}")
    })?;
    let mut source = vec![
        format!("format {}, channel {:?}", map.format, map.channel),
        format!(
            "{} × {} points, spacing {:e} × {:e} m (heights in m; the file stores heights in {:?}, lengths in {:?})",
            map.nx, map.ny, map.dx, map.dy, map.height_unit, map.lateral_unit
        ),
    ];
    if let Some(mask) = &map.mask {
        let invalid = mask.iter().filter(|v| !**v).count();
        if invalid > 0 {
            source.push(format!(
                "{invalid} invalid points, filled with the mean height by the reader"
            ));
        }
    }
    // Issue #29: heights near 1e300 gave an rms height of inf (exit 0) and a PSD plot of
    // unbounded ticks; beyond 1e150 their squares overflow.
    if let Some(h) = map.heights.iter().find(|h| h.abs() > 1e150 && h.is_finite()) {
        bail!(
            "{}: a height of {h:e} m lies beyond 1e150 m, where its square (the rms height, the PSD) overflows: check the file's height unit",
            path.display()
        );
    }
    if args.detrend {
        let (_, slope_x, slope_y) = map.detrend_mean_plane().map_err(|e| anyhow!("{e}"))?;
        source.push(format!("mean plane subtracted (slopes {slope_x:e}, {slope_y:e})"));
    }
    let spacing = map.dx.min(map.dy);
    let n = ((map.nx - 1) as f64 * map.dx / spacing)
        .min((map.ny - 1) as f64 * map.dy / spacing)
        .floor() as usize
        + 1;
    let n = if (map.dx - map.dy).abs() <= 1e-9 * map.dx {
        map.nx.min(map.ny)
    } else {
        n
    };
    if n < 3 {
        bail!(
            "{}: a {}×{} map is too small for statistics (3×3 at least)",
            path.display(),
            map.nx,
            map.ny
        );
    }
    let heights = if n == map.nx && n == map.ny {
        map.heights.clone()
    } else {
        source.push(format!("statistics of the first {n} × {n} square of the map"));
        map.resample_to(n, n, spacing, spacing)
            .map_err(|e| anyhow!("{}: {e}", path.display()))?
            .topography
            .heights
    };
    let grid = Grid::new(n, n as f64 * spacing, Boundary::Free).map_err(|e| {
        anyhow!(
            "{}: spacing {spacing:e} m (--spacing or the file's): {e}",
            path.display()
        )
    })?;
    Ok(Surface {
        grid,
        heights,
        source,
        band: (None, None),
    })
}

/// A scenario's `[roughness]` (or `[substrate_roughness]`) as sampled on its grid.
fn from_scenario(args: &TopographyArgs) -> Result<Surface> {
    let path = &args.input;
    let text = adhesim_scenario::read_input_text(path, "scenario")?;
    let base = path.parent().unwrap_or(Path::new("."));
    let limit = crate::resources::memory_limit(false)?;
    let scenario = adhesim_scenario::load_within(&text, &path.display().to_string(), base, &[], limit.as_ref())?;
    let (name, section, heights) = if args.substrate {
        let heights = scenario
            .translation
            .as_ref()
            .and_then(|t| t.contact.substrate_roughness())
            .map(<[f64]>::to_vec);
        (
            "substrate_roughness",
            scenario.file.substrate_roughness.as_ref(),
            heights,
        )
    } else {
        (
            "roughness",
            scenario.file.roughness.as_ref(),
            scenario.roughness.clone(),
        )
    };
    let heights = heights.ok_or_else(|| {
        anyhow!(
            "{} has no [{name}] section{}",
            path.display(),
            if args.substrate {
                ""
            } else {
                " (pass --substrate for [substrate_roughness])"
            }
        )
    })?;
    let band = section.map_or((None, None), generator_band);
    let source = vec![format!(
        "[{name}] of the scenario on its grid ({})",
        section.map_or(String::new(), describe)
    )];
    Ok(Surface {
        grid: scenario.grid,
        heights,
        source,
        band,
    })
}

fn describe(section: &RoughnessSection) -> String {
    match &section.file {
        Some(file) => format!("file {}", file.display()),
        None => format!(
            "random self-affine, hurst = {:?}, seed = {:?}",
            section.hurst.unwrap_or(f64::NAN),
            section.seed.unwrap_or(-1)
        ),
    }
}

/// (q_r, q_s) of the generator keys, where given.
fn generator_band(section: &RoughnessSection) -> (Option<f64>, Option<f64>) {
    (
        section.rolloff_wavelength.map(|w| TAU / w),
        section.cutoff_wavelength.map(|w| TAU / w),
    )
}

/// H from a power-law fit of the PSD bins between 4·(2π/L) (or twice the roll-off) and
/// π/(2Δ) (or the cutoff / 1.5): the lowest modes are few and scattered, the highest
/// ones feel the lattice. `None` with fewer than 3 bins in the range.
fn hurst_estimate(surface: &Surface, psd: &[PsdBin]) -> Option<HurstFit> {
    let grid = &surface.grid;
    let low = (4.0 * TAU / grid.size()).max(surface.band.0.map_or(0.0, |q| 2.0 * q));
    let high = (PI / (2.0 * grid.element_size())).min(surface.band.1.map_or(f64::INFINITY, |q| q / 1.5));
    let points: Vec<(f64, f64)> = psd
        .iter()
        .filter(|b| b.wavevector >= low && b.wavevector <= high && b.psd > 0.0)
        .map(|b| (b.wavevector, b.psd))
        .collect();
    if points.len() < 3 {
        return None;
    }
    let (prefactor, exponent) = fit_power_law(&points)?;
    Some(HurstFit {
        hurst: -(exponent + 2.0) / 2.0,
        prefactor,
        range: (low, high),
    })
}

/// C(q) = prefactor·q^(−2−2H) fitted over `range`.
#[derive(Clone, Copy)]
struct HurstFit {
    hurst: f64,
    prefactor: f64,
    range: (f64, f64),
}

fn write_psd_csv(out: &Path, psd: &[PsdBin]) -> Result<String> {
    let path = out.join("psd.csv");
    let mut writer = csv::Writer::from_path(&path).with_context(|| format!("cannot write {}", path.display()))?;
    writer.write_record(["q_low", "q_high", "q", "psd", "modes"])?;
    for bin in psd {
        writer.write_record([
            bin.edges.0.to_string(),
            bin.edges.1.to_string(),
            bin.wavevector.to_string(),
            bin.psd.to_string(),
            bin.modes.to_string(),
        ])?;
    }
    writer
        .flush()
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok("psd.csv".into())
}

/// The log–log PSD with the fitted power law over its range; an error for a flat map (no
/// positive bin to draw on a log axis).
fn psd_figure(bins: &[PsdBin], fit: Option<HurstFit>) -> Result<Figure> {
    let positive: Vec<(f64, f64)> = bins
        .iter()
        .filter(|b| b.psd > 0.0)
        .map(|b| (b.wavevector, b.psd))
        .collect();
    if positive.is_empty() {
        bail!("the PSD has no positive bin (a flat map)");
    }
    let (q_min, q_max) = positive
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
    let (c_min, c_max) = positive
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| (lo.min(p.1), hi.max(p.1)));
    let title = match fit {
        Some(fit) => format!("Isotropic PSD (Hurst estimate H = {:.3})", fit.hurst),
        None => "Isotropic PSD".to_string(),
    };
    let mut series = vec![Series::new("", PALETTE[0], Mark::LinePoints, positive)];
    if let Some(HurstFit {
        hurst: h,
        prefactor,
        range: (low, high),
    }) = fit
    {
        let line = [low, high].map(|q| (q, prefactor * q.powf(-2.0 - 2.0 * h)));
        series.push(Series::new(
            format!("fit ∝ q^(−2−2H), H = {h:.3}"),
            PALETTE[1],
            Mark::Line,
            line.to_vec(),
        ));
    }
    let panel = Panel::new(title, "wavevector q (1/length)", "C(q) (length⁴)")
        .with(series)
        .log_x()
        .x_range(q_min / 1.2, q_max * 1.2)
        .log_y(c_min / 2.0, c_max * 2.0)
        .scientific_ticks()
        .legend_at(SeriesLabelPosition::UpperRight);
    Ok(Figure::stacked(vec![panel]))
}

/// The height map as a PNG, y upwards, blue (low) – white (mean) – red (high) scaled to the
/// largest deviation from the mean.
fn write_height_map(path: &Path, n: usize, heights: &[f64]) -> Result<String> {
    let mean = heights.iter().sum::<f64>() / heights.len() as f64;
    let span = heights.iter().map(|h| (h - mean).abs()).fold(0.0, f64::max);
    let scale = (512 / n).clamp(1, 16);
    let side = (n * scale) as u32;
    let mut image = image::RgbImage::new(side, side);
    for (px, py, pixel) in image.enumerate_pixels_mut() {
        let column = px as usize / scale;
        let row = n - 1 - py as usize / scale;
        let t = if span > 0.0 {
            (heights[row * n + column] - mean) / span
        } else {
            0.0
        };
        let fade = |c: u8, t: f64| (255.0 + (c as f64 - 255.0) * t).round() as u8;
        pixel.0 = if t >= 0.0 {
            [fade(178, t), fade(24, t), fade(43, t)]
        } else {
            [fade(33, -t), fade(102, -t), fade(172, -t)]
        };
    }
    crate::figure::files::save_image(&image, path)?;
    Ok("heights.png".into())
}
