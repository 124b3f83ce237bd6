//! A fit's expensive runs through a `runs` executor (a local process pool, a Slurm job
//! array): each batch of requests becomes a batch of `prediction` tasks (`task`) in a
//! folder `batch-<k>` of `work_dir`, removed once its predictions are read (kept, with
//! the tasks' logs, when one failed). Requests of models with a cheap Jacobian (the
//! single-point levels, milliseconds a run) stay in this process: a task costs more than
//! such a run.

use super::task::{description, SERIES};
use super::{predict_here, Evaluations, Prediction, Request};
use anyhow::{bail, Context, Result};
use rayon::prelude::*;
use runs::{Batch, Executor};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

pub struct ExecutorEvaluations {
    pub executor: Box<dyn Executor + Send + Sync>,
    /// The fit set's file, as the tasks read it (absolute, on a shared file system).
    pub set_file: PathBuf,
    /// Where the batches go.
    pub work_dir: PathBuf,
    /// Set to cancel the batch under way.
    pub stop: Arc<AtomicBool>,
    /// Independent fits that may run at once (`Evaluations::fits_at_once`).
    pub fits_at_once: usize,
    batches: AtomicUsize,
}

impl ExecutorEvaluations {
    pub fn new(
        executor: Box<dyn Executor + Send + Sync>,
        set_file: PathBuf,
        work_dir: PathBuf,
        stop: Arc<AtomicBool>,
    ) -> Result<Self> {
        let set_file = set_file
            .canonicalize()
            .with_context(|| format!("cannot find {}", set_file.display()))?;
        Ok(ExecutorEvaluations {
            executor,
            set_file,
            work_dir,
            stop,
            fits_at_once: 1,
            batches: AtomicUsize::new(0),
        })
    }

    fn run_batch(&self, requests: &[&Request]) -> Result<Vec<Prediction>> {
        if requests.is_empty() {
            return Ok(Vec::new());
        }
        let k = self.batches.fetch_add(1, Ordering::Relaxed);
        let descriptions: Vec<_> = requests
            .iter()
            .map(|r| description(&self.set_file, r))
            .collect();
        let batch = Batch::create(&self.work_dir.join(format!("batch-{k}")), &descriptions)?;
        let reports = self.executor.run(&batch, &self.stop, &|_| {})?;
        let mut predictions = Vec::with_capacity(reports.len());
        for (report, request) in reports.into_iter().zip(requests) {
            let name = &request.block.name;
            let (outcome, _) = report
                .result
                .map_err(|f| anyhow::anyhow!("experiment `{name}`: {f}"))?;
            let Some(prediction) = outcome.series(SERIES) else {
                bail!("experiment `{name}`: the task's outcome has no `{SERIES}`");
            };
            predictions.push((prediction.to_vec(), outcome.warnings));
        }
        std::fs::remove_dir_all(&batch.dir)
            .with_context(|| format!("cannot remove {}", batch.dir.display()))?;
        Ok(predictions)
    }
}

impl Evaluations for ExecutorEvaluations {
    fn describe(&self) -> String {
        self.executor.describe()
    }

    fn fits_at_once(&self) -> usize {
        self.fits_at_once.max(1)
    }

    fn predict(&self, requests: &[Request]) -> Result<Vec<Prediction>> {
        let remote: Vec<&Request> = requests
            .iter()
            .filter(|r| !r.block.model.jacobian_is_cheap())
            .collect();
        let mut from_batch = self.run_batch(&remote)?.into_iter();
        let here: Vec<Option<Prediction>> = requests
            .par_iter()
            .map(|r| match r.block.model.jacobian_is_cheap() {
                true => predict_here(r).map(Some),
                false => Ok(None),
            })
            .collect::<Result<_>>()?;
        Ok(here
            .into_iter()
            .map(|p| {
                p.unwrap_or_else(|| {
                    from_batch
                        .next()
                        .expect("one prediction per remote request")
                })
            })
            .collect())
    }
}
