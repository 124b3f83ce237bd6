//! The Slurm executor: each round of a batch is one job array,
//!
//! `sbatch --parsable --array=<tasks>%<max_running> <batch>/array-<round>.sh`,
//!
//! whose element i runs `PROGRAM run-one <batch>/task-i/description.toml <batch>/task-i`
//! on `cpus_per_task` CPUs with `RAYON_NUM_THREADS = SLURM_CPUS_PER_TASK`, its output in
//! `task-i/log-<job>.txt`. The array's state comes from `squeue` (one line per element:
//! running or pending) until none of it is left; what each task did is then read from its files (Slurm forgets finished jobs, and
//! its accounting may be off). A stop cancels the array with `scancel` and waits until
//! `squeue` shows none of it.
//!
//! The batch folder must be on a file system the compute nodes share (`work_dir`).

use super::{in_rounds, BatchState, Executor, Progress, SlurmConfig};
use crate::batch::{Batch, TaskReport};
use anyhow::{bail, Context, Result};
use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

pub struct Slurm {
    pub config: SlurmConfig,
    /// The program the compute nodes run (`config.program`, else this program).
    pub program: PathBuf,
    /// The job name, e.g. `mpw-sweep`.
    pub job_name: String,
}

/// How long a cancelled array may take to leave the queue.
const CANCEL_WAIT: Duration = Duration::from_secs(120);

impl Slurm {
    pub fn new(config: SlurmConfig, this_program: PathBuf, job_name: &str) -> Self {
        let program = config.program.clone().unwrap_or(this_program);
        Slurm {
            config,
            program,
            job_name: job_name.to_string(),
        }
    }

    /// The batch script of the arrays of `batch`.
    pub fn script(&self, batch: &Batch) -> String {
        let c = &self.config;
        let dir = batch.dir.display().to_string();
        let mut lines = vec![
            "#!/bin/bash".to_string(),
            format!("#SBATCH --job-name={}", self.job_name),
            format!(
                "#SBATCH --output={}",
                quote(&format!("{dir}/task-%a/log-%A.txt"))
            ),
            format!("#SBATCH --cpus-per-task={}", c.cpus_per_task),
            format!("#SBATCH --time={}", c.time_limit),
        ];
        lines.extend(
            c.partition
                .iter()
                .map(|p| format!("#SBATCH --partition={p}")),
        );
        lines.extend(c.account.iter().map(|a| format!("#SBATCH --account={a}")));
        lines.extend(c.sbatch_options.iter().map(|o| format!("#SBATCH {o}")));
        lines.push(format!(
            "export RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-{}}}\"",
            c.cpus_per_task
        ));
        lines.push(format!(
            "task={}/task-\"$SLURM_ARRAY_TASK_ID\"",
            quote(&dir)
        ));
        lines.push(format!(
            "exec {} run-one \"$task/description.toml\" \"$task\"",
            quote(&self.program.display().to_string())
        ));
        lines.join("\n") + "\n"
    }

    fn submit(&self, batch: &Batch, tasks: &[usize], attempt: usize) -> Result<String> {
        let script = batch.dir.join(format!("array-{attempt}.sh"));
        crate::atomic::write(&script, &self.script(batch))?;
        let array = format!("--array={}%{}", ranges(tasks), self.config.max_running);
        let out = command(
            "sbatch",
            &["--parsable", &array, &script.display().to_string()],
        )?;
        // --parsable prints `jobid` or `jobid;cluster`
        let id = out.split(';').next().unwrap_or_default().trim().to_string();
        if id.is_empty() || !id.bytes().all(|b| b.is_ascii_digit()) {
            bail!("sbatch gave `{out}`, not a job id");
        }
        Ok(id)
    }

    /// Wait until no element of array `id` is queued or running; on `stop`, cancel it first.
    fn wait(
        &self,
        batch: &Batch,
        id: &str,
        tasks: &[usize],
        stop: &AtomicBool,
        progress: Progress,
    ) -> Result<()> {
        let poll = Duration::from_secs_f64(self.config.poll_seconds);
        loop {
            if stop.load(Ordering::Relaxed) {
                command("scancel", &[id])?;
                let since = Instant::now();
                while queue_state(id)?.is_some() {
                    if since.elapsed() > CANCEL_WAIT {
                        bail!("job array {id} is still in the queue {CANCEL_WAIT:?} after scancel");
                    }
                    std::thread::sleep(Duration::from_millis(200));
                }
                return Ok(());
            }
            let Some((running, waiting)) = queue_state(id)? else {
                return Ok(());
            };
            let done = tasks.iter().filter(|&&i| batch.finished(i)).count();
            progress(&BatchState {
                done: done + batch.len - tasks.len(),
                all: batch.len,
                running,
                waiting,
            });
            std::thread::sleep(poll);
        }
    }
}

impl Executor for Slurm {
    fn describe(&self) -> String {
        let c = &self.config;
        let partition = c.partition.as_deref().unwrap_or("the default partition");
        format!(
            "Slurm job arrays on {partition}, {} CPU(s) per task, at most {} at once",
            c.cpus_per_task, c.max_running
        )
    }

    fn run(&self, batch: &Batch, stop: &AtomicBool, progress: Progress) -> Result<Vec<TaskReport>> {
        in_rounds(batch, self.config.retries, stop, |tasks, attempt| {
            let id = self.submit(batch, tasks, attempt)?;
            eprintln!("submitted job array {id} ({} tasks)", tasks.len());
            self.wait(batch, &id, tasks, stop, progress)
        })
    }
}

/// The elements of job array `id` that `squeue` lists, as (running, waiting) — pending
/// ones waiting, every other state running —, or `None` once none is listed. A job Slurm
/// no longer knows ("Invalid job id") has left the queue.
fn queue_state(id: &str) -> Result<Option<(usize, usize)>> {
    let out = Command::new("squeue")
        .args(["-h", "-r", "-o", "%t", "-j", id])
        .output()
        .context("cannot run squeue (is Slurm installed and SLURM_CONF set?)")?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        if stderr.contains("Invalid job id") {
            return Ok(None);
        }
        bail!("squeue -j {id} failed: {}", stderr.trim());
    }
    let states = String::from_utf8_lossy(&out.stdout);
    let states: Vec<&str> = states.split_whitespace().collect();
    if states.is_empty() {
        return Ok(None);
    }
    let waiting = states.iter().filter(|s| **s == "PD").count();
    Ok(Some((states.len() - waiting, waiting)))
}

/// Run a Slurm command; its standard output, or an error with its standard error.
fn command(program: &str, args: &[&str]) -> Result<String> {
    let out = Command::new(program).args(args).output().with_context(|| {
        format!("cannot run {program} (is Slurm installed and SLURM_CONF set?)")
    })?;
    if !out.status.success() {
        bail!(
            "{program} {} failed: {}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// Sorted task indices as Slurm's array list: `0-7`, `1,3,5-6`.
fn ranges(tasks: &[usize]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < tasks.len() {
        let start = tasks[i];
        while i + 1 < tasks.len() && tasks[i + 1] == tasks[i] + 1 {
            i += 1;
        }
        parts.push(match tasks[i] {
            end if end == start => start.to_string(),
            end => format!("{start}-{end}"),
        });
        i += 1;
    }
    parts.join(",")
}

/// `text` in single quotes for bash.
fn quote(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn task_lists_are_written_as_slurm_ranges() {
        assert_eq!(ranges(&[0, 1, 2, 3]), "0-3");
        assert_eq!(ranges(&[1, 3, 5, 6]), "1,3,5-6");
        assert_eq!(ranges(&[4]), "4");
    }

    #[test]
    fn the_script_runs_the_task_on_its_cpus_with_the_configured_options() {
        let config: SlurmConfig = toml::from_str(
            "work_dir = \"/w\"\npartition = \"short\"\ntime_limit = \"5\"\ncpus_per_task = 2\nmax_running = 3\nsbatch_options = [\"--qos=low\"]\n",
        )
        .unwrap();
        let slurm = Slurm::new(config, "/opt/it's/mpw".into(), "mpw-sweep");
        let batch = Batch {
            dir: "/w/b".into(),
            len: 2,
        };
        let s = slurm.script(&batch);
        for line in [
            "#SBATCH --output='/w/b/task-%a/log-%A.txt'",
            "#SBATCH --cpus-per-task=2",
            "#SBATCH --time=5",
            "#SBATCH --partition=short",
            "#SBATCH --qos=low",
            "export RAYON_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-2}\"",
            r"exec '/opt/it'\''s/mpw' run-one",
        ] {
            assert!(s.contains(line), "{line} not in\n{s}");
        }
    }
}
