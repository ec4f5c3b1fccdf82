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

/// Receives the rows of a curve one at a time.
type RowSink<'a> = dyn FnMut(&[f64]) -> Result<()> + 'a;

/// Generates the rows of a curve into a [`RowSink`].
type Rows = Box<dyn Fn(&mut RowSink) -> Result<()>>;

/// A closed-form curve: its columns and a generator of its rows.
struct Curve {
    header: &'static [&'static str],
    rows: Rows,
}

/// The curve `args` asks for, its inputs checked.
fn curve(args: &ReferenceArgs) -> Result<Curve> {
    let radius = check("radius", args.radius, false)?;
    let modulus = check("contact-modulus", args.contact_modulus, false)?;
    let gamma = check("work-of-adhesion", args.work_of_adhesion, true)?;
    let points = args.points;
    Ok(match args.kind {
        ReferenceKind::Hertz => {
            let hertz = Hertz {
                radius,
                contact_modulus: modulus,
            };
            let top = check("max-radius", args.max_radius.unwrap_or(0.1 * radius), false)?;
            Curve {
                header: &["a", "d", "force"],
                rows: Box::new(move |emit| {
                    for a in samples(0.0, top, points) {
                        let d = a * a / radius;
                        emit(&[a, d, hertz.force(d)])?;
                    }
                    Ok(())
                }),
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
            let scales = [("F_JKR", f), ("d_JKR", d), ("a_JKR", a0)];
            if let Some((name, value)) = scales.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
                bail!(
                    "{name} = {value:e} is not a usable number; it comes from {}: bring these inputs to commensurate units",
                    inputs(args)
                );
            }
            let top = check("max-radius", args.max_radius.unwrap_or(3.0 * a0), false)?;
            let mut radii = samples(0.0, top, points);
            for special in [a0, a0 / 9f64.cbrt()] {
                if special < top {
                    radii.push(special);
                }
            }
            radii.sort_by(f64::total_cmp);
            radii.dedup();
            Curve {
                header: &["a", "d", "force", "a_norm", "d_norm", "force_norm"],
                rows: Box::new(move |emit| {
                    for &a in &radii {
                        let (depth, force) = (jkr.depth(a), jkr.force(a));
                        emit(&[a, depth, force, a / a0, depth / d, force / f])?;
                    }
                    Ok(())
                }),
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
            Curve {
                header: &["d", "force"],
                rows: Box::new(move |emit| {
                    for depth in samples(low, top, points) {
                        emit(&[depth, punch.stiffness() * depth])?;
                    }
                    Ok(())
                }),
            }
        }
    })
}

/// The inputs as the user gave them, for the error of a curve that leaves f64.
fn inputs(args: &ReferenceArgs) -> String {
    let mut text = format!(
        "--radius {:e}, --contact-modulus {:e}, --work-of-adhesion {:e}",
        args.radius, args.contact_modulus, args.work_of_adhesion
    );
    for (name, value) in [("max-radius", args.max_radius), ("max-depth", args.max_depth)] {
        if let Some(value) = value {
            text.push_str(&format!(", --{name} {value:e}"));
        }
    }
    text
}

pub fn print(args: &ReferenceArgs) -> Result<()> {
    if !(2..=MAX_POINTS).contains(&args.points) {
        bail!("--points must be in 2..={MAX_POINTS}, got {}", args.points);
    }
    if let Some(limit) = crate::resources::memory_limit(false)? {
        // The sample radii are held at once (the JKR curve sorts its special points in).
        crate::resources::check_allocation(&format!("--points {}", args.points), args.points as u128 * 8, &limit)?;
    }
    let curve = curve(args)?;
    // A first pass checks every value, so that no inf or NaN row is printed (the closed
    // forms overflow where the inputs are of very different magnitudes) and nothing is
    // printed before the error.
    (curve.rows)(&mut |row| {
        if let Some((column, value)) = curve.header.iter().zip(row).find(|(_, v)| !v.is_finite()) {
            bail!(
                "the curve leaves double precision: {column} = {value} at {} = {:e}; it comes from {}: bring these inputs to commensurate units",
                curve.header[0],
                row[0],
                inputs(args)
            );
        }
        Ok(())
    })?;
    match write_curve(&curve) {
        // `adhesim reference ... | head` closes the pipe early: the reader has what it
        // wanted, which is no error.
        Err(error) if is_broken_pipe(&error) => Ok(()),
        other => other,
    }
}

fn write_curve(curve: &Curve) -> Result<()> {
    let stdout = std::io::stdout();
    let mut csv = csv::Writer::from_writer(stdout.lock());
    csv.write_record(curve.header)?;
    (curve.rows)(&mut |row| Ok(csv.serialize(row)?))?;
    csv.flush()?;
    std::io::stdout().flush()?;
    Ok(())
}

/// Whether an error is a write into a closed pipe (EPIPE; Rust ignores SIGPIPE).
fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        let io = cause
            .downcast_ref::<std::io::Error>()
            .or_else(|| match cause.downcast_ref::<csv::Error>()?.kind() {
                csv::ErrorKind::Io(io) => Some(io),
                _ => None,
            });
        io.is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}
