//! The columns of `curve.csv`, declared once (docs/cli.md lists them): the command line
//! writes them as text, the Python package as numpy arrays, from the same declaration,
//! so header, row and arrays cannot drift apart. The normalised columns (`d_norm`,
//! `force_norm`, `radius_norm`) exist where the JKR scales do.

use adhesim::analysis::reference::Jkr;
use adhesim::StepRecord;
use std::fmt;

/// One cell of `curve.csv`. Its `Display` is the text written to the file: Rust's
/// shortest round-trip form for floats, so parsing the text gives back the same bits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CurveCell {
    /// A count or a 0/1 flag.
    Integer(u64),
    /// A physical quantity.
    Float(f64),
    /// The phase name (empty where a record has none).
    Text(&'static str),
}

impl fmt::Display for CurveCell {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Integer(value) => write!(f, "{value}"),
            Self::Float(value) => write!(f, "{value}"),
            Self::Text(value) => f.write_str(value),
        }
    }
}

/// What a column holds (the numpy dtype the Python package gives it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurveKind {
    Integer,
    Float,
    Text,
}

/// How a column's cell is computed from a step's record (and the JKR scales).
type CellFn = fn(&StepRecord, &Jkr) -> CurveCell;

/// One column: its header, its kind and its cell.
#[derive(Clone, Copy)]
pub struct CurveColumn {
    /// The header in `curve.csv`.
    pub name: &'static str,
    /// What the column holds.
    pub kind: CurveKind,
    cell: CellFn,
}

impl fmt::Debug for CurveColumn {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "CurveColumn({}, {:?})", self.name, self.kind)
    }
}

const fn float(name: &'static str, cell: CellFn) -> CurveColumn {
    CurveColumn {
        name,
        kind: CurveKind::Float,
        cell,
    }
}

const fn integer(name: &'static str, cell: CellFn) -> CurveColumn {
    CurveColumn {
        name,
        kind: CurveKind::Integer,
        cell,
    }
}

use CurveCell::{Float, Integer};

/// The columns before the normalised ones.
const LEADING: [CurveColumn; 12] = [
    integer("step", |r, _| Integer(r.step as u64)),
    CurveColumn {
        name: "phase",
        kind: CurveKind::Text,
        cell: |r, _| CurveCell::Text(r.phase.map(|p| p.name()).unwrap_or("")),
    },
    float("d", |r, _| Float(r.depth)),
    float("x", |r, _| Float(r.offset)),
    float("force_normal", |r, _| Float(r.force_normal)),
    float("force_tangential", |r, _| Float(r.force_tangential)),
    float("area", |r, _| Float(r.area)),
    float("radius", |r, _| Float(r.radius)),
    integer("n_contact", |r, _| Integer(r.contact_elements as u64)),
    float("dissipated_energy", |r, _| Float(r.cumulative_dissipated_energy)),
    float("force_tangential_before_change", |r, _| {
        Float(r.force_tangential_before_change)
    }),
    float("half_width", |r, _| Float(r.half_width)),
];

/// The columns normalised by the JKR scales (only where they exist).
const NORMALISED: [CurveColumn; 3] = [
    float("d_norm", |r, jkr| Float(r.depth / jkr.critical_depth().abs())),
    float("force_norm", |r, jkr| {
        Float(r.force_normal / jkr.critical_force().abs())
    }),
    float("radius_norm", |r, jkr| Float(r.radius / jkr.critical_radius())),
];

/// The solver's counters of the step, last.
const TRAILING: [CurveColumn; 8] = [
    integer("attached", |r, _| Integer(r.report.attached as u64)),
    integer("detached", |r, _| Integer(r.report.detached as u64)),
    integer("jumped", |r, _| Integer(u64::from(r.jumped))),
    float("step_dissipated_energy", |r, _| Float(r.report.dissipated_energy)),
    integer("solves", |r, _| Integer(r.report.solves as u64)),
    integer("cg_iterations", |r, _| Integer(r.report.cg_iterations as u64)),
    integer("fft_pairs", |r, _| Integer(r.report.operator_applications)),
    integer("touches_border", |r, _| Integer(u64::from(r.touches_border))),
];

/// The columns of a run with friction at the interface, after the solver's counters.
const FRICTION: [CurveColumn; 5] = [
    integer("n_stick", |r, _| Integer(r.stick_elements as u64)),
    integer("n_slip", |r, _| Integer(r.slip_elements as u64)),
    float("area_front", |r, _| Float(r.area_front)),
    float("area_rear", |r, _| Float(r.area_rear)),
    float("frictional_dissipation", |r, _| {
        Float(r.cumulative_frictional_dissipation)
    }),
];

/// The drive's position under a compliant drive, last (`x` is the indenter's shift, which
/// lags it).
const DRIVE: CurveColumn = float("drive_x", |r, _| Float(r.drive_offset));

/// The time since the hold began (an indentation with `protocol.hold_time`), last.
const TIME: CurveColumn = float("time", |r, _| Float(r.time));

/// The columns of one run's `curve.csv` (they depend on whether the JKR scales exist and
/// whether the interface has friction).
#[derive(Debug, Clone)]
pub struct CurveColumns {
    columns: Vec<CurveColumn>,
    /// The JKR scales of the normalised columns (unused where there are none).
    jkr: Jkr,
}

impl CurveColumns {
    /// The columns of a run with these JKR scales (`None`: no normalised columns).
    pub fn new(jkr: Option<Jkr>) -> Self {
        let mut columns = LEADING.to_vec();
        if jkr.is_some() {
            columns.extend(NORMALISED);
        }
        columns.extend(TRAILING);
        Self {
            columns,
            // Never read without the normalised columns; any value will do.
            jkr: jkr.unwrap_or(Jkr {
                radius: 1.0,
                contact_modulus: 1.0,
                work_of_adhesion: 1.0,
            }),
        }
    }

    /// The columns of a scenario's run: with the friction columns where it has
    /// `[friction]`.
    pub fn of(scenario: &crate::model::ValidScenario) -> Self {
        let mut columns = Self::new(scenario.jkr);
        if scenario.has_interface_friction() {
            columns.columns.extend(FRICTION);
        }
        let translation_drive = scenario
            .translation
            .as_ref()
            .and_then(|translation| translation.friction)
            .is_some_and(|friction| friction.drive_stiffness.is_some());
        if translation_drive || scenario.shear.is_some_and(|shear| shear.drive_stiffness.is_some()) {
            columns.columns.push(DRIVE);
        }
        if scenario.hold.is_some() {
            columns.columns.push(TIME);
        }
        columns
    }

    /// Every column a run's `curve.csv` can have (for reading one back by name).
    pub fn every() -> Vec<CurveColumn> {
        let mut columns = LEADING.to_vec();
        columns.extend(NORMALISED);
        columns.extend(TRAILING);
        columns.extend(FRICTION);
        columns.push(DRIVE);
        columns.push(TIME);
        columns
    }

    /// The columns in file order.
    pub fn columns(&self) -> &[CurveColumn] {
        &self.columns
    }

    /// The headers in file order.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.columns.iter().map(|c| c.name)
    }

    /// The cells of one step's row, in file order.
    pub fn row<'a>(&'a self, record: &'a StepRecord) -> impl Iterator<Item = CurveCell> + 'a {
        self.columns.iter().map(move |c| (c.cell)(record, &self.jkr))
    }

    /// The cell of column `index` for one step.
    pub fn cell(&self, index: usize, record: &StepRecord) -> CurveCell {
        (self.columns[index].cell)(record, &self.jkr)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalised_columns_only_with_jkr_scales() {
        let plain: Vec<_> = CurveColumns::new(None).names().collect();
        assert_eq!(plain.len(), 20);
        assert!(!plain.contains(&"d_norm"));
        let jkr = Jkr {
            radius: 1.0,
            contact_modulus: 1.0,
            work_of_adhesion: 0.01,
        };
        let with = CurveColumns::new(Some(jkr));
        let names: Vec<_> = with.names().collect();
        assert_eq!(names.len(), 23);
        assert_eq!(&names[12..15], ["d_norm", "force_norm", "radius_norm"]);
        let record = StepRecord {
            depth: jkr.critical_depth(),
            step: 7,
            jumped: true,
            ..Default::default()
        };
        let row: Vec<String> = with.row(&record).map(|c| c.to_string()).collect();
        assert_eq!(row[0], "7");
        assert_eq!(row[1], "");
        assert_eq!(row[12], (jkr.critical_depth() / jkr.critical_depth().abs()).to_string());
        assert_eq!(row[names.iter().position(|n| *n == "jumped").unwrap()], "1");
    }
}
