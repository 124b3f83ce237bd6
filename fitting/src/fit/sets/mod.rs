//! Experiment sets: the set file as written (`set_file`) and as loaded, with experiments
//! at their model levels, free parameters and stages (`fit_set`).

pub mod fit_set;
pub mod set_file;
