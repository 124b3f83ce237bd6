//! A batch: a folder of task folders `task-0` ... `task-{n-1}`, each with its description,
//! and the report of each task read from the files it left (`TaskReport`), the same
//! whichever executor ran it.

use crate::description::RunDescription;
use crate::manifest::{Manifest, Status};
use crate::outcome::Outcome;
use crate::task::TaskDir;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

#[derive(Debug, Clone)]
pub struct Batch {
    pub dir: PathBuf,
    pub len: usize,
}

/// How a task ended, from its files.
#[derive(Debug, Clone)]
pub struct TaskReport {
    pub index: usize,
    /// How many times it was started.
    pub attempts: usize,
    pub result: Result<(Outcome, Manifest), TaskFailure>,
}

/// A task that did not give an outcome: why, and its newest log.
#[derive(Debug, Clone)]
pub struct TaskFailure {
    pub message: String,
    pub log: Option<PathBuf>,
}

impl std::fmt::Display for TaskFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.message)?;
        if let Some(log) = &self.log {
            write!(f, " (log: {})", log.display())?;
        }
        Ok(())
    }
}

impl Batch {
    /// Make the batch folder `dir` with one task folder per description; task folders of
    /// an earlier batch in `dir` are removed first, so that no old file is read as new.
    pub fn create(dir: &Path, descriptions: &[RunDescription]) -> Result<Batch> {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        for entry in std::fs::read_dir(dir)? {
            let entry = entry?;
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.starts_with("task-") && entry.file_type()?.is_dir() {
                std::fs::remove_dir_all(entry.path())?;
            }
        }
        let dir = dir.canonicalize()?;
        for (i, d) in descriptions.iter().enumerate() {
            let task = TaskDir(dir.join(format!("task-{i}")));
            std::fs::create_dir_all(&task.0)?;
            d.write(&task.description())?;
        }
        Ok(Batch {
            dir,
            len: descriptions.len(),
        })
    }

    pub fn task(&self, index: usize) -> TaskDir {
        TaskDir(self.dir.join(format!("task-{index}")))
    }

    /// Whether task `index` has finished (its manifest is there).
    pub fn finished(&self, index: usize) -> bool {
        self.task(index).manifest().is_file()
    }

    /// The report of task `index` after `attempts` starts.
    pub fn report(&self, index: usize, attempts: usize) -> TaskReport {
        let task = self.task(index);
        let log = newest_log(&task.0);
        let result = match Manifest::read(&task.manifest()) {
            Err(_) => Err(TaskFailure {
                message: format!(
                    "task {index} ended {attempts} time(s) without a manifest (stopped from outside: killed, out of memory, time limit or node lost)"
                ),
                log,
            }),
            Ok(m) if m.status == Status::Failed => Err(TaskFailure {
                message: format!(
                    "task {index} failed: {}",
                    m.message.as_deref().unwrap_or("no reason given")
                ),
                log,
            }),
            Ok(m) => Outcome::read(&task.outcome())
                .map(|o| (o, m))
                .map_err(|e| TaskFailure {
                    message: format!("task {index}: {e:#}"),
                    log,
                }),
        };
        TaskReport {
            index,
            attempts,
            result,
        }
    }
}

/// The most recently written `log-*.txt` of a task folder.
fn newest_log(dir: &Path) -> Option<PathBuf> {
    std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| e.ok())
        .filter(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name.starts_with("log-") && name.ends_with(".txt")
        })
        .max_by_key(|e| e.metadata().and_then(|m| m.modified()).ok())
        .map(|e| e.path())
}
