//! What a run description (`runs::RunDescription`) means to mpw: the table of run kinds
//! that `mpw run-one` and the in-process executor execute.
//!
//! - `scene`: an MPM scene file (`mpw simulate`'s) with the description's changes set by
//!   field path and its seed as `grid.seed` (the grid-shift sequence); the outcome is the
//!   scene's named results (`mpm_core::results`) and `run.time` (the time reached: the
//!   end, or where the run stopped), `run.steps`, `run.dt`, `run.particles`; a
//!   simulation that stops early is an outcome with its failure;
//! - `prediction`: one experiment of a fit set predicted at one material
//!   (`fitting::fit::evaluations::task`), the runs of `mpw fit --executor`;
//! - `verify-part`: one part of the verification catalogue (`verify::CATALOGUE`; input:
//!   the data folder; `part = "mpm"`, `full = true`), its rows written to `rows.toml` in
//!   the run folder (a row is more than a value: reference, tolerance, verdict, note); the
//!   outcome counts them.

use anyhow::{bail, Context, Result};
use runs::{Outcome, RunDescription};
use std::ops::ControlFlow;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

/// The run kinds, for messages.
pub const KINDS: [&str; 3] = ["scene", fitting::fit::evaluations::task::KIND, VERIFY_PART];

/// The run kind of a part of the verification catalogue.
pub const VERIFY_PART: &str = "verify-part";

/// Run `description` into `dir`; `stop`, when given, stops a simulation at its next step
/// (the task then fails as interrupted).
pub fn execute(
    description: &RunDescription,
    dir: &Path,
    stop: Option<&AtomicBool>,
) -> Result<Outcome> {
    match description.kind.as_str() {
        "scene" => scene(description, dir, stop),
        fitting::fit::evaluations::task::KIND => {
            fitting::fit::evaluations::task::execute_prediction(description, dir)
        }
        VERIFY_PART => verify_part(description, dir),
        other => bail!("run kind `{other}` is not one of {}", KINDS.join(", ")),
    }
}

/// The scene file of `description` with its changes and seed, as TOML.
pub fn changed_scene(description: &RunDescription) -> Result<toml::Value> {
    let path = &description.input;
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read the scene {}", path.display()))?;
    let mut scene: toml::Value = toml::from_str(&text)
        .map_err(|e| anyhow::anyhow!("{}: {}", path.display(), e.message()))?;
    for (field, value) in &description.set {
        runs::changes::set(&mut scene, field, value.clone())
            .with_context(|| format!("changing {}", path.display()))?;
    }
    if let Some(seed) = description.seed {
        let seed = i64::try_from(seed).context("the seed must be below 2^63")?;
        runs::changes::set(&mut scene, "grid.seed", toml::Value::Integer(seed))
            .with_context(|| format!("seeding {}", path.display()))?;
    }
    Ok(scene)
}

fn scene(description: &RunDescription, dir: &Path, stop: Option<&AtomicBool>) -> Result<Outcome> {
    let path = &description.input;
    if fitting::shpb_model::scene::is_shpb_scene(path) {
        bail!(
            "{} is an SHPB scene; the run kind `scene` takes MPM scenes",
            path.display()
        );
    }
    let spec: mpm_core::scene::SceneFile =
        changed_scene(description)?
            .try_into()
            .map_err(|e: toml::de::Error| {
                anyhow::anyhow!(
                    "{} with the description's changes: {}",
                    path.display(),
                    e.message()
                )
            })?;
    let scene = mpm_core::scene::from_description(&spec, path)?;
    let end = scene.end;
    let mut warnings = Vec::new();
    let summary = mpm_core::run::run_scene(
        scene,
        dir,
        |ts| warnings.extend(ts.risk().map(|r| r.to_string())),
        |_, _| match stop.is_some_and(|s| s.load(Ordering::Relaxed)) {
            true => ControlFlow::Break(()),
            false => ControlFlow::Continue(()),
        },
    )
    .with_context(|| format!("writing the run's output to {}", dir.display()))?;
    if stop.is_some_and(|s| s.load(Ordering::Relaxed)) {
        bail!("interrupted at step {}", summary.steps);
    }
    warnings.extend(summary.melting.iter().map(|m| m.to_string()));
    let mut outcome = Outcome {
        failure: summary.failure.as_ref().map(|f| f.to_string()),
        warnings,
        ..Outcome::default()
    };
    for r in &summary.results {
        outcome.push(&r.name, r.value, r.unit);
    }
    let reached = summary.failure.as_ref().map_or(end, |f| f.time);
    outcome.push("run.time", reached, "s");
    outcome.push("run.steps", summary.steps as f64, "-");
    outcome.push("run.dt", summary.time_step.dt, "s");
    outcome.push("run.particles", summary.particles as f64, "-");
    Ok(outcome)
}

/// The rows file of a `verify-part` run.
pub const ROWS_FILE: &str = "rows.toml";

#[derive(serde::Serialize, serde::Deserialize)]
pub struct VerifyRows {
    pub rows: Vec<crate::verify::row::Row>,
}

fn verify_part(description: &RunDescription, dir: &Path) -> Result<Outcome> {
    let setting = |key: &str| description.set.get(key);
    let Some(part) = setting("part").and_then(|v| v.as_str()) else {
        bail!("a verify-part run needs `part` (a part of the catalogue)");
    };
    let full = match setting("full") {
        None => false,
        Some(v) => v.as_bool().context("`full` must be true or false")?,
    };
    let data = crate::verify::data::VerifyData::new(&description.input);
    let inputs = crate::verify::Inputs { data: &data, full };
    let rows = crate::verify::part(&inputs, part)?;
    let count = rows.len();
    let text = toml::to_string(&VerifyRows { rows }).context("rows as TOML")?;
    runs::atomic::write(&dir.join(ROWS_FILE), &text)?;
    let mut outcome = Outcome::default();
    outcome.push("rows", count as f64, "-");
    Ok(outcome)
}
