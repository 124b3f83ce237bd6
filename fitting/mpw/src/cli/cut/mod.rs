//! `mpw cut`: metal cutting (thesis chapter 12, library `cutting`).
//!
//! - `mpw cut vertical --set G0`: the vertical cut at a set of table 12.2: the punch force
//!   per unit thickness against relative feed (`force.csv`, `force.png`), a picture of the
//!   sheet at the end coloured by plastic strain (`sheet.png`) and the relative
//!   feed reached: "ran through" to the end feed, or where and why the run stopped.
//! - `mpw cut orthogonal`: the orthogonal cut: tool forces f_x, f_y raw and
//!   Savitzky-Golay filtered (31 history samples, first order; `force.csv`, `force.png`),
//!   the shear angle in each snapshot from 20 µs on (from the chip's flow, and the
//!   strain-rate band with its contrast), the steady cutting force against Merchant's
//!   estimate from the mean angle, and a picture of the chip (`chip.png`); with
//!   `--derivatives A,B,N,C,M` also the forces' sensitivities to those parameters from
//!   exact derivatives (`force_sensitivity.csv`, `force_sensitivity.png`).
//! - `mpw cut map [--cut orthogonal]`: the stability map: one run per grid spacing ×
//!   points over the height, for each variant (shape function, grid shift), the feed (or
//!   time) reached and the wall time in each cell, for the orthogonal cut with its steady
//!   cutting force (`map.csv`, `map_<variant>.png`).
//! - `mpw cut repeat --set G0 --seeds 1,2,3,4,5`: the vertical cut once per grid-shift
//!   seed; the punch force's mean ± sample standard deviation and CV(t) per history sample
//!   (`repeat.csv`, `repeat.png`).
//! - `mpw cut scenes`: the scene of every vertical set and every cell of the orthogonal
//!   sensitivity matrix into `data/scenes/cutting/` (the shipped ones).
//!
//! Each run's folder holds its scene (`scene.toml`, runnable with `mpw simulate`), history,
//! snapshots and results as `simulate` writes them, and its record (`run.toml`: points,
//! steps, time step, wall time, how far it got).

mod map;
mod orthogonal;
mod pictures;
mod repeat;
mod sensitivity;
mod vertical;

pub use map::MapArgs;
pub use orthogonal::OrthogonalArgs;
pub use repeat::RepeatArgs;
pub use vertical::VerticalArgs;

use anyhow::{Context, Result};
use cutting::orthogonal::{OrthogonalCut, Resolution};
use cutting::record::RunRecord;
use cutting::vertical::{Discretization, VerticalCut, SETS};
use cutting::workpiece::RunOptions;
use mpm_core::run::RunSummary;
use std::path::{Path, PathBuf};

#[derive(clap::Subcommand, Debug)]
pub enum Cut {
    /// Run the vertical cut (Al 7075-T6) at one set of table 12.2.
    Vertical(VerticalArgs),
    /// Run the orthogonal cut (42CrMo4): forces, shear angle, Merchant's estimate, chip.
    Orthogonal(OrthogonalArgs),
    /// Stability maps: feed (vertical) or time (orthogonal) reached over spacing × points.
    Map(MapArgs),
    /// The vertical cut once per grid-shift seed: mean, spread and CV(t) of the punch force.
    Repeat(RepeatArgs),
    /// Write the scene of every set of table 12.2 and of every cell of the orthogonal
    /// cut's sensitivity matrix into a folder.
    Scenes {
        #[arg(long, default_value = "data/scenes/cutting")]
        out: PathBuf,
    },
}

/// The relative feed a shipped vertical scene runs to.
const END_FEED: f64 = 1.2;

/// What every cut takes.
#[derive(clap::Args, Debug, Clone)]
pub struct Common {
    /// Shape functions: linear, ugimp, cpgimp, cpdi.
    #[arg(long, default_value = "linear")]
    pub shape_function: String,
    /// A fixed time step [s]; default the solver's stability limit (CFL, and the
    /// penalty and spring stiffness on the lightest point).
    #[arg(long)]
    pub dt: Option<f64>,
    /// Seed of the grid shift.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl Common {
    /// The run options with `material` (made absolute: the scene is written elsewhere).
    fn options(&self, material: &Path) -> Result<RunOptions> {
        Ok(RunOptions {
            shape_function: self.shape_function.clone(),
            dt: self.dt,
            seed: self.seed,
            ..RunOptions::new(absolute(material)?)
        })
    }
}

pub fn run(cut: Cut) -> Result<()> {
    match cut {
        Cut::Vertical(args) => vertical::vertical(args),
        Cut::Repeat(args) => repeat::repeat(args),
        Cut::Orthogonal(args) => orthogonal::orthogonal(args),
        Cut::Map(args) => map::map(args),
        Cut::Scenes { out } => scenes(&out),
    }
}

fn scenes(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;
    let cut = VerticalCut::default();
    for set in &SETS {
        let path = out.join(format!("vertical_{}.toml", set.name));
        std::fs::write(
            &path,
            vertical_scene_text(
                &cut,
                set,
                END_FEED,
                &RunOptions::new(cutting::vertical::MATERIAL),
            )?,
        )
        .with_context(|| format!("{}: cannot write", path.display()))?;
        println!("{}", path.display());
    }
    let cut = OrthogonalCut::default();
    for resolution in cutting::orthogonal::sensitivity_matrix() {
        let path = out.join(format!(
            "orthogonal_dx{}_ny{}.toml",
            resolution.spacing, resolution.points_y
        ));
        let options = RunOptions::new(cutting::orthogonal::MATERIAL);
        std::fs::write(&path, orthogonal_scene_text(&cut, &resolution, &options)?)
            .with_context(|| format!("{}: cannot write", path.display()))?;
        println!("{}", path.display());
    }
    Ok(())
}

/// The scene file of `set`: a comment naming it, then the TOML.
fn vertical_scene_text(
    cut: &VerticalCut,
    set: &Discretization,
    end_feed: f64,
    options: &RunOptions,
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
        toml::to_string(&cut.scene(set, end_feed, options))?
    ))
}

/// The scene file of the orthogonal cut at `resolution`: a comment naming it, then the
/// TOML.
fn orthogonal_scene_text(
    cut: &OrthogonalCut,
    resolution: &Resolution,
    options: &RunOptions,
) -> Result<String> {
    Ok(format!(
        "# Orthogonal cut, thesis section 12.3: dx = {} m, {} x {} points, depth of cut {} m.\n\
         # Written by `mpw cut orthogonal` (cutting::orthogonal explains every chosen value).\n{}",
        resolution.spacing,
        3 * resolution.points_y,
        resolution.points_y,
        cut.feed,
        toml::to_string(&cut.scene(resolution, options))?
    ))
}

/// An existing material file as an absolute path, for a scene written elsewhere.
fn absolute(material: &Path) -> Result<String> {
    let path = material
        .canonicalize()
        .with_context(|| format!("{}: cannot find the material file", material.display()))?;
    Ok(path.display().to_string())
}

/// The run in `out` is of the scene `text` (for `--analyse-only`).
fn same_scene(out: &Path, text: &str) -> Result<()> {
    let written = std::fs::read_to_string(out.join("scene.toml"))
        .with_context(|| format!("{}: no run to analyse", out.display()))?;
    if written != text {
        anyhow::bail!(
            "{}: holds a run of another scene; give the options it was run with",
            out.join("scene.toml").display()
        );
    }
    Ok(())
}

/// A finished cutting run: its summary and wall time [s].
struct CutRun {
    summary: RunSummary,
    wall_s: f64,
}

impl CutRun {
    /// Write `scene_text` into `out/scene.toml` and run it there with a progress bar.
    fn start(scene_text: &str, out: &Path) -> Result<CutRun> {
        std::fs::create_dir_all(out)
            .with_context(|| format!("{}: cannot create", out.display()))?;
        let scene_file = out.join("scene.toml");
        std::fs::write(&scene_file, scene_text)?;
        let scene = mpm_core::scene::load(&scene_file)?;
        let end_s = scene.end;
        let start = std::time::Instant::now();
        let summary = super::simulate::run_with_progress(scene, out)?;
        for m in &summary.melting {
            eprintln!("warning: {m}");
        }
        let run = CutRun {
            summary,
            wall_s: start.elapsed().as_secs_f64(),
        };
        run.record(end_s).write(out)?;
        Ok(run)
    }

    /// The run's record (`run.toml`), `end_s` being the scene's end.
    fn record(&self, end_s: f64) -> RunRecord {
        let s = &self.summary;
        RunRecord {
            points: s.particles,
            steps: s.steps,
            dt_s: s.time_step.dt,
            wall_s: self.wall_s,
            threads: rayon::current_num_threads(),
            time_reached_s: s.failure.as_ref().map_or(end_s, |f| f.time),
            end_s,
            failure: s.failure.as_ref().map(|f| f.to_string()),
        }
    }

    /// Particle-steps per second.
    fn throughput(&self) -> f64 {
        (self.summary.steps * self.summary.particles) as f64 / self.wall_s
    }

    fn report(&self, name: &str) {
        println!(
            "{name}: {} points, {} steps of {:.3e} s in {:.1} s, {:.2} M particle-steps/s",
            self.summary.particles,
            self.summary.steps,
            self.summary.time_step.dt,
            self.wall_s,
            self.throughput() / 1e6
        );
    }
}
