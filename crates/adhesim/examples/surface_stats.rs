//! Generates random self-affine surfaces with `adhesim::surface` and prints their
//! statistics as JSON, for the cross-check against SurfaceTopography
//! (`bench/compare/surface_generator.py`).
//!
//! ```sh
//! cargo run --release -p adhesim --example surface_stats -- \
//!     --n 256 --size 1 --hurst 0.8 --rms-slope 0.1 --rolloff 0.5 --cutoff 0.03125 \
//!     --amplitudes filtered --seeds 16 --bins 40 --npy /tmp/heights.npy
//! ```
//! Prints one JSON object: the parameters, the prefactor C₀ of C(q) = C₀q^(−2−2H), per
//! seed the rms height, rms slope (spectral and forward differences), rms curvature (on the
//! periodic grid, and by finite differences treating the same map as non-periodic), and
//! the isotropic PSD averaged over the seeds with the target C(q) at each bin, and the
//! PSD of the first seed alone. `--npy`
//! writes the heights of the first seed as a little-endian float64 `.npy` (N×N, row y).

use adhesim::surface::{isotropic_psd, rms_curvature, rms_height, rms_slope, rms_slope_finite_differences};
use adhesim::{Amplitudes, Boundary, Grid, RmsTarget, SelfAffine};
use std::fmt::Write as _;

fn main() {
    if let Err(message) = run() {
        eprintln!("surface_stats: {message}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let mut n = 256usize;
    let mut size = 1.0f64;
    let mut hurst = 0.8f64;
    let mut target = RmsTarget::Slope(0.1);
    let (mut rolloff, mut cutoff) = (None, None);
    let mut amplitudes = Amplitudes::RandomPhase;
    let (mut seeds, mut bins) = (4u64, 40usize);
    let mut npy = None;
    let mut args = std::env::args().skip(1);
    while let Some(key) = args.next() {
        let mut value = || args.next().ok_or(format!("{key} needs a value"));
        let number = |text: String| text.parse::<f64>().map_err(|e| format!("{key}: {e}"));
        match key.as_str() {
            "--n" => n = value()?.parse().map_err(|e| format!("--n: {e}"))?,
            "--size" => size = number(value()?)?,
            "--hurst" => hurst = number(value()?)?,
            "--rms-slope" => target = RmsTarget::Slope(number(value()?)?),
            "--rms-height" => target = RmsTarget::Height(number(value()?)?),
            "--rolloff" => rolloff = Some(number(value()?)?),
            "--cutoff" => cutoff = Some(number(value()?)?),
            "--amplitudes" => {
                amplitudes = match value()?.as_str() {
                    "random_phase" => Amplitudes::RandomPhase,
                    "filtered" => Amplitudes::Filtered,
                    other => return Err(format!("--amplitudes: random_phase or filtered, got {other}")),
                }
            }
            "--seeds" => seeds = value()?.parse().map_err(|e| format!("--seeds: {e}"))?,
            "--bins" => bins = value()?.parse().map_err(|e| format!("--bins: {e}"))?,
            "--npy" => npy = Some(value()?),
            other => return Err(format!("unknown option {other}")),
        }
    }
    let grid = Grid::new(n, size, Boundary::Periodic).map_err(|e| e.to_string())?;
    let free = Grid::new(n, size, Boundary::Free).map_err(|e| e.to_string())?;
    let mut spectrum = SelfAffine::new(hurst, target).with_amplitudes(amplitudes);
    spectrum.rolloff_wavelength = rolloff;
    spectrum.cutoff_wavelength = cutoff;
    let mut json = String::from("{");
    let mut per_seed = Vec::new();
    let mut psd_sum: Vec<(f64, f64, f64, usize)> = Vec::new();
    let mut prefactor = 0.0;
    let mut first_psd: Vec<String> = Vec::new();
    for seed in 0..seeds {
        let surface = spectrum.generate(&grid, seed).map_err(|e| e.to_string())?;
        prefactor = surface.prefactor;
        let heights = &surface.heights;
        let stat = |result: Result<f64, adhesim::SurfaceError>| result.map_err(|e| e.to_string());
        per_seed.push(format!(
            "{{\"seed\": {seed}, \"rms_height\": {:e}, \"rms_slope\": {:e}, \"rms_slope_fd_periodic\": {:e}, \"rms_curvature\": {:e}, \"rms_slope_fd_free\": {:e}, \"rms_curvature_fd_free\": {:e}}}",
            stat(rms_height(&grid, heights))?,
            stat(rms_slope(&grid, heights))?,
            stat(rms_slope_finite_differences(&grid, heights))?,
            stat(rms_curvature(&grid, heights))?,
            stat(rms_slope(&free, heights))?,
            stat(rms_curvature(&free, heights))?,
        ));
        let psd = isotropic_psd(&grid, heights, bins).map_err(|e| e.to_string())?;
        psd_sum.resize(psd.len(), (0.0, 0.0, 0.0, 0));
        for (sum, bin) in psd_sum.iter_mut().zip(&psd) {
            *sum = (
                bin.wavevector,
                sum.1 + bin.psd / seeds as f64,
                surface.target_psd(bin.wavevector),
                bin.modes,
            );
        }
        if seed == 0 {
            first_psd = psd
                .iter()
                .map(|b| format!("[{:e}, {:e}, {}]", b.wavevector, b.psd, b.modes))
                .collect();
            if let Some(path) = &npy {
                write_npy(path, heights, n).map_err(|e| format!("{path}: {e}"))?;
            }
        }
    }
    let _ = write!(
        json,
        "\"n\": {n}, \"size\": {size:e}, \"hurst\": {hurst:e}, \"target\": \"{target:?}\", \"amplitudes\": \"{amplitudes:?}\", \"prefactor\": {prefactor:e}, \"seeds\": ["
    );
    json.push_str(&per_seed.join(", "));
    json.push_str("], \"psd\": [");
    let rows: Vec<String> = psd_sum
        .iter()
        .map(|(q, c, target, modes)| format!("[{q:e}, {c:e}, {target:e}, {modes}]"))
        .collect();
    json.push_str(&rows.join(", "));
    json.push_str("], \"psd_first_seed\": [");
    json.push_str(&first_psd.join(", "));
    json.push_str("]}");
    println!("{json}");
    Ok(())
}

/// numpy's `.npy` version 1.0: magic, header length, a dict padded to 64 bytes, then the
/// little-endian float64 data in C order.
fn write_npy(path: &str, values: &[f64], n: usize) -> std::io::Result<()> {
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, {n}), }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    for value in values {
        bytes.extend_from_slice(&value.to_le_bytes());
    }
    std::fs::write(path, bytes)
}
