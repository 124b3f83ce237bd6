//! `mpw cut vertical --set G0`: the vertical cut of thesis §12.2 at one discretization of
//! table 12.2 (`cutting::vertical`). Writes the run's scene (`scene.toml`, runnable with
//! `mpw simulate`), the history, snapshots and results as `simulate` does, the punch force
//! per unit thickness against relative feed (`force.csv`, `force.png`), and prints the
//! relative feed reached: "ran through" to the end feed, or where and why the run stopped.
//! `mpw cut scenes` writes every set's scene into `data/scenes/cutting/` (the shipped ones).

use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use cutting::record::ToolForce;
use cutting::vertical::{discretization, CutOptions, VerticalCut, SETS};
use std::path::{Path, PathBuf};

#[derive(clap::Subcommand, Debug)]
pub enum Cut {
    /// Run the vertical cut (Al 7075-T6) at one set of table 12.2.
    Vertical(VerticalArgs),
    /// Write the scene of every set of table 12.2 into a folder.
    Scenes {
        #[arg(long, default_value = "data/scenes/cutting")]
        out: PathBuf,
    },
}

#[derive(clap::Args, Debug)]
pub struct VerticalArgs {
    /// Set of table 12.2: S0, S1, S2 (no grid shift, grid conditions), G0, G1, G2, G0_100,
    /// G0_200, G1_60, G1_200 (grid shift dx/2, springs).
    #[arg(long, default_value = "G0")]
    pub set: String,
    /// Relative feed at which the run ends (1 = 100 %, the sheet's thickness).
    #[arg(long, default_value_t = 1.2)]
    pub feed: f64,
    /// Shape functions: linear, ugimp, cpgimp, cpdi.
    #[arg(long, default_value = "linear")]
    pub shape_function: String,
    /// A fixed time step [s] (the thesis: 5e-10); default the solver's stability limit.
    #[arg(long)]
    pub dt: Option<f64>,
    /// Seed of the grid shift.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Material file.
    #[arg(long, default_value = "data/materials/al7075_t6.toml")]
    pub material: PathBuf,
    /// Output folder (default out/cut_vertical_<set>).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

pub fn run(cut: Cut) -> Result<()> {
    match cut {
        Cut::Vertical(args) => vertical(args),
        Cut::Scenes { out } => scenes(&out),
    }
}

fn scenes(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let cut = VerticalCut::default();
    for set in &SETS {
        let path = out.join(format!("vertical_{}.toml", set.name));
        std::fs::write(&path, scene_text(&cut, set, &CutOptions::default())?)
            .with_context(|| format!("{}: cannot write", path.display()))?;
        println!("{}", path.display());
    }
    Ok(())
}

/// The scene file of `set`: a comment naming it, then the TOML.
pub fn scene_text(
    cut: &VerticalCut,
    set: &cutting::vertical::Discretization,
    options: &CutOptions,
) -> Result<String> {
    let shift = match set.shift {
        true => "grid shift dx/2 and spring conditions (eq. 12.1)",
        false => "no grid shift, grid conditions",
    };
    Ok(format!(
        "# Vertical cut, thesis section 12.2, set {} of table 12.2: dx = {} m, {} x {} points, {shift}.\n\
         # Written by `mpw cut scenes` (cutting::vertical, where every value the thesis gives\n\
         # only in a figure is chosen and explained); `mpw cut vertical --set {}` runs it with the\n\
         # punch force against relative feed.\n{}",
        set.name,
        set.spacing,
        3 * set.points_y,
        set.points_y,
        set.name,
        toml::to_string(&cut.scene(set, options))?
    ))
}

fn vertical(args: VerticalArgs) -> Result<()> {
    let set = discretization(&args.set).with_context(|| {
        let names: Vec<&str> = SETS.iter().map(|s| s.name).collect();
        format!("--set {}: expected one of {}", args.set, names.join(", "))
    })?;
    if !(args.feed > 0.0 && args.feed <= 3.0) {
        anyhow::bail!("--feed {}: expected a relative feed in (0, 3]", args.feed);
    }
    let material = args
        .material
        .canonicalize()
        .with_context(|| format!("{}: cannot find the material file", args.material.display()))?;
    let out = args
        .out
        .unwrap_or_else(|| Path::new("out").join(format!("cut_vertical_{}", set.name)));
    std::fs::create_dir_all(&out).with_context(|| format!("{}: cannot create", out.display()))?;
    let cut = VerticalCut::default();
    let options = CutOptions {
        end_feed: args.feed,
        shape_function: args.shape_function.clone(),
        dt: args.dt,
        seed: args.seed,
        material_file: material.display().to_string(),
        ..CutOptions::default()
    };
    let scene_file = out.join("scene.toml");
    std::fs::write(&scene_file, scene_text(&cut, &set, &options)?)?;
    let scene = mpm_core::scene::load(&scene_file)?;
    let start = std::time::Instant::now();
    let summary = super::simulate::run_with_progress(scene, &out)?;
    let wall = start.elapsed().as_secs_f64();
    let force = ToolForce::read(&out.join("history.csv"), "punch")?;
    force.write_csv(&out.join("force.csv"), |t| cut.feed_at(t))?;
    force_chart(&force, &cut, set.name, &out.join("force.png"))?;
    for m in &summary.melting {
        eprintln!("warning: {m}");
    }
    println!(
        "{} ({} points, dx = {} m, {}): {} steps of {:.3e} s in {:.1} s, {:.2} M particle-steps/s",
        set.name,
        summary.particles,
        set.spacing,
        args.shape_function,
        summary.steps,
        summary.time_step.dt,
        wall,
        (summary.steps * summary.particles) as f64 / wall / 1e6
    );
    let peak = force.force_y.iter().copied().fold(0.0, f64::max);
    println!("peak punch force f_y = {:.4} MN/m", peak * 1e-6);
    match &summary.failure {
        None => println!(
            "ran through to {:.0} % relative feed; force.csv, force.png, history and snapshots in {}",
            100.0 * args.feed,
            out.display()
        ),
        Some(e) => {
            println!(
                "stopped at {:.1} % relative feed: {e}",
                100.0 * cut.feed_at(e.time)
            );
            println!("force.csv, force.png, history and snapshots up to there in {}", out.display());
        }
    }
    Ok(())
}

fn force_chart(force: &ToolForce, cut: &VerticalCut, set: &str, png: &Path) -> Result<()> {
    let feed: Vec<f64> = force
        .time_s
        .iter()
        .map(|&t| 100.0 * cut.feed_at(t))
        .collect();
    LineChart::new(
        format!("vertical cut {set}: punch force"),
        "relative feed [%]",
        "punch force f_y per unit thickness [MN/m]",
    )
    .with(Series::scaled("f_y", &feed, &force.force_y, 1.0, 1e-6))
    .write_png(png)
}
