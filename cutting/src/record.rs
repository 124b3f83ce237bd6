//! What a cutting run leaves: the tool's contact force per unit thickness against time (read
//! from the run's history, columns `time_s` and `<tool>_force_<axis>_n_per_m`), with exact
//! derivatives its sensitivities p ∂f/∂p to each parameter p (`derivatives.csv`, columns
//! `<tool>_force_<axis>_<p>_n_per_m`, `mpm_core::derivative_history`), and how far
//! the run got (`RunRecord`, the run folder's `run.toml`). The force on the tool is the
//! reaction of the workpiece: a punch pressing down feels f_y > 0.

use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};

/// The tool force history of one run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ToolForce {
    /// Times of the history rows [s].
    pub time_s: Vec<f64>,
    /// Force on the tool per metre of thickness, x and y [N/m].
    pub force_x: Vec<f64>,
    pub force_y: Vec<f64>,
}

impl ToolForce {
    /// Read `tool`'s force from a plane-strain run's `history.csv`.
    pub fn read(history: &Path, tool: &str) -> Result<ToolForce> {
        Self::read_columns(history, tool, "")
    }

    /// Read the sensitivity p ∂f/∂p [N/m] of `tool`'s force to `parameter` from a
    /// plane-strain run's `derivatives.csv`.
    pub fn read_sensitivity(derivatives: &Path, tool: &str, parameter: &str) -> Result<ToolForce> {
        Self::read_columns(derivatives, tool, &format!("_{parameter}"))
    }

    /// Read the columns `<tool>_force_<axis><infix>_n_per_m` of a CSV file.
    fn read_columns(history: &Path, tool: &str, infix: &str) -> Result<ToolForce> {
        let mut reader = csv::Reader::from_path(history)
            .with_context(|| format!("{}: cannot read the run's history", history.display()))?;
        let header = reader.headers()?.clone();
        let col = |name: &str| {
            header.iter().position(|h| h == name).with_context(|| {
                format!(
                    "{}: no column {name} (a plane-strain run with a rigid body `{tool}`?)",
                    history.display()
                )
            })
        };
        let (t, fx, fy) = (
            col("time_s")?,
            col(&format!("{tool}_force_x{infix}_n_per_m"))?,
            col(&format!("{tool}_force_y{infix}_n_per_m"))?,
        );
        let mut out = ToolForce::default();
        for (k, row) in reader.records().enumerate() {
            let row = row?;
            let number = |c: usize| -> Result<f64> {
                row[c].parse().with_context(|| {
                    format!(
                        "{}: row {}: column {c} is not a number",
                        history.display(),
                        k + 2
                    )
                })
            };
            out.time_s.push(number(t)?);
            out.force_x.push(number(fx)?);
            out.force_y.push(number(fy)?);
        }
        if out.time_s.is_empty() {
            bail!("{}: the history has no rows", history.display());
        }
        Ok(out)
    }

    /// Write relative feed [-], time [s] and both force components [N/m] as CSV, the feed
    /// from `feed_at(t)`.
    pub fn write_csv(&self, path: &Path, feed_at: impl Fn(f64) -> f64) -> Result<()> {
        let mut text =
            String::from("relative_feed,time_s,tool_force_x_n_per_m,tool_force_y_n_per_m\n");
        for k in 0..self.time_s.len() {
            let t = self.time_s[k];
            text += &format!(
                "{:e},{t:e},{:e},{:e}\n",
                feed_at(t),
                self.force_x[k],
                self.force_y[k]
            );
        }
        std::fs::write(path, text).with_context(|| format!("{}: cannot write", path.display()))
    }

    /// The time of the last history row [s].
    pub fn last_time(&self) -> f64 {
        *self.time_s.last().unwrap_or(&0.0)
    }
}

/// The snapshots (`*.vtp`) of a run folder in time order.
pub fn snapshot_files(run: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(run)
        .with_context(|| format!("{}: cannot read the run folder", run.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "vtp"))
        .collect();
    files.sort();
    Ok(files)
}

/// How a run went, kept beside its output as `run.toml`: enough to chart it in a map
/// without running it again.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunRecord {
    pub points: usize,
    pub steps: usize,
    /// Time step [s].
    pub dt_s: f64,
    /// Wall time of the run [s] and the threads it had.
    pub wall_s: f64,
    pub threads: usize,
    /// Simulated time reached [s] and the end the scene asked for.
    pub time_reached_s: f64,
    pub end_s: f64,
    /// Why the run stopped before its end.
    pub failure: Option<String>,
}

impl RunRecord {
    /// The file name in a run folder.
    pub const FILE: &'static str = "run.toml";

    pub fn write(&self, run: &Path) -> Result<()> {
        let path = run.join(Self::FILE);
        std::fs::write(&path, toml::to_string(self)?)
            .with_context(|| format!("{}: cannot write", path.display()))
    }

    /// The record of the run in folder `run`.
    pub fn read(run: &Path) -> Result<RunRecord> {
        let path = run.join(Self::FILE);
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("{}: no record of a finished run", path.display()))?;
        toml::from_str(&text).map_err(|e| anyhow::anyhow!("{}: {}", path.display(), e.message()))
    }

    /// Particle-steps per second.
    pub fn throughput(&self) -> f64 {
        (self.points * self.steps) as f64 / self.wall_s
    }
}
