//! Johnson-Cook parameter identification: model levels for experiments, the objective,
//! optimizers (Nelder-Mead from argmin, Levenberg-Marquardt with the exact AD Jacobian or
//! finite differences), staged and multi-start fits, statistics and reports.

pub mod assumptions;
pub mod bootstrap;
pub mod cross_validation;
pub mod fit_set;
pub mod identifiability;
pub mod lm;
pub mod model;
pub mod mpm_shpb;
pub mod mpm_synthetic;
pub mod nelder_mead;
pub mod objective;
pub mod params;
pub mod report;
pub mod run;
pub mod scatter;
pub mod set_file;
pub mod shpb_input;
pub mod shpb_specimen;
pub mod single_point;
pub mod study_report;
pub mod synth;
pub mod tensile;
pub mod trace;
