//! `mpw simulate SCENE.toml` on an SHPB scene (`kind = "shpb"`, module
//! `shpb_model::scene`): the MPM model of one SHPB record. Writes `history.csv` (model and
//! measured face forces, face velocities, model and measured gauge strains at the faces,
//! specimen length, on the record's time base), VTK snapshots of the specimen, and the
//! charts `forces.png` and `pulses.png`; prints the force agreement over the plateau.

use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use fitting::fit::reports::report::{read_parameters, show};
use fitting::shpb::signal::interpolate;
use fitting::shpb_model::scene::ShpbScene;
use fitting::shpb_model::study::{contact_sensitivity, refinement, relative_rms, Resolution};
use fitting::shpb_model::{Discretization, Drive, ModelLevel, ShpbRun};
use materials::material::Model;
use materials::plasticity::ElastoPlastic;
use mpm_core::output::SnapshotWriter;
use std::fmt::Write as _;
use std::path::Path;

/// Snapshots written over the run.
const SNAPSHOTS: usize = 10;

/// The scene and its material (the scene's file, or `params`), saying on stderr which
/// parameters the run uses and where they come from.
pub fn load(scene_file: &Path, params: Option<&Path>) -> Result<(ShpbScene, ElastoPlastic)> {
    let scene = ShpbScene::load(scene_file)?;
    let base = materials::load_elasto_plastic(&scene.material_file)?;
    let (material, source) = match params {
        Some(file) => (read_parameters(&base, file)?, file.display().to_string()),
        None => (
            base,
            format!(
                "the material file {} (the file's own values, not a fit's: pass a fit's report with --params out/fit/report.toml)",
                scene.material_file.display()
            ),
        ),
    };
    let values: Vec<String> = ["A", "B", "N", "C", "M"]
        .iter()
        .filter_map(|n| material.param(n).map(|v| format!("{n} = {}", show(n, v))))
        .collect();
    eprintln!("parameters: {} from {source}", values.join(", "));
    Ok((scene, material))
}

/// `--refine`: the scene at each level and point count of `runs`, each against the
/// last; `refinement.csv` and the chart `accuracy_vs_cost.png`.
pub fn refine(scene_file: &Path, params: Option<&Path>, runs: &[String], out: &Path) -> Result<()> {
    let (scene, material) = load(scene_file, params)?;
    let runs = runs
        .iter()
        .map(|r| Discretization::parse(r, scene.settings.level))
        .collect::<Result<Vec<_>, String>>()
        .map_err(|e| anyhow::anyhow!("--refine: {e}"))?;
    let names: Vec<String> = runs.iter().map(|d| d.to_string()).collect();
    println!(
        "{}: {} against {}, one thread each",
        scene.experiment.name,
        names[..names.len() - 1].join(", "),
        names[names.len() - 1]
    );
    let rows = refinement(&scene, &material, &runs, &|d, r| {
        println!(
            "  {d}: {} points, {} steps, {:.2} s",
            r.particles, r.steps, r.wall_s
        )
    })?;
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let mut csv = String::from(
        "level,layers,particles,steps,wall_s,f1_error_vs_reference,f2_error_vs_reference\n",
    );
    println!(
        "{:>22} {:>9} {:>7} {:>9} {:>14} {:>14}",
        "level:layers", "points", "steps", "wall s", "F1 vs ref.", "F2 vs ref."
    );
    for r in &rows {
        let d = r.discretization;
        writeln!(
            csv,
            "{},{},{},{},{:e},{:e},{:e}",
            d.level.name(),
            d.layers,
            r.particles,
            r.steps,
            r.wall_s,
            r.error_incident,
            r.error_transmitted
        )?;
        println!(
            "{:>22} {:>9} {:>7} {:>9.2} {:>13.2}% {:>13.2}%",
            d.to_string(),
            r.particles,
            r.steps,
            r.wall_s,
            100.0 * r.error_incident,
            100.0 * r.error_transmitted
        );
    }
    std::fs::write(out.join("refinement.csv"), csv)?;
    let chart = out.join("accuracy_vs_cost.png");
    accuracy_chart(&scene.experiment.name, &rows, &chart)?;
    println!(
        "refinement.csv and accuracy_vs_cost.png in {}",
        out.display()
    );
    Ok(())
}

/// Force error against wall time, one line per model level and face, each point a
/// resolution (the reference, the last row, left out).
fn accuracy_chart(record: &str, rows: &[Resolution], path: &Path) -> Result<()> {
    let (coarse, reference) = rows.split_at(rows.len() - 1);
    let mut chart = LineChart::new(
        format!(
            "{record}: MPM model, accuracy against cost (vs {})",
            reference[0].discretization
        ),
        "log10 wall time of one run, 1 thread [s]",
        "force RMS vs reference over the plateau [%]",
    )
    .markers();
    let mut levels: Vec<ModelLevel> = Vec::new();
    for r in coarse {
        if !levels.contains(&r.discretization.level) {
            levels.push(r.discretization.level);
        }
    }
    for level in levels {
        let at = |f: &dyn Fn(&Resolution) -> f64| -> Vec<(f64, f64)> {
            coarse
                .iter()
                .filter(|r| r.discretization.level == level)
                .map(|r| (r.wall_s.log10(), 100.0 * f(r)))
                .collect()
        };
        for (face, points) in [
            ("F1", at(&|r| r.error_incident)),
            ("F2", at(&|r| r.error_transmitted)),
        ] {
            chart = chart.with(Series {
                label: format!("{face}, {}", level.name()),
                points,
            });
        }
    }
    chart.write_png(path)
}

pub fn run(scene_file: &Path, params: Option<&Path>, out: &Path, sensitivity: bool) -> Result<()> {
    let (scene, material) = load(scene_file, params)?;
    let model = scene.model(&material)?;
    let (e, s) = (&scene.experiment, &scene.settings);
    println!("SHPB record: {} ({})", e.name, e.data_file.display());
    println!(
        "specimen: d = {:.3} mm, L = {:.3} mm, {} K; {} points ({} along the length), {}",
        e.specimen.diameter_m * 1e3,
        e.specimen.length_m * 1e3,
        e.temperature_k,
        model.particles(),
        s.layers,
        s.level.name()
    );
    println!(
        "drive: {}; faces: μ = {}, contact frequency {} c/s; {:.1} µs of record",
        match s.drive {
            Drive::IncidentPulse =>
                "incident pulse on elastic bars (predicts reflected and transmitted pulses)",
            Drive::MeasuredVelocity =>
                "measured relative face velocity v1 - v2 on s_i, s_t fixed (thesis)",
        },
        s.friction,
        s.contact_factor,
        model.end_s() * 1e6
    );
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let mut snapshots = SnapshotWriter::new(out, model.end_s(), SNAPSHOTS);
    let run = model.run_observed(
        scene.material(&material),
        model.end_s(),
        &mut [&mut snapshots],
    )?;
    println!(
        "{} steps of {:.3e} s in {:.2} s ({:.2} M particle-steps/s)",
        run.steps,
        run.dt_s,
        run.wall_s,
        (run.steps * run.particles) as f64 / run.wall_s / 1e6
    );
    write_history(&out.join("history.csv"), &scene, &run)?;
    charts(out, &scene, &run)?;
    for (name, model_force, measured) in [
        (
            "F1 (incident face)",
            &run.history.force_incident_n,
            &scene.analysis.force_front_n,
        ),
        (
            "F2 (transmitter face)",
            &run.history.force_transmitted_n,
            &scene.analysis.force_back_n,
        ),
    ] {
        let rms = relative_rms(
            &scene.plateau_times(),
            (&run.history.time_s, model_force),
            (&scene.analysis.time_s, measured),
        );
        println!(
            "{name}: model vs measured over the plateau, RMS {:.2} % of the mean measured force",
            100.0 * rms
        );
    }
    println!(
        "history.csv, snapshots, forces.png and pulses.png in {}",
        out.display()
    );
    for m in &run.melting {
        eprintln!("warning: {m}");
    }
    if sensitivity {
        println!("contact parameters (F2 over the plateau, against the run above):");
        for v in contact_sensitivity(&scene, &material)? {
            println!(
                "  {:<44} mean {:+.2} %, RMS change {:.2} %",
                v.label,
                100.0 * v.mean_change,
                100.0 * v.rms_change
            );
        }
    }
    Ok(())
}

fn write_history(path: &Path, scene: &ShpbScene, run: &ShpbRun) -> Result<()> {
    let a = &scene.analysis;
    let h = &run.history;
    let mut text = String::from(
        "time_s,model_force_incident_n,model_force_transmitted_n,measured_force_front_n,measured_force_back_n,\
model_velocity_incident_m_per_s,model_velocity_transmitted_m_per_s,measured_relative_velocity_m_per_s,\
incident_strain,model_reflected_strain,measured_reflected_strain,model_transmitted_strain,measured_transmitted_strain,\
model_specimen_length_m\n",
    );
    for k in 0..h.time_s.len() {
        let t = h.time_s[k];
        let at = |v: &[f64]| interpolate(&a.time_s, v, t);
        writeln!(
            text,
            "{t:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            h.force_incident_n[k],
            h.force_transmitted_n[k],
            at(&a.force_front_n),
            at(&a.force_back_n),
            h.velocity_incident_m_per_s[k],
            h.velocity_transmitted_m_per_s[k],
            at(&a.relative_velocity_m_per_s),
            at(&a.incident),
            h.reflected[k],
            at(&a.reflected),
            h.transmitted[k],
            at(&a.transmitted),
            h.length_m[k],
        )?;
    }
    std::fs::write(path, text).with_context(|| format!("{}: cannot write", path.display()))
}

fn charts(out: &Path, scene: &ShpbScene, run: &ShpbRun) -> Result<()> {
    let (a, h) = (&scene.analysis, &run.history);
    let name = &scene.experiment.name;
    let us = 1e6;
    LineChart::new(
        format!(
            "{name}: face forces, MPM model ({}, {} along, {}) vs record",
            scene.settings.level.name(),
            scene.settings.layers,
            scene.settings.shape_function.name()
        ),
        "t [µs]",
        "force [kN]",
    )
    .with(Series::scaled(
        "measured F1 (incident face)",
        &a.time_s,
        &a.force_front_n,
        us,
        1e-3,
    ))
    .with(Series::scaled(
        "measured F2 (transmitter face)",
        &a.time_s,
        &a.force_back_n,
        us,
        1e-3,
    ))
    .with(Series::scaled(
        "model F1",
        &h.time_s,
        &h.force_incident_n,
        us,
        1e-3,
    ))
    .with(Series::scaled(
        "model F2",
        &h.time_s,
        &h.force_transmitted_n,
        us,
        1e-3,
    ))
    .write_png(&out.join("forces.png"))?;
    LineChart::new(
        format!("{name}: bar strains at the faces"),
        "t [µs]",
        "strain [µε], compression positive",
    )
    .with(Series::scaled(
        "incident (drives the model)",
        &a.time_s,
        &a.incident,
        us,
        1e6,
    ))
    .with(Series::scaled(
        "measured reflected",
        &a.time_s,
        &a.reflected,
        us,
        1e6,
    ))
    .with(Series::scaled(
        "measured transmitted",
        &a.time_s,
        &a.transmitted,
        us,
        1e6,
    ))
    .with(Series::scaled(
        "model reflected",
        &h.time_s,
        &h.reflected,
        us,
        1e6,
    ))
    .with(Series::scaled(
        "model transmitted",
        &h.time_s,
        &h.transmitted,
        us,
        1e6,
    ))
    .write_png(&out.join("pulses.png"))
}
