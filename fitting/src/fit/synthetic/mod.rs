//! Synthetic data with a known truth: experiment files from a stated parameter set
//! (`synth`), and SHPB data from another model than the ones fitted (`mpm_synthetic`).

pub mod mpm_synthetic;
pub mod synth;
