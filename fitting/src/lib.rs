//! Experiments, SHPB signal processing, Johnson-Cook fitting, charts, and the `mpw`
//! subcommands (one module per subcommand in `cli`).

pub mod chart;
pub mod cli;
pub mod experiment;
pub mod heatmap;
pub mod shpb;

pub use experiment::{load_experiment, Experiment, ExperimentError};
pub mod fit;
