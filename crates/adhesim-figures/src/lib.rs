//! The figures of adhesim: the pictures of a run folder ([`run_figures::RunFigures`]:
//! contact and slip maps, the force curves of an indentation or a translation), the master
//! curves of sweep tables ([`master_plots`]) and the drawing layer under them ([`figure`]:
//! panels, log axes, legends, PNG and SVG files with fonts of their own).
//!
//! The scenario crate's run pipeline draws nothing itself: it takes a
//! [`RunPictures`](adhesim_scenario::output::observer::RunPictures). The command line and
//! the Python package both hand it [`run_figures::RunFigures`], so a folder is the same
//! whoever ran it.
//!
//! ```
//! use adhesim_figures::figure::{Figure, Mark, Panel, Series, PALETTE};
//!
//! let curve = Series::new("F(d)", PALETTE[0], Mark::Line, vec![(0.0, 0.0), (1.0, 1.0), (2.0, 2.8)]);
//! let figure = Figure::stacked(vec![Panel::new("an indentation", "d", "F").with([curve])]);
//! let dir = std::env::temp_dir().join(format!("adhesim-figures-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let written = figure.save(&dir, "force_depth", (640, 480))?;
//! assert_eq!(written, ["force_depth.svg".to_string(), "force_depth.png".to_string()]);
//! assert!(dir.join("force_depth.png").is_file());
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), anyhow::Error>(())
//! ```

pub mod figure;
pub mod log_ticks;
pub mod map_key;
pub mod master_plots;
pub mod plots;
pub mod rough_sphere_plots;
pub mod run_figures;
pub mod tangential_plots;
