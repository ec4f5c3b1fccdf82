//! `adhesim plot master TABLE.csv...`: the master curves of sweep tables, redrawn
//! (`adhesim_figures::master_plots`).

use adhesim_figures::master_plots::{check_rows, write, MasterStyle};
use anyhow::{bail, Result};
use clap::{Args, Subcommand};
use std::path::{Path, PathBuf};

/// `adhesim plot ...`
#[derive(Args)]
pub struct PlotArgs {
    #[command(subcommand)]
    what: PlotKind,
}

#[derive(Subcommand)]
enum PlotKind {
    /// Master curves (Figs. 2, 3, 5) from one or more sweep tables; rows are grouped into
    /// series by the table's `series` column.
    Master {
        /// table.csv files written by `adhesim sweep` (their case folders are used for the
        /// force–radius plot when present).
        #[arg(required = true)]
        tables: Vec<PathBuf>,
        /// Output folder [default: plots/ next to the first table].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Join each series' points by a line in α order (a few series side by side).
        #[arg(long)]
        join: bool,
        /// Leave out the γ fits with the area-equivalent radius √(A/π).
        #[arg(long)]
        no_area: bool,
    },
}

/// Entry point of `adhesim plot`.
pub fn command(args: &PlotArgs) -> Result<()> {
    match &args.what {
        PlotKind::Master {
            tables,
            out,
            join,
            no_area,
        } => {
            let out = match out {
                Some(out) => out.clone(),
                None => tables[0].parent().unwrap_or(Path::new(".")).join("plots"),
            };
            let style = MasterStyle {
                join: *join,
                area: !*no_area,
            };
            for table in tables {
                check_rows(table)?;
            }
            let written = write(tables, &out, style)?;
            if written.is_empty() {
                bail!(
                    "no finished row of {} has a johnson_parameter > 0: nothing to draw",
                    tables
                        .iter()
                        .map(|t| t.display().to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                );
            }
            outln!("plots in {}/: {}", out.display(), written.join(", "));
            Ok(())
        }
    }
}
