//! Experiment files: a CSV of measured samples plus a TOML that states what they are
//! (`kind`, the unit of each column, temperature, rate, geometry, valid window). Values
//! are converted to SI when read; bad input is an error naming file, line and column.
//!
//! Kinds: `tensile` ([`TensileExperiment`]) and `shpb` ([`ShpbExperiment`]). The CSV path
//! in the TOML (`data = "..."`) is relative to the TOML's folder.

mod error;
pub mod header;
pub mod lanl_raw;
pub mod limits;
mod pattern;
pub mod processing;
mod shpb;
mod sidecar;
mod table;
mod tensile;
pub mod units;

pub use error::{ExperimentError, Location};
pub use shpb::{Bar, ShpbExperiment, Specimen};
pub use tensile::TensileExperiment;

use std::path::Path;

/// Any experiment file.
#[derive(Debug, Clone)]
pub enum Experiment {
    Tensile(TensileExperiment),
    Shpb(ShpbExperiment),
}

impl Experiment {
    pub fn name(&self) -> &str {
        match self {
            Experiment::Tensile(e) => &e.name,
            Experiment::Shpb(e) => &e.name,
        }
    }
}

/// Read the experiment TOML at `toml_file` and every record it names (a tensile TOML may
/// name a folder or a pattern of CSVs; an SHPB TOML names one record).
pub fn load_experiments(toml_file: &Path) -> Result<Vec<Experiment>, ExperimentError> {
    let sidecar = sidecar::Sidecar::read(toml_file)?;
    let kind: sidecar::KindOnly = sidecar.parse()?;
    if kind.kind.get_ref() == "tensile" {
        let all = TensileExperiment::load_all(toml_file)?;
        return Ok(all.into_iter().map(Experiment::Tensile).collect());
    }
    load_experiment(toml_file).map(|e| vec![e])
}

/// Read the experiment TOML at `toml_file` (its `kind` decides the type) and its CSV.
pub fn load_experiment(toml_file: &Path) -> Result<Experiment, ExperimentError> {
    let sidecar = sidecar::Sidecar::read(toml_file)?;
    let kind: sidecar::KindOnly = sidecar.parse()?;
    match kind.kind.get_ref().as_str() {
        "tensile" => TensileExperiment::load(toml_file).map(Experiment::Tensile),
        "shpb" => ShpbExperiment::load(toml_file).map(Experiment::Shpb),
        other => Err(ExperimentError::WrongKind {
            at: sidecar.at(kind.kind.span()),
            key: "kind".into(),
            found: other.to_string(),
            expected: "tensile\" or \"shpb".into(),
        }),
    }
}
