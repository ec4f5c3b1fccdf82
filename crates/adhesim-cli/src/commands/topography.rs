//! `adhesim topography FILE|SCENARIO`: the statistics of a measured topography (any format
//! of `adhesim_topography::read_topography`) or of a scenario's `[roughness]` as sampled on
//! its grid: size, spacings, units, invalid points, rms height, and rms slope and curvature
//! both by finite differences and (periodic maps) spectrally, each labelled
//! (`adhesim::surface::HeightMap`), a Hurst estimate from a power-law fit of the isotropic
//! PSD (Jacobs, Junge & Pastewka 2017, *Surf. Topogr.: Metrol. Prop.* 5, 013001,
//! doi:10.1088/2051-672X/aa51f8: C(q) ∝ q^(−2−2H)); writes `psd.csv`, the log–log PSD
//! plot, a height-map picture and `statistics.json` into `--out`.

use adhesim::analysis::fit::fit_power_law;
use adhesim::surface::{HeightMap, PsdBin};
use adhesim::Boundary;
use adhesim_figures::figure::{Figure, Mark, Panel, Series, PALETTE};
use adhesim_scenario::RoughnessSection;
use adhesim_topography::{length_unit_to_metres, read_topography, ReadOptions, TopographyError};
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
    /// Sample spacing in metres of a file that records none (npy, npz, bare ASCII), or of a
    /// .gwy whose lateral unit is empty.
    #[arg(long)]
    spacing: Option<f64>,
    /// Unit of the heights of a file that records none (npy, npz, bare ASCII, xyz without
    /// header, .gwy with an empty unit): m, mm, um, nm, pm, Å ….
    #[arg(long)]
    height_unit: Option<String>,
    /// Unit of the x and y columns of an xyz file without header (or of a .gwy's sizes
    /// whose unit is empty).
    #[arg(long)]
    lateral_unit: Option<String>,
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

/// A height map (measured: a rectangle with its own spacings and invalid points; or a
/// scenario's roughness on its square grid), with where it came from.
struct Surface {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    heights: Vec<f64>,
    /// Validity of each point, `None` when all are valid.
    valid: Option<Vec<bool>>,
    periodic: bool,
    /// Description lines (format, size, units) printed and written to statistics.json.
    source: Vec<String>,
    /// Wavevector band of the power law (q_r, q_s) where the generator keys give it.
    band: (Option<f64>, Option<f64>),
    /// The unit of lengths and heights in the pictures: metres for a file (the readers
    /// convert to SI), the scenario's length unit for a scenario.
    unit: &'static str,
}

impl Surface {
    fn map(&self) -> Result<HeightMap<'_>> {
        HeightMap::new(
            (self.nx, self.ny),
            (self.dx, self.dy),
            &self.heights,
            self.valid.as_deref(),
            self.periodic,
        )
        .map_err(|e| anyhow!("{e}"))
    }
}

/// rms slope and curvature by one definition.
#[derive(Serialize, Clone, Copy)]
struct Derivatives {
    rms_slope: Option<f64>,
    rms_curvature: Option<f64>,
}

/// What `statistics.json` holds.
#[derive(Serialize)]
struct Report {
    input: String,
    source: Vec<String>,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    size_x: f64,
    size_y: f64,
    boundary: &'static str,
    valid_points: usize,
    invalid_points: usize,
    /// Over the valid points.
    rms_height: f64,
    /// Forward differences and the five-point Laplacian with the true spacings
    /// (SurfaceTopography's rms_gradient and rms_curvature_from_area), valid points only.
    finite_differences: Derivatives,
    /// Parseval sums of a periodic map with every point valid; absent otherwise.
    spectral: Option<Derivatives>,
    hurst_estimate: Option<f64>,
    hurst_fit_range: Option<(f64, f64)>,
}

/// `adhesim topography`.
pub fn command(args: &TopographyArgs) -> Result<()> {
    let max_bins = adhesim::surface::MAX_PSD_BINS;
    if !(2..=max_bins).contains(&args.bins) {
        bail!("--bins must be 2 … {max_bins}, got {}", args.bins);
    }
    if let Some(limit) = crate::resources::memory_limit(false)? {
        let bytes = args.bins as u128 * adhesim_scenario::memory::PSD_BYTES_PER_BIN;
        crate::resources::check_allocation(&format!("--bins {}", args.bins), bytes, &limit)?;
    }
    if let Some(spacing) = args.spacing {
        if !(spacing.is_finite() && spacing > 0.0) {
            bail!("--spacing must be > 0, got {spacing}");
        }
    }
    for (flag, unit) in [
        ("--height-unit", &args.height_unit),
        ("--lateral-unit", &args.lateral_unit),
    ] {
        if let Some(unit) = unit {
            length_unit_to_metres(unit).map_err(|e| anyhow!("{flag} {unit:?}: {e}"))?;
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
    let name = args.input.display();
    let map = surface.map().map_err(|e| anyhow!("{name}: {e}"))?;
    let psd = map.isotropic_psd(args.bins).map_err(|e| anyhow!("{name}: {e}"))?;
    let fit = hurst_estimate(&surface, &psd);
    let report = report(args, &surface, &map, fit);
    let mut written = vec![write_psd_csv(&out, &psd)?];
    written.extend(psd_figure(&psd, fit, surface.unit)?.save(&out, "psd", (800, 600))?);
    written.push(write_height_map(&out.join("heights.png"), &surface)?);
    let json = serde_json::to_string_pretty(&report)?;
    std::fs::write(out.join("statistics.json"), json + "\n")
        .with_context(|| format!("cannot write {}", out.join("statistics.json").display()))?;
    written.push("statistics.json".into());
    print_report(&report);
    outln!("outputs in {}/: {}", out.display(), written.join(", "));
    Ok(())
}

fn report(args: &TopographyArgs, surface: &Surface, map: &HeightMap<'_>, fit: Option<HurstFit>) -> Report {
    let valid_points = map.valid_count();
    Report {
        input: args.input.display().to_string(),
        source: surface.source.clone(),
        nx: surface.nx,
        ny: surface.ny,
        dx: surface.dx,
        dy: surface.dy,
        size_x: surface.nx as f64 * surface.dx,
        size_y: surface.ny as f64 * surface.dy,
        boundary: if surface.periodic { "periodic" } else { "free" },
        valid_points,
        invalid_points: surface.heights.len() - valid_points,
        rms_height: map.rms_height(),
        finite_differences: Derivatives {
            rms_slope: map.rms_slope_finite_differences(),
            rms_curvature: map.rms_curvature_finite_differences(),
        },
        spectral: map
            .spectral_slope_and_curvature()
            .map(|(slope, curvature)| Derivatives {
                rms_slope: Some(slope),
                rms_curvature: Some(curvature),
            }),
        hurst_estimate: fit.map(|f| f.hurst),
        hurst_fit_range: fit.map(|f| f.range),
    }
}

fn print_report(report: &Report) {
    let number = |value: Option<f64>| value.map_or("none (map too small)".to_string(), |v| format!("{v:.6e}"));
    outln!("topography {}", report.input);
    for line in &report.source {
        outln!("  {line}");
    }
    outln!(
        "  analysed: the whole map, {} × {} points, spacing {:e} × {:e}, size {:e} × {:e}, {} boundary",
        report.nx,
        report.ny,
        report.dx,
        report.dy,
        report.size_x,
        report.size_y,
        report.boundary
    );
    if report.invalid_points > 0 {
        outln!(
            "  {} invalid points left out of every statistic ({} valid)",
            report.invalid_points,
            report.valid_points
        );
    }
    outln!("  rms height                             {:.6e}", report.rms_height);
    let fd = report.finite_differences;
    outln!("  rms slope      (finite differences)    {}", number(fd.rms_slope));
    outln!("  rms curvature  (finite differences)    {}", number(fd.rms_curvature));
    match report.spectral {
        Some(spectral) => {
            outln!(
                "  rms slope      (spectral)              {}",
                number(spectral.rms_slope)
            );
            outln!(
                "  rms curvature  (spectral)              {}",
                number(spectral.rms_curvature)
            );
        }
        None => outln!("  spectral slope and curvature: none (only for a periodic map with every point valid)"),
    }
    match (report.hurst_estimate, report.hurst_fit_range) {
        (Some(h), Some((low, high))) => outln!(
            "  Hurst estimate H = {h:.3} (power-law fit C ∝ q^(−2−2H) of the PSD for q in [{low:.4e}, {high:.4e}])"
        ),
        _ => outln!("  Hurst estimate: none (fewer than 3 PSD bins inside the fit range)"),
    }
}

/// A measured file: read, detrend on request; the whole map with its own spacings, its
/// invalid points marked.
fn from_file(args: &TopographyArgs) -> Result<Surface> {
    let path = &args.input;
    let options = ReadOptions {
        channel: args.channel.clone(),
        spacing: args.spacing.map(|s| (s, s)),
        height_unit: args.height_unit.clone(),
        lateral_unit: args.lateral_unit.clone(),
    };
    adhesim_scenario::check_regular_file(path, "topography file")?;
    let mut map = read_topography(path, &options).map_err(|e| {
        let hint = match &e {
            TopographyError::MissingOption { option, .. } => {
                format!("; give --{}", option.replace('_', "-"))
            }
            _ => String::new(),
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
    // A spacing of 1e±300 overflows the wavevectors and the PSD's areas (docs/reliability.md).
    let sane = |d: f64| d.is_finite() && (1e-150..=1e150).contains(&d);
    if !(sane(map.dx) && sane(map.dy)) {
        bail!(
            "{}: spacing {:e} × {:e} m (--spacing or the file's) lies outside the floating-point range of the statistics (1e-150 … 1e150 m)",
            path.display(),
            map.dx,
            map.dy
        );
    }
    // Heights near 1e300 (docs/reliability.md) gave an rms height of inf (exit 0) and a PSD
    // plot of unbounded ticks; beyond 1e150 their squares overflow.
    let valid = |i: usize| map.mask.as_ref().is_none_or(|m| m[i]);
    if let Some(h) = (0..map.heights.len())
        .filter(|&i| valid(i))
        .map(|i| map.heights[i])
        .find(|h| h.abs() > 1e150 && h.is_finite())
    {
        bail!(
            "{}: a height of {h:e} m lies beyond 1e150 m, where its square (the rms height, the PSD) overflows: check the file's height unit (--height-unit)",
            path.display()
        );
    }
    if args.detrend {
        let (_, slope_x, slope_y) = map.detrend_mean_plane().map_err(|e| anyhow!("{e}"))?;
        source.push(format!(
            "mean plane of the valid points subtracted (slopes {slope_x:e}, {slope_y:e})"
        ));
    }
    Ok(Surface {
        nx: map.nx,
        ny: map.ny,
        dx: map.dx,
        dy: map.dy,
        heights: map.heights,
        valid: map.mask,
        periodic: false,
        source,
        band: (None, None),
        unit: "m",
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
    let grid = &scenario.grid;
    Ok(Surface {
        nx: grid.nx(),
        ny: grid.ny(),
        dx: grid.dx(),
        dy: grid.dy(),
        heights,
        valid: None,
        periodic: grid.boundary() == Boundary::Periodic,
        source,
        band,
        unit: "length units",
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

/// H from a power-law fit of the PSD bins between 4·(2π/L) (L the shorter side; or twice
/// the roll-off) and π/(2Δ) (Δ the coarser spacing; or the cutoff / 1.5): the lowest modes
/// are few and scattered, the highest ones feel the lattice. `None` with fewer than 3 bins
/// in the range.
fn hurst_estimate(surface: &Surface, psd: &[PsdBin]) -> Option<HurstFit> {
    let side = (surface.nx as f64 * surface.dx).min(surface.ny as f64 * surface.dy);
    let low = (4.0 * TAU / side).max(surface.band.0.map_or(0.0, |q| 2.0 * q));
    let high = (PI / (2.0 * surface.dx.max(surface.dy))).min(surface.band.1.map_or(f64::INFINITY, |q| q / 1.5));
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
fn psd_figure(bins: &[PsdBin], fit: Option<HurstFit>, unit: &str) -> Result<Figure> {
    let positive: Vec<(f64, f64)> = bins
        .iter()
        .filter(|b| b.psd > 0.0)
        .map(|b| (b.wavevector, b.psd))
        .collect();
    if positive.is_empty() {
        // Heights of 1e-300 have squares that underflow to 0: not a flat map.
        bail!("the PSD has no positive bin: the map is flat, or its heights are so small that their squares underflow to 0 (check the height unit)");
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
    let (q_label, c_label) = if unit == "m" {
        ("wavevector q (1/m)".to_string(), "C(q) (m⁴)".to_string())
    } else {
        ("wavevector q (1/length)".to_string(), "C(q) (length⁴)".to_string())
    };
    let panel = Panel::new(title, &q_label, &c_label)
        .with(series)
        .log_x()
        .x_range(q_min / 1.2, q_max * 1.2)
        .log_y(c_min / 2.0, c_max * 2.0)
        .scientific_ticks()
        .legend_at(SeriesLabelPosition::UpperRight);
    Ok(Figure::stacked(vec![panel]))
}

/// Blue (t = −1) – white (0) – red (+1).
fn diverging(t: f64) -> [u8; 3] {
    let fade = |c: u8, t: f64| (255.0 + (c as f64 - 255.0) * t).round() as u8;
    if t >= 0.0 {
        [fade(178, t), fade(24, t), fade(43, t)]
    } else {
        [fade(33, -t), fade(102, -t), fade(172, -t)]
    }
}

/// The height map as a PNG, y upwards, blue (low) – white (mean) – red (high) scaled to the
/// largest deviation of a valid point from the mean; invalid points grey. Drawn to scale:
/// one pixel is the same length along x and y (a map of 83 × 204 µm was drawn as a square,
/// with a scale bar right along x only), at least one pixel per point along the finer axis.
fn write_height_map(path: &Path, surface: &Surface) -> Result<String> {
    let (nx, ny) = (surface.nx, surface.ny);
    let is_valid = |k: usize| surface.valid.as_ref().is_none_or(|v| v[k]);
    let valid: Vec<f64> = (0..nx * ny)
        .filter(|&k| is_valid(k))
        .map(|k| surface.heights[k])
        .collect();
    let mean = valid.iter().sum::<f64>() / valid.len().max(1) as f64;
    let span = valid.iter().map(|h| (h - mean).abs()).fold(0.0, f64::max);
    // Pixels per length: one per point of the finer spacing, times an integer scale that
    // brings the longer side near 512 pixels (at most 16), the longer side capped at 4096.
    let (size_x, size_y) = (nx as f64 * surface.dx, ny as f64 * surface.dy);
    let finest = 1.0 / surface.dx.min(surface.dy);
    let longest = size_x.max(size_y) * finest;
    let scale = (512.0 / longest).floor().clamp(1.0, 16.0);
    let pixels_per_length = finest * scale * (4096.0 / (longest * scale)).min(1.0);
    let width = ((size_x * pixels_per_length).round() as u32).max(1);
    let height = ((size_y * pixels_per_length).round() as u32).max(1);
    let mut image = image::RgbImage::new(width, height);
    for (px, py, pixel) in image.enumerate_pixels_mut() {
        let column = (((px as f64 + 0.5) / pixels_per_length / surface.dx) as usize).min(nx - 1);
        let row = ny - 1 - (((py as f64 + 0.5) / pixels_per_length / surface.dy) as usize).min(ny - 1);
        let k = row * nx + column;
        if !is_valid(k) {
            pixel.0 = [160, 160, 160];
            continue;
        }
        let t = if span > 0.0 {
            (surface.heights[k] - mean) / span
        } else {
            0.0
        };
        pixel.0 = diverging(t);
    }
    let legend = adhesim_figures::map_key::Legend::ColourBar {
        low: mean - span,
        high: mean + span,
        label: if surface.unit == "m" {
            "height (m)"
        } else {
            "height (length units)"
        },
        colour: &diverging,
    };
    // The scale bar: the same pixels per length along both axes.
    let keyed = adhesim_figures::map_key::with_key(&image, pixels_per_length, legend)?;
    adhesim_figures::figure::files::save_image(&keyed, path)?;
    Ok("heights.png".into())
}
