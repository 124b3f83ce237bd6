//! The executor options every command with many runs shares (`mpw sweep`, `mpw fit`):
//! where the runs go (`--executor`), and the Slurm config file or the pool's size.

use anyhow::{bail, Context, Result};
use runs::{Execute, Executor, InProcess, ProcessPool, Slurm, SlurmConfig};
use std::path::PathBuf;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// One run after another in this process, on its threads.
    InProcess,
    /// `mpw run-one` subprocesses, as many at a time as the CPUs allow.
    Pool,
    /// A Slurm job array per round (needs --slurm CONFIG).
    Slurm,
}

#[derive(clap::Args, Debug, Clone)]
pub struct ExecutorArgs {
    /// Where the runs go.
    #[arg(long, value_enum, default_value = "in-process")]
    pub executor: Kind,
    /// The Slurm config (TOML: work_dir, partition, time_limit, cpus_per_task, ...).
    #[arg(long)]
    pub slurm: Option<PathBuf>,
    /// Pool: threads of each run (the pool runs CPUs / this many at a time).
    #[arg(long, default_value_t = 1)]
    pub threads_per_run: usize,
    /// Pool: starts again of a run stopped from outside (Slurm: the config's `retries`).
    #[arg(long, default_value_t = 1)]
    pub retries: usize,
}

impl ExecutorArgs {
    /// The subprocess executor asked for (`None`: in process) and the folder its batches
    /// go to: `local_dir`, or `<job_name>-<process id>` under Slurm's shared `work_dir`.
    pub fn subprocesses(
        &self,
        job_name: &str,
        local_dir: PathBuf,
    ) -> Result<Option<(Box<dyn Executor + Send + Sync>, PathBuf)>> {
        if self.slurm.is_some() && self.executor != Kind::Slurm {
            bail!("--slurm is the config of --executor slurm");
        }
        let this = std::env::current_exe().context("cannot find this program's path")?;
        Ok(match self.executor {
            Kind::InProcess => None,
            Kind::Pool => {
                let cpus = mpm_core::parallel::cpus();
                let pool = ProcessPool::new(this, cpus, self.threads_per_run, self.retries);
                Some((Box::new(pool), local_dir))
            }
            Kind::Slurm => {
                let Some(path) = &self.slurm else {
                    bail!("--executor slurm needs --slurm CONFIG (a TOML file: work_dir, time_limit, max_running, ...)");
                };
                let config = SlurmConfig::read(path)?;
                // this process's own folder: two commands on one work_dir never share one
                let dir = config
                    .work_dir
                    .join(format!("{job_name}-{}", std::process::id()));
                Some((Box::new(Slurm::new(config, this, job_name)), dir))
            }
        })
    }

    /// How many runs the executor asked for runs at once: the CPUs in process, the
    /// pool's workers, Slurm's `max_running`.
    pub fn runs_at_once(&self) -> Result<usize> {
        let cpus = mpm_core::parallel::cpus();
        Ok(match (self.executor, &self.slurm) {
            (Kind::Slurm, Some(path)) => SlurmConfig::read(path)?.max_running,
            (Kind::Pool, _) => (cpus / self.threads_per_run.max(1)).max(1),
            _ => cpus,
        })
    }

    /// The executor asked for, running `execute` when in process, and its batch folder.
    pub fn build<'a>(
        &self,
        job_name: &str,
        execute: Execute<'a>,
        local_dir: PathBuf,
    ) -> Result<(Box<dyn Executor + 'a>, PathBuf)> {
        Ok(match self.subprocesses(job_name, local_dir.clone())? {
            Some((executor, dir)) => (executor, dir),
            None => {
                let program = super::run_one::program();
                (Box::new(InProcess { program, execute }), local_dir)
            }
        })
    }
}
