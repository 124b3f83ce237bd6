//! Synthetic data with a known truth: experiment files from a stated parameter set
//! (`synth`), and SHPB data from another model than the ones fitted (`mpm_synthetic`,
//! its data kept in a file by `synthetic_data`).

pub mod mpm_synthetic;
pub mod synth;
pub mod synthetic_data;
