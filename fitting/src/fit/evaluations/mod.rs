//! Where a fit's model runs go. The objective asks for predictions in batches, every
//! (experiment, material) pair a pass or a Jacobian needs at once (`Request`), so that an
//! executor can run a whole batch side by side: in this process on its threads
//! (`InProcess`, the default), or as tasks of a `runs` executor, a local process pool or a
//! Slurm job array (`executor::ExecutorEvaluations`, tasks of kind `prediction`, run by
//! `task::execute_prediction`). The predictions are the same, bit for bit, either way.
//!
//! The objective forms forward differences (`levels::model::fd_points`, `fd_matrix`) for
//! every model without a cheap Jacobian as requests of the same batch: one per free
//! parameter beside the base point.

pub mod executor;
pub mod task;

use crate::fit::levels::model::Material;
use crate::fit::objective::Block;
use anyhow::{Context, Result};
use rayon::prelude::*;

/// One prediction to make: an experiment's model at a material.
#[derive(Clone, Copy)]
pub struct Request<'a> {
    pub block: &'a Block,
    pub material: Material,
}

/// A prediction at the experiment's samples, and what its run warns about.
pub type Prediction = (Vec<f64>, Vec<String>);

pub trait Evaluations: Send + Sync {
    /// Where the runs go, for reports (`in this process`, `Slurm job arrays on ...`).
    fn describe(&self) -> String;

    /// The prediction of every request, in order; an error names the experiment.
    fn predict(&self, requests: &[Request]) -> Result<Vec<Prediction>>;

    /// How many independent fits (bootstrap refits) may ask for predictions at once: one
    /// in this process, whose threads a single fit's batches already fill.
    fn fits_at_once(&self) -> usize {
        1
    }
}

/// Every request in this process, side by side on its threads.
pub struct InProcess;

/// The default evaluations of an objective.
pub static IN_PROCESS: InProcess = InProcess;

impl Evaluations for InProcess {
    fn describe(&self) -> String {
        format!("in this process, {} threads", rayon::current_num_threads())
    }

    fn predict(&self, requests: &[Request]) -> Result<Vec<Prediction>> {
        requests.par_iter().map(predict_here).collect()
    }
}

/// One request in this process.
pub fn predict_here(r: &Request) -> Result<Prediction> {
    r.block
        .model
        .predict_with_warnings(&r.material)
        .with_context(|| format!("experiment `{}`", r.block.name))
}
