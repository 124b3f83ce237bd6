//! One task: its folder, and running it there (`run_one`, what `mpw run-one` does).
//!
//! A task folder holds `description.toml` (written by whoever made the batch),
//! `outcome.toml` and `manifest.toml` (written by the run, in that order), the run's own
//! output in `run/`, and the log of each attempt (`log-<attempt>.txt` from a subprocess,
//! `log-<job>.txt` from Slurm).

use crate::description::RunDescription;
use crate::manifest::{host_name, Manifest, Program, Status};
use crate::outcome::Outcome;
use anyhow::Result;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// How a program runs a description: into `dir` (the run's own output), giving its
/// outcome. An error is a failure of the task (status `failed`), not of the simulation.
pub type Execute<'a> = &'a (dyn Fn(&RunDescription, &Path) -> Result<Outcome> + Sync);

/// The files of one task folder.
#[derive(Debug, Clone)]
pub struct TaskDir(pub PathBuf);

impl TaskDir {
    pub fn description(&self) -> PathBuf {
        self.0.join("description.toml")
    }
    pub fn outcome(&self) -> PathBuf {
        self.0.join("outcome.toml")
    }
    pub fn manifest(&self) -> PathBuf {
        self.0.join("manifest.toml")
    }
    /// The run's own output (history, snapshots).
    pub fn run(&self) -> PathBuf {
        self.0.join("run")
    }
}

/// Run the description at `description` into the task folder `dir`: the outcome, then the
/// manifest. The run gets the calling pool's threads, or the description's `threads` when
/// it asks for fewer. A task error is written into the manifest (status `failed`) and
/// returned as well.
pub fn run_one(
    program: Program,
    description: &Path,
    dir: &Path,
    execute: Execute,
) -> Result<Manifest> {
    let task = TaskDir(dir.to_path_buf());
    std::fs::create_dir_all(task.run())?;
    let start = Instant::now();
    let read = RunDescription::read(description);
    let available = rayon::current_num_threads();
    let threads = match read.as_ref().map(|d| d.threads) {
        Ok(asked) if asked > 0 && asked < available => asked,
        _ => available,
    };
    let run = |d: &RunDescription| execute(d, &task.run())?.keep(&d.returns);
    let result = read
        .as_ref()
        .map_err(|e| anyhow::anyhow!("{e:#}"))
        .and_then(|d| match threads < available {
            true => rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()?
                .install(|| run(d)),
            false => run(d),
        })
        .and_then(|outcome| outcome.write(&task.outcome()));
    let manifest = Manifest {
        program: format!("{} {}", program.name, program.version),
        commit: program.commit.to_string(),
        description_hash: read.as_ref().map(|d| d.hash()).unwrap_or_default(),
        seed: read.as_ref().ok().and_then(|d| d.seed),
        threads,
        host: host_name(),
        wall_seconds: start.elapsed().as_secs_f64(),
        status: match result {
            Ok(()) => Status::Ok,
            Err(_) => Status::Failed,
        },
        message: result.as_ref().err().map(|e| format!("{e:#}")),
    };
    manifest.write(&task.manifest())?;
    result.map(|()| manifest)
}
