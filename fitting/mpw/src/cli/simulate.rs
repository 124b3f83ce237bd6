//! `mpw simulate SCENE.toml`: run an MPM scene with a progress bar; write the time history
//! (CSV), particle snapshots (VTK), the named results (`results.csv`, also printed) and an
//! energy chart (PNG) into the output directory.
//! A failed run is reported with its step, time, particle and cause; its output stays. A
//! run stopped with Ctrl-C (or SIGTERM) writes its last state, results and chart too.

use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (see data/scenes/).
    pub scene: PathBuf,
    /// Output directory (default: out/<scene name>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// SHPB scenes: the material parameters of a fit report (report.toml) or a material
    /// file instead of the scene's material.
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// SHPB scenes: run these point counts along the specimen instead of the scene's, at
    /// the scene's level (10,20,40,80) or at a named one (mpm-axisymmetric:20,
    /// mpm-3d-quarter:40, mpm-3d:20), and report each against the last (accuracy against
    /// cost).
    #[arg(long, value_delimiter = ',')]
    pub refine: Vec<String>,
    /// SHPB scenes: also run with the penalty stiffness and the friction each halved and
    /// doubled, and report how far the transmitter-face force moves.
    #[arg(long)]
    pub sensitivity: bool,
    /// Carry exact derivatives along these material parameters (e.g. A,B,N,C,M; at most
    /// 6). MPM scenes (instead of the scene's `output.derivatives`): the rigid bodies'
    /// contact-force sensitivities p ∂f/∂p and the control points' p ∂x/∂p to
    /// derivatives.csv, the points' charted in derivatives.png. SHPB scenes (either
    /// drive): the face forces' sensitivities, scaled by the standard errors of the
    /// --params report (else by the values). Needs linear, CPDI, cpGIMP or uGIMP shape
    /// functions; rigid bodies of prescribed motion, faces on elastic bars and springs
    /// are carried.
    #[arg(long, value_delimiter = ',')]
    pub derivatives: Vec<String>,
}

pub fn run(args: Args) -> Result<()> {
    let name = args
        .scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    let out = args.out.unwrap_or_else(|| Path::new("out").join(&name));
    if fitting::shpb_model::scene::is_shpb_scene(&args.scene) {
        let params = args.params.as_deref();
        let options = [
            !args.refine.is_empty(),
            !args.derivatives.is_empty(),
            args.sensitivity,
        ];
        if options.iter().filter(|o| **o).count() > 1 {
            anyhow::bail!("--refine, --derivatives and --sensitivity are separate runs of an SHPB scene: give one");
        }
        return if !args.refine.is_empty() {
            super::simulate_shpb::refine(&args.scene, params, &args.refine, &out)
        } else if !args.derivatives.is_empty() {
            super::simulate_shpb_derivatives::run(&args.scene, params, &args.derivatives, &out)
        } else {
            super::simulate_shpb::run(&args.scene, params, &out, args.sensitivity)
        };
    }
    if args.params.is_some() || !args.refine.is_empty() || args.sensitivity {
        anyhow::bail!("--params, --refine and --sensitivity are for SHPB scenes (kind = \"shpb\"); {} is an MPM scene with its materials inside", args.scene.display());
    }
    let mut scene = mpm_core::scene::load(&args.scene)?;
    if !args.derivatives.is_empty() {
        scene.output.derivatives = args.derivatives;
    }
    run_loaded(scene, &out, &name)
}

/// Run a loaded scene into `out` with a progress bar (Ctrl-C stops it with its output
/// written): the run log, results, energy chart and warnings; a failure is returned as the
/// error after everything is written, with the likely cause when the time step was risky.
pub fn run_loaded(scene: mpm_core::scene::Scene, out: &Path, name: &str) -> Result<()> {
    let derivatives = scene.output.derivatives.clone();
    let last_axis = match scene.simulation {
        mpm_core::scene::Simulation::Planar(_) => "y",
        mpm_core::scene::Simulation::Solid(_) => "z",
    };
    let summary = run_with_progress(scene, out)?;
    println!("{} particles, {}", summary.particles, summary.time_step);
    for change in &summary.time_step_changes {
        println!("time step: {change}");
    }
    println!(
        "{} steps; history, snapshots, results.csv and chart in {}",
        summary.steps,
        out.display()
    );
    for r in &summary.results {
        println!("  {:<28} {:>14.6e} {}", r.name, r.value, r.unit);
    }
    energy_chart(&out.join("history.csv"), &out.join("energy.png"), name)?;
    if !derivatives.is_empty() {
        let columns = (last_axis, derivatives.as_slice());
        derivative_chart(
            &out.join("derivatives.csv"),
            columns,
            &out.join("derivatives.png"),
            name,
        )?;
        println!("exact derivatives: derivatives.csv and derivatives.png");
    }
    for m in &summary.melting {
        eprintln!("warning: {m}");
    }
    if let Some(e) = summary.failure {
        match summary.time_step.risk() {
            Some(risk) => anyhow::bail!("{e}\n  likely cause: {risk}"),
            None => anyhow::bail!("{e}"),
        }
    }
    Ok(())
}

/// Run a loaded scene into `out` with a progress bar; Ctrl-C (or SIGTERM) stops it at the
/// next step with its output written. The summary holds a failure, if any.
pub fn run_with_progress(
    scene: mpm_core::scene::Scene,
    out: &Path,
) -> Result<mpm_core::run::RunSummary> {
    for line in scene.describe() {
        println!("{line}");
    }
    let bar = ProgressBar::new(1000);
    bar.set_style(ProgressStyle::with_template(
        "{bar:40} {percent:>3}% t = {msg} [{elapsed} < {eta}]",
    )?);
    let warn = |ts: &mpm_core::TimeStep| {
        if let Some(risk) = ts.risk() {
            bar.suspend(|| eprintln!("warning: {risk}"));
        }
    };
    let stop = crate::cli::interrupt::interrupt_flag()?;
    let summary = mpm_core::run::run_scene(scene, out, warn, |t, end| {
        bar.set_position((1000.0 * t / end) as u64);
        bar.set_message(format!("{t:.3e} s"));
        match stop.load(Ordering::Relaxed) {
            true => ControlFlow::Break(()),
            false => ControlFlow::Continue(()),
        }
    })
    .with_context(|| format!("writing output to {}", out.display()))?;
    bar.finish();
    Ok(summary)
}

/// Chart the sensitivities p ∂x/∂p of every control point along its last axis `axis`
/// (the axial or vertical one) to each of `parameters` from a derivatives file (columns
/// `{point}_{axis}_{parameter}_m`), one series per point and parameter.
pub fn derivative_chart(
    derivatives: &Path,
    (axis, parameters): (&str, &[String]),
    png: &Path,
    title: &str,
) -> Result<()> {
    let mut reader = csv::Reader::from_path(derivatives)?;
    let header: Vec<String> = reader.headers()?.iter().map(String::from).collect();
    let rows: Vec<Vec<f64>> = reader
        .records()
        .map(|r| Ok(r?.iter().map(|v| v.parse().unwrap_or(f64::NAN)).collect()))
        .collect::<Result<_>>()?;
    let mut chart = LineChart::new(
        format!("{title}: sensitivity of the control points (exact derivatives)"),
        "t [µs]",
        format!("p ∂{axis}/∂p [mm]"),
    );
    for (c, name) in header.iter().enumerate().skip(1) {
        let point = parameters.iter().find_map(|p| {
            let point = name.strip_suffix(&format!("_{axis}_{p}_m"))?;
            Some(format!("{point} {p}"))
        });
        if let Some(label) = point {
            chart = chart.with(Series {
                label,
                points: rows.iter().map(|r| (r[0] * 1e6, r[c] * 1e3)).collect(),
            });
        }
    }
    chart.write_png(png)
}

/// Chart kinetic, internal and total energy from a history file.
pub fn energy_chart(history: &Path, png: &Path, title: &str) -> Result<()> {
    let mut reader = csv::Reader::from_path(history)?;
    let header = reader.headers()?.clone();
    // columns are `<quantity>_<unit>`; energies in j, or j_per_m in plane strain
    let plane = header.iter().any(|h| h == "kinetic_j_per_m");
    let unit = if plane { "J/m" } else { "J" };
    let suffix = if plane { "_j_per_m" } else { "_j" };
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h == name || h.strip_suffix(suffix) == Some(name))
            .context(format!("history has no column {name}"))
    };
    let (t, k, w, x, b) = (
        col("time_s")?,
        col("kinetic")?,
        col("internal")?,
        col("external_work")?,
        col("boundary_work")?,
    );
    let mut rows: Vec<[f64; 5]> = Vec::new();
    for r in reader.records() {
        let r = r?;
        let v = |i: usize| r[i].parse::<f64>().unwrap_or(f64::NAN);
        rows.push([v(t), v(k), v(w), v(x), v(b)]);
    }
    let series = |label: &str, f: &dyn Fn(&[f64; 5]) -> f64| Series {
        label: label.into(),
        points: rows.iter().map(|r| (r[0], f(r))).collect(),
    };
    LineChart::new(
        format!("{title}: energies"),
        "t [s]",
        format!("energy [{unit}]"),
    )
    .with(series("kinetic", &|r| r[1]))
    .with(series("internal (stress work)", &|r| r[2]))
    .with(series("K + W_int - W_ext - W_bc", &|r| {
        r[1] + r[2] - r[3] - r[4]
    }))
    .write_png(png)
}
