//! The exact derivatives of the cutting force (library `cutting`, `solver::Tangent`)
//! against central differences: the coarse orthogonal cut (dx = 2e-4 m, n_y = 40, the
//! shipped 42CrMo4) over its first 4 µs, in which the tool meets the workpiece (at
//! 2.1 µs) and the chip starts: polygon-tool penalty contact, the base's springs and the
//! JC return in every direction. Along A and C, p ∂f/∂p of the tool force f_x and f_y at
//! every history row against (f(p + h) − f(p − h)) p / 2h at h = 1e-6 p, the error as a
//! fraction of the largest |p ∂f/∂p| of the run (the contact's stiff penalty makes single
//! rows spike: the largest is about a hundred times the force itself).
//!
//! The step: at 1e-5 p the quotient straddles contact events (points entering or
//! leaving the tool's penalty zone) and is off by 1.4 of the largest value; at 1e-7 p the
//! ten digits of the history's force give 2e-5; 1e-6 p lies between (measured 2e-6 for
//! f_x along A).

use crate::verify::row::Row;
use crate::verify::Inputs;
use cutting::orthogonal::{OrthogonalCut, Resolution};
use cutting::orthogonal_result::TOOL;
use cutting::record::ToolForce;
use cutting::workpiece::RunOptions;
use materials::Model;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

/// The parameters checked.
const FREE: [&str; 2] = ["A", "C"];

/// The central-difference step, relative to the parameter.
const STEP: f64 = 1e-6;

/// The largest error as a fraction of the largest |p ∂f/∂p|: the bound the tangent tests
/// use (round-off amplified through the run at 1e-7 is about 1e-5; a missing term of the
/// derivative is off by 1e-2 or more).
const TOLERANCE: f64 = 3e-5;

pub fn rows(inputs: &Inputs) -> anyhow::Result<Vec<Row>> {
    let scene_file = inputs
        .data
        .scenes()
        .join("cutting/orthogonal_dx0.0002_ny80.toml");
    let material = inputs.data.materials().join("42crmo4_qt660.toml");
    let exact_dir = run(&scene_file, &material, None, &FREE)?;
    let derivatives = exact_dir.join("derivatives.csv");
    let mut rows = Vec::new();
    for name in FREE {
        let exact = ToolForce::read_sensitivity(&derivatives, TOOL, name)?;
        let value = parameter(&material, name)?;
        let h = STEP * value;
        let [up, down] = [h, -h].map(|dp| -> anyhow::Result<ToolForce> {
            let dir = run(&scene_file, &material, Some((name, value + dp)), &[])?;
            let force = ToolForce::read(&dir.join("history.csv"), TOOL);
            std::fs::remove_dir_all(&dir)?;
            force
        });
        let (up, down) = (up?, down?);
        let axes: [(&str, fn(&ToolForce) -> &[f64]); 2] =
            [("x", |f| &f.force_x), ("y", |f| &f.force_y)];
        for (axis, of) in axes {
            let central: Vec<f64> = (of(&up).iter().zip(of(&down)))
                .map(|(u, d)| (u - d) * value / (2.0 * h))
                .collect();
            let largest = of(&exact).iter().fold(0.0, |m: f64, e| m.max(e.abs()));
            let error = (of(&exact).iter().zip(&central))
                .fold(0.0, |m: f64, (e, c)| m.max((e - c).abs()))
                / largest;
            rows.push(
                Row::at_most(
                    format!("cutting/orthogonal/derivative-f_{axis}-{name}"),
                    error,
                    TOLERANCE,
                )
                .with_note(format!(
                    "coarse cut, first 4 µs, {} rows: largest |exact − central| of p ∂f_{axis}/∂{name} (h = {STEP:e} p) over the largest |p ∂f_{axis}/∂{name}|, {:.3e} N/m",
                    central.len(),
                    largest
                )),
            );
        }
    }
    std::fs::remove_dir_all(&exact_dir)?;
    Ok(rows)
}

/// Run the coarse cut for 4 µs in a scratch folder, with parameter `changed` set to its
/// value if given and derivatives along `free`; the folder.
fn run(
    scene_file: &Path,
    material: &Path,
    changed: Option<(&str, f64)>,
    free: &[&str],
) -> anyhow::Result<PathBuf> {
    let cut = OrthogonalCut {
        end: 4e-6,
        ..OrthogonalCut::default()
    };
    let resolution = Resolution {
        spacing: 2e-4,
        points_y: 40,
    };
    let options = RunOptions {
        snapshots: 1,
        derivatives: free.iter().map(|p| p.to_string()).collect(),
        ..RunOptions::new(cutting::orthogonal::MATERIAL)
    };
    let mut spec = cut.scene(&resolution, &options);
    if let Some((name, value)) = changed {
        let mut table: toml::Table = toml::from_str(&std::fs::read_to_string(material)?)?;
        let jc = (table.get_mut("johnson_cook").and_then(|t| t.as_table_mut()))
            .ok_or_else(|| anyhow::anyhow!("{}: no [johnson_cook]", material.display()))?;
        jc.insert(name.into(), toml::Value::Float(value));
        spec.materials[0].file = None;
        spec.materials[0].parameters = Some(table);
    }
    let scene = mpm_core::scene::from_description(&spec, scene_file)?;
    let tag = changed.map_or("exact".to_string(), |(n, v)| format!("{n}{v:e}"));
    let dir = std::env::temp_dir().join(format!(
        "mpw-verify-cut-derivatives-{}-{tag}",
        std::process::id()
    ));
    let summary = mpm_core::run::run_scene(scene, &dir, |_| {}, |_, _| ControlFlow::Continue(()))?;
    if let Some(f) = summary.failure {
        anyhow::bail!("the coarse orthogonal cut stopped: {f}");
    }
    Ok(dir)
}

/// The value of Johnson-Cook parameter `name` in the material file.
fn parameter(material: &Path, name: &str) -> anyhow::Result<f64> {
    materials::load_elasto_plastic(material)?
        .param(name)
        .ok_or_else(|| anyhow::anyhow!("{}: no parameter {name}", material.display()))
}
