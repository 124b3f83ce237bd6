//! Experiments (CSV and SHPB records), SHPB signal processing, the SHPB test as an MPM
//! model, Johnson-Cook fitting (model levels, objective, optimizers, statistics, reports)
//! and solver cards. The `mpw` program (`fitting/mpw`) is built on this library; the
//! library depends on no command-line, chart or terminal crate.

// Input checks are written `!(x > lower)` on purpose: the negation also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::nonminimal_bool)]

pub mod experiment;
pub mod export;
pub mod flow_table;
pub mod shpb;
pub mod shpb_model;
pub mod tabulated_cards;

pub use experiment::{load_experiment, Experiment, ExperimentError};
pub mod fit;
