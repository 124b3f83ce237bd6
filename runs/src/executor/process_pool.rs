//! The local process pool: `workers` subprocesses `PROGRAM run-one DESCRIPTION DIR` at a
//! time, each with `RAYON_NUM_THREADS = threads_per_task` and its output in the task's
//! `log-<attempt>.txt`. `workers × threads_per_task` should not exceed the CPUs this
//! process may use (`new` makes it so): a thread beyond them only waits for a CPU.
//!
//! Batches may be run from several threads at once (a bootstrap's refits): the pool counts
//! its running subprocesses across them, so that `workers` is the limit of them all.
//!
//! Each subprocess leads its own process group, so that a Ctrl-C at the terminal reaches
//! this process alone, which then stops every task it started (SIGTERM to its group, so a
//! run writes its last state) and waits for them.

use super::{in_rounds, BatchState, Executor, Progress};
use crate::batch::{Batch, TaskReport};
use anyhow::{Context, Result};
use std::os::unix::process::CommandExt;
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

pub struct ProcessPool {
    /// The program with a `run-one DESCRIPTION DIR` command.
    pub program: PathBuf,
    pub workers: usize,
    pub threads_per_task: usize,
    /// Starts again of a task left without a manifest.
    pub retries: usize,
    /// Subprocesses running, over every batch under way.
    running: AtomicUsize,
}

/// How often the pool looks at its subprocesses.
const POLL: Duration = Duration::from_millis(5);

impl ProcessPool {
    /// `cpus / threads_per_task` workers (at least one).
    pub fn new(program: PathBuf, cpus: usize, threads_per_task: usize, retries: usize) -> Self {
        let threads_per_task = threads_per_task.max(1);
        ProcessPool {
            program,
            workers: (cpus / threads_per_task).max(1),
            threads_per_task,
            retries,
            running: AtomicUsize::new(0),
        }
    }

    /// Take a place for one more subprocess, if there is one.
    fn take_place(&self) -> bool {
        self.running
            .fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| {
                (n < self.workers).then_some(n + 1)
            })
            .is_ok()
    }

    fn give_places(&self, n: usize) {
        self.running.fetch_sub(n, Ordering::AcqRel);
    }

    fn start(&self, batch: &Batch, index: usize, attempt: usize) -> Result<Child> {
        let task = batch.task(index);
        let log_path = task.0.join(format!("log-{attempt}.txt"));
        let log = std::fs::File::create(&log_path)
            .with_context(|| format!("cannot create {}", log_path.display()))?;
        Command::new(&self.program)
            .arg("run-one")
            .arg(task.description())
            .arg(&task.0)
            .env("RAYON_NUM_THREADS", self.threads_per_task.to_string())
            .stdin(Stdio::null())
            .stdout(log.try_clone()?)
            .stderr(log)
            .process_group(0)
            .spawn()
            .with_context(|| format!("cannot start {}", self.program.display()))
    }
}

impl Executor for ProcessPool {
    fn describe(&self) -> String {
        format!(
            "{} processes of {} thread(s)",
            self.workers, self.threads_per_task
        )
    }

    fn run(&self, batch: &Batch, stop: &AtomicBool, progress: Progress) -> Result<Vec<TaskReport>> {
        in_rounds(batch, self.retries, stop, |tasks, attempt| {
            let mut queue = tasks.iter().copied().peekable();
            let mut running: Vec<Child> = Vec::new();
            let mut done = 0;
            loop {
                if stop.load(Ordering::Relaxed) {
                    self.give_places(running.len());
                    return terminate(running);
                }
                while queue.peek().is_some() && self.take_place() {
                    let i = queue.next().expect("peeked");
                    match self.start(batch, i, attempt) {
                        Ok(child) => running.push(child),
                        Err(e) => {
                            self.give_places(running.len() + 1);
                            terminate(running)?;
                            return Err(e);
                        }
                    }
                }
                if running.is_empty() && queue.peek().is_none() {
                    return Ok(());
                }
                let before = running.len();
                running.retain_mut(|child| !matches!(child.try_wait(), Ok(Some(_))));
                if running.len() < before {
                    self.give_places(before - running.len());
                    done += before - running.len();
                    progress(&BatchState {
                        done: batch.len - tasks.len() + done,
                        all: batch.len,
                        running: running.len(),
                        waiting: queue.len(),
                    });
                } else {
                    std::thread::sleep(POLL);
                }
            }
        })
    }
}

/// SIGTERM to each child's process group, then wait for every child.
fn terminate(running: Vec<Child>) -> Result<()> {
    for child in &running {
        let group = child.id() as libc::pid_t;
        // SIGTERM to the group the child leads: the child and whatever it started
        // SAFETY: kill has no memory effects; a group that has already ended gives ESRCH.
        unsafe { libc::kill(-group, libc::SIGTERM) };
    }
    for mut child in running {
        child.wait()?;
    }
    Ok(())
}
