//! `adhesim reference`: closed-form curves as CSV on stdout.

use adhesim::analysis::reference::{FlatPunchReference, Hertz, Jkr};
use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use std::io::Write;

#[derive(Clone, Copy, ValueEnum)]
pub enum ReferenceKind {
    /// Hertz: columns a, d, force for a from 0 to --max-radius (default 0.1 R).
    Hertz,
    /// JKR: columns a, d, force, a_norm, d_norm, force_norm for a from 0 to --max-radius
    /// (default 3 a_JKR); a_JKR and the displacement-control jump point are sample points.
    Jkr,
    /// Flat circular punch (radius = punch radius): columns d, force, from Kendall's
    /// pull-off depth (0 without adhesion) to --max-depth (default 0.01 a).
    FlatPunch,
}

#[derive(Args)]
pub struct ReferenceArgs {
    /// Which closed form.
    kind: ReferenceKind,
    /// Sphere radius R, or the punch radius a.
    #[arg(long, default_value_t = 1.0)]
    radius: f64,
    /// Contact modulus E*.
    #[arg(long, default_value_t = 1.0)]
    contact_modulus: f64,
    /// Work of adhesion γ0 (required > 0 for jkr).
    #[arg(long, default_value_t = 0.0)]
    work_of_adhesion: f64,
    /// Number of sample points (>= 2).
    #[arg(long, default_value_t = 200)]
    points: usize,
    /// Largest contact radius (hertz, jkr).
    #[arg(long)]
    max_radius: Option<f64>,
    /// Largest depth (flat-punch).
    #[arg(long)]
    max_depth: Option<f64>,
}

/// Most sample points of a reference curve: 10⁷ rows (about 0.5 GB of CSV) is far beyond
/// any plot; more only fills the disk or, before this cap, aborted on allocation.
const MAX_POINTS: usize = 10_000_000;

fn check(name: &str, value: f64, allow_zero: bool) -> Result<f64> {
    if value.is_finite() && (value > 0.0 || (allow_zero && value == 0.0)) {
        Ok(value)
    } else if allow_zero {
        bail!("--{name} must be >= 0, got {value}")
    } else {
        bail!("--{name} must be > 0, got {value}")
    }
}

fn samples(low: f64, high: f64, points: usize) -> Vec<f64> {
    (0..points)
        .map(|i| low + (high - low) * i as f64 / (points - 1) as f64)
        .collect()
}

pub fn print(args: &ReferenceArgs) -> Result<()> {
    let radius = check("radius", args.radius, false)?;
    let modulus = check("contact-modulus", args.contact_modulus, false)?;
    let gamma = check("work-of-adhesion", args.work_of_adhesion, true)?;
    if !(2..=MAX_POINTS).contains(&args.points) {
        bail!("--points must be in 2..={MAX_POINTS}, got {}", args.points);
    }
    let stdout = std::io::stdout();
    let mut csv = csv::Writer::from_writer(stdout.lock());
    match args.kind {
        ReferenceKind::Hertz => {
            let hertz = Hertz {
                radius,
                contact_modulus: modulus,
            };
            let top = check("max-radius", args.max_radius.unwrap_or(0.1 * radius), false)?;
            csv.write_record(["a", "d", "force"])?;
            for a in samples(0.0, top, args.points) {
                let d = a * a / radius;
                csv.serialize((a, d, hertz.force(d)))?;
            }
        }
        ReferenceKind::Jkr => {
            if gamma == 0.0 {
                bail!("--work-of-adhesion must be > 0 for jkr, got 0");
            }
            let jkr = Jkr {
                radius,
                contact_modulus: modulus,
                work_of_adhesion: gamma,
            };
            let (f, d, a0) = (
                jkr.critical_force().abs(),
                jkr.critical_depth().abs(),
                jkr.critical_radius(),
            );
            let top = check("max-radius", args.max_radius.unwrap_or(3.0 * a0), false)?;
            let mut radii = samples(0.0, top, args.points);
            for special in [a0, a0 / 9f64.cbrt()] {
                if special < top {
                    radii.push(special);
                }
            }
            radii.sort_by(f64::total_cmp);
            radii.dedup();
            csv.write_record(["a", "d", "force", "a_norm", "d_norm", "force_norm"])?;
            for a in radii {
                let (depth, force) = (jkr.depth(a), jkr.force(a));
                csv.serialize((a, depth, force, a / a0, depth / d, force / f))?;
            }
        }
        ReferenceKind::FlatPunch => {
            let punch = FlatPunchReference {
                radius,
                contact_modulus: modulus,
            };
            let low = if gamma > 0.0 { punch.kendall_depth(gamma) } else { 0.0 };
            let top = args.max_depth.unwrap_or(0.01 * radius);
            if !(top.is_finite() && top > low) {
                bail!("--max-depth must be > {low}, got {top}");
            }
            csv.write_record(["d", "force"])?;
            for depth in samples(low, top, args.points) {
                csv.serialize((depth, punch.stiffness() * depth))?;
            }
        }
    }
    csv.flush()?;
    std::io::stdout().flush()?;
    Ok(())
}
