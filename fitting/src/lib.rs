//! Experiments, SHPB signal processing, Johnson-Cook fitting, charts, and the `mpw`
//! subcommands (one module per subcommand in `cli`).

// Input checks are written `!(x > lower)` on purpose: the negation also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::nonminimal_bool)]

pub mod case_result;
pub mod chart;
pub mod cli;
pub mod experiment;
pub mod export;
pub mod heatmap;
pub mod materials_verify;
pub mod mpm_verify;
pub mod shpb;
pub mod shpb_model;
pub mod verify_data;

pub use experiment::{load_experiment, Experiment, ExperimentError};
pub mod fit;
