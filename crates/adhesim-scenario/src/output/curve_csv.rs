//! `curve.csv` written as the steps come (moved from the command line's `output.rs`).

use crate::CurveColumns;
use adhesim::StepRecord;
use anyhow::{Context, Result};
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// `curve.csv` (its columns are the scenario crate's [`CurveColumns`]): one row per step, flushed as it comes into `curve.csv.partial` (a killed
/// run keeps its steps there), renamed to `curve.csv` when the run ends: a `curve.csv`
/// is always whole, never cut mid-line by a full disk. I/O errors name the file.
pub struct CurveCsv {
    writer: csv::Writer<BufWriter<File>>,
    columns: CurveColumns,
    partial: PathBuf,
    path: PathBuf,
}

impl CurveCsv {
    /// Creates `PATH.partial` and writes its header.
    pub fn create(path: &Path, columns: CurveColumns) -> Result<Self> {
        let mut partial = path.as_os_str().to_owned();
        partial.push(".partial");
        let partial = PathBuf::from(partial);
        let file = File::create(&partial).with_context(|| format!("cannot create {}", partial.display()))?;
        let writer = csv::Writer::from_writer(BufWriter::new(file));
        let mut csv = Self {
            writer,
            columns,
            partial,
            path: path.to_path_buf(),
        };
        let header: Vec<&str> = csv.columns.names().collect();
        csv.writer
            .write_record(header)
            .map_err(anyhow::Error::from)
            .and_then(|()| csv.flush())
            .with_context(|| format!("cannot write {}", csv.partial.display()))?;
        Ok(csv)
    }

    /// Writes the row of one step.
    pub fn write(&mut self, record: &StepRecord) -> Result<()> {
        self.writer
            .write_record(self.columns.row(record).map(|cell| cell.to_string()))
            .map_err(anyhow::Error::from)
            .and_then(|()| self.flush())
            .with_context(|| format!("cannot write {}", self.partial.display()))
    }

    /// Flushes the file.
    pub fn flush(&mut self) -> Result<()> {
        self.writer.flush()?;
        Ok(())
    }

    /// Flushes the rows to disk and renames the file to its final name.
    pub fn commit(&mut self) -> Result<()> {
        self.writer
            .flush()
            .map_err(anyhow::Error::from)
            .and_then(|()| Ok(self.writer.get_ref().get_ref().sync_all()?))
            .with_context(|| format!("cannot write {}", self.partial.display()))?;
        std::fs::rename(&self.partial, &self.path)
            .with_context(|| format!("cannot rename {} to {}", self.partial.display(), self.path.display()))
    }
}
