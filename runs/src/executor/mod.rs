//! The executors: one interface (`Executor`), three ways of running a batch.
//!
//! Every executor runs the tasks that have not finished, in rounds: after a round, a task
//! without a manifest (stopped from outside) is started again, up to `retries` more times;
//! a task whose manifest says `failed` is not (it would fail again). The reports are then
//! read from the task files (`Batch::report`).

mod in_process;
mod process_pool;
mod slurm;
mod slurm_config;

pub use in_process::InProcess;
pub use process_pool::ProcessPool;
pub use slurm::Slurm;
pub use slurm_config::SlurmConfig;

use crate::batch::{Batch, TaskReport};
use anyhow::{bail, Result};
use std::sync::atomic::{AtomicBool, Ordering};

/// Where a batch stands: tasks finished, in all, running and waiting (the queue's word for
/// Slurm, this executor's for the others).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BatchState {
    pub done: usize,
    pub all: usize,
    pub running: usize,
    pub waiting: usize,
}

impl std::fmt::Display for BatchState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}/{} runs finished, {} running, {} waiting",
            self.done, self.all, self.running, self.waiting
        )
    }
}

/// Progress of a batch, told whenever its state changes (Slurm: at every poll).
pub type Progress<'a> = &'a (dyn Fn(&BatchState) + Sync);

pub trait Executor {
    /// What runs the tasks, for logs (`in-process, 2 threads`, `slurm partition ci`).
    fn describe(&self) -> String;

    /// Run every task of `batch` and report each. When `stop` is set the tasks under way
    /// are cancelled and the call fails with `cancelled`; finished tasks keep their files.
    fn run(&self, batch: &Batch, stop: &AtomicBool, progress: Progress) -> Result<Vec<TaskReport>>;
}

/// Run `batch` in rounds of `round(tasks, attempt)` (attempt 1, 2, ...), starting again the
/// tasks left without a manifest, up to `retries` more times; then report every task.
pub(crate) fn in_rounds(
    batch: &Batch,
    retries: usize,
    stop: &AtomicBool,
    mut round: impl FnMut(&[usize], usize) -> Result<()>,
) -> Result<Vec<TaskReport>> {
    let mut attempts = vec![0; batch.len];
    for attempt in 1..=retries + 1 {
        let pending: Vec<usize> = (0..batch.len).filter(|&i| !batch.finished(i)).collect();
        if pending.is_empty() {
            break;
        }
        for &i in &pending {
            attempts[i] = attempt;
        }
        round(&pending, attempt)?;
        if stop.load(Ordering::Relaxed) {
            bail!(
                "cancelled: the batch in {} was stopped",
                batch.dir.display()
            );
        }
    }
    Ok((0..batch.len)
        .map(|i| batch.report(i, attempts[i]))
        .collect())
}
