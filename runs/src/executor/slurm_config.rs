//! The Slurm executor's settings, from a TOML file (the cluster's, not the code's):
//!
//! ```toml
//! work_dir = "/scratch/me/mpw"   # shared by this machine and the compute nodes
//! program = "/home/me/bin/mpw"   # mpw as the compute nodes see it (default: this mpw)
//! partition = "short"            # optional
//! account = "proj42"             # optional
//! time_limit = "00:30:00"        # per task, Slurm's format
//! cpus_per_task = 2              # the task runs this many threads, never more
//! max_running = 16               # tasks of an array at once (--array=0-K%M)
//! retries = 1                    # starts again of a task left without a manifest
//! poll_seconds = 5               # how often squeue is asked
//! sbatch_options = ["--qos=normal"]   # passed to sbatch as they are
//! ```

use anyhow::{bail, Result};
use serde::Deserialize;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlurmConfig {
    pub work_dir: PathBuf,
    #[serde(default)]
    pub program: Option<PathBuf>,
    #[serde(default)]
    pub partition: Option<String>,
    #[serde(default)]
    pub account: Option<String>,
    pub time_limit: String,
    #[serde(default = "one")]
    pub cpus_per_task: usize,
    pub max_running: usize,
    #[serde(default = "one")]
    pub retries: usize,
    #[serde(default = "five")]
    pub poll_seconds: f64,
    #[serde(default)]
    pub sbatch_options: Vec<String>,
}

fn one() -> usize {
    1
}

fn five() -> f64 {
    5.0
}

impl SlurmConfig {
    /// Read and check a config file; a relative `work_dir` or `program` is relative to
    /// the file's folder.
    pub fn read(path: &Path) -> Result<Self> {
        let mut config: SlurmConfig = crate::atomic::read_toml(path, "the Slurm config")?;
        let folder = path.parent().unwrap_or(Path::new("."));
        config.work_dir = folder.join(&config.work_dir);
        config.program = config.program.map(|p| folder.join(p));
        config
            .check()
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        Ok(config)
    }

    fn check(&self) -> Result<()> {
        if self.cpus_per_task == 0 {
            bail!("`cpus_per_task` must be at least 1");
        }
        if self.max_running == 0 {
            bail!("`max_running` must be at least 1");
        }
        if !(self.poll_seconds > 0.0 && self.poll_seconds <= 600.0) {
            bail!(
                "`poll_seconds` = {} is not within (0, 600]",
                self.poll_seconds
            );
        }
        let clock = |s: &str| {
            s.split(['-', ':'])
                .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
        };
        if !clock(&self.time_limit) {
            bail!(
                "`time_limit` = \"{}\" is not a Slurm time (minutes, MM:SS, HH:MM:SS or D-HH:MM:SS)",
                self.time_limit
            );
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<SlurmConfig> {
        let dir = std::env::temp_dir().join(format!("runs-slurm-config-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("slurm.toml");
        std::fs::write(&path, text).unwrap();
        let config = SlurmConfig::read(&path);
        std::fs::remove_dir_all(&dir).unwrap();
        config
    }

    #[test]
    fn a_config_reads_with_defaults_and_bad_values_are_named() {
        let c = read("work_dir = \"/scratch/mpw\"\ntime_limit = \"00:10:00\"\nmax_running = 4\n")
            .unwrap();
        assert_eq!((c.cpus_per_task, c.retries, c.poll_seconds), (1, 1, 5.0));
        assert_eq!(c.work_dir, PathBuf::from("/scratch/mpw"));
        let e =
            read("work_dir = \"w\"\ntime_limit = \"ten minutes\"\nmax_running = 4\n").unwrap_err();
        assert!(e.to_string().contains("slurm.toml: `time_limit`"), "{e}");
        let e = read("work_dir = \"w\"\ntime_limit = \"10\"\nmax_running = 0\n").unwrap_err();
        assert!(
            e.to_string().contains("`max_running` must be at least 1"),
            "{e}"
        );
        let e = read("work_dir = \"w\"\ntime_limit = \"10\"\nmax_running = 2\npartiton = \"x\"\n")
            .unwrap_err();
        assert!(e.to_string().contains("partiton"), "{e}");
    }
}
