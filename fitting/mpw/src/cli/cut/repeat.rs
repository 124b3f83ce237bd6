//! `mpw cut repeat`: a cut once per grid-shift seed, each a `scene` task of an executor
//! (`--executor pool` runs them side by side); the mean, spread and CV(t) of the force
//! over the seeds: the vertical cut's punch force f_y against relative feed, or
//! (`--cut orthogonal`) the orthogonal cut's cutting force f_x against time. Each seed's
//! scene is in `seed_<s>/scene.toml`, its run in the batch folder (`tasks/task-<i>/run`, or
//! under Slurm's `work_dir`).

use super::pictures::{force_range, mean, with_peak};
use super::{absolute, orthogonal_scene_text, same_scene, vertical_scene_text};
use crate::charts::{LineChart, Series};
use crate::cli::executor_args::ExecutorArgs;
use crate::cut_forces::FORCE_FILTER;
use anyhow::{Context, Result};
use cutting::orthogonal::{OrthogonalCut, Resolution};
use cutting::orthogonal_result::STEADY_FROM;
use cutting::record::ToolForce;
use cutting::vertical::{discretization, VerticalCut};
use cutting::workpiece::RunOptions;
use fitting::experiment::processing::SavitzkyGolay;
use runs::task::TaskDir;
use runs::{Batch, RunDescription};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct RepeatArgs {
    /// Which cut: vertical (a set of table 12.2) or orthogonal (`--spacing`, `--points`).
    #[arg(long, default_value = "vertical")]
    pub cut: String,
    /// Vertical: the set of table 12.2.
    #[arg(long, default_value = "G0")]
    pub set: String,
    /// Orthogonal: grid spacing [m].
    #[arg(long, default_value_t = 2e-4)]
    pub spacing: f64,
    /// Orthogonal: points over the workpiece's height.
    #[arg(long, default_value_t = 80)]
    pub points: usize,
    /// Orthogonal: run time [s].
    #[arg(long, default_value_t = 80e-6)]
    pub end: f64,
    /// Grid-shift seeds, one run each (at least two).
    #[arg(long, value_delimiter = ',', default_value = "1,2,3,4,5")]
    pub seeds: Vec<u64>,
    /// Vertical: the relative feed to run to.
    #[arg(long, default_value_t = 1.2)]
    pub feed: f64,
    /// Material file (default: the cut's, Al 7075-T6 or 42CrMo4).
    #[arg(long)]
    pub material: Option<PathBuf>,
    /// Output folder (default: out/cut_repeat, or out/cut_repeat_orthogonal).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Chart the runs already in the output folder (each seed's scene must be this one).
    #[arg(long)]
    pub analyse_only: bool,
    #[command(flatten)]
    pub executor: ExecutorArgs,
}

/// What is repeated: the scene of a seed, the tool and force component read, and the
/// abscissa and labels of the charts.
struct Repeated {
    name: String,
    tool: &'static str,
    /// Read f_y (vertical) or f_x (orthogonal).
    vertical_force: bool,
    /// The filter the cut's forces are read through (orthogonal: the thesis's
    /// Savitzky-Golay filter); the spread is of the filtered force, the raw force's CV is
    /// printed beside it.
    filter: Option<SavitzkyGolay>,
    /// Abscissa of a history time [s], and its chart label.
    abscissa: Box<dyn Fn(f64) -> f64>,
    abscissa_label: &'static str,
    /// A CSV column before `time_s` (name, factor from the abscissa), if the abscissa is
    /// not the time.
    abscissa_column: Option<(&'static str, f64)>,
    force_label: &'static str,
    /// CV is summarized from this abscissa on (settled cut).
    settled_from: f64,
    scene: Box<dyn Fn(&RunOptions) -> Result<String>>,
}

fn repeated(args: &RepeatArgs) -> Result<(Repeated, PathBuf, PathBuf)> {
    let (material, out) = match args.cut.as_str() {
        "vertical" => ("data/materials/al7075_t6.toml", "out/cut_repeat"),
        "orthogonal" => (
            "data/materials/42crmo4_qt660.toml",
            "out/cut_repeat_orthogonal",
        ),
        other => anyhow::bail!("--cut \"{other}\": expected \"vertical\" or \"orthogonal\""),
    };
    let material = args.material.clone().unwrap_or_else(|| material.into());
    let out = args.out.clone().unwrap_or_else(|| out.into());
    let what = match args.cut.as_str() {
        "vertical" => {
            let set = discretization(&args.set)
                .with_context(|| format!("--set {}: not a set of table 12.2", args.set))?;
            let cut = VerticalCut::default();
            let feed = args.feed;
            Repeated {
                name: format!("vertical cut {}", set.name),
                tool: "punch",
                vertical_force: true,
                filter: None,
                abscissa: Box::new(|t| 100.0 * VerticalCut::default().feed_at(t)),
                abscissa_label: "relative feed [%]",
                abscissa_column: Some(("relative_feed", 0.01)),
                force_label: "punch force f_y [MN/m]",
                settled_from: 40.0,
                scene: Box::new(move |options| vertical_scene_text(&cut, &set, feed, options)),
            }
        }
        _ => {
            let cut = OrthogonalCut {
                end: args.end,
                ..OrthogonalCut::default()
            };
            let resolution = Resolution {
                spacing: args.spacing,
                points_y: args.points,
            };
            Repeated {
                name: format!("orthogonal cut dx {} m, n_y {}", args.spacing, args.points),
                tool: "tool",
                vertical_force: false,
                filter: Some(FORCE_FILTER),
                abscissa: Box::new(|t| t * 1e6),
                abscissa_label: "time [µs]",
                abscissa_column: None,
                force_label: "cutting force f_x [MN/m]",
                settled_from: STEADY_FROM * 1e6,
                scene: Box::new(move |options| orthogonal_scene_text(&cut, &resolution, options)),
            }
        }
    };
    Ok((what, PathBuf::from(material), out))
}

pub fn repeat(args: RepeatArgs) -> Result<()> {
    if args.seeds.len() < 2 {
        anyhow::bail!("--seeds: at least two seeds, to have a spread");
    }
    let (what, material, out) = repeated(&args)?;
    let material = absolute(&material)?;
    let mut descriptions = Vec::new();
    for &seed in &args.seeds {
        let options = RunOptions {
            seed,
            snapshots: 2,
            ..RunOptions::new(&material)
        };
        let folder = out.join(format!("seed_{seed}"));
        let text = (what.scene)(&options)?;
        match args.analyse_only {
            true => same_scene(&folder, &text)?,
            false => {
                std::fs::create_dir_all(&folder)?;
                std::fs::write(folder.join("scene.toml"), &text)?;
            }
        }
        let scene = folder.join("scene.toml").canonicalize()?;
        descriptions.push(RunDescription::new("scene", &scene));
    }
    let stop = crate::cli::interrupt::interrupt_flag()?;
    let execute = |d: &RunDescription, dir: &Path| crate::tasks::execute(d, dir, Some(&stop));
    let (executor, dir) = args
        .executor
        .build("mpw-cut-repeat", &execute, out.join("tasks"))?;
    if !args.analyse_only {
        let batch = Batch::create(&dir, &descriptions)?;
        println!(
            "{} runs ({}) in {}",
            args.seeds.len(),
            executor.describe(),
            batch.dir.display()
        );
        let reports = executor.run(&batch, &stop, &|_| {})?;
        for (report, seed) in reports.into_iter().zip(&args.seeds) {
            let (outcome, manifest) = report
                .result
                .map_err(|f| anyhow::anyhow!("seed {seed}: {f}"))?;
            let time = outcome.value("run.time").unwrap_or(f64::NAN);
            let end = match &outcome.failure {
                None => "ran through".to_string(),
                Some(e) => format!(
                    "stopped at {:.1} ({}): {e}",
                    (what.abscissa)(time),
                    what.abscissa_label
                ),
            };
            println!(
                "{} seed {seed}: {:.1} s, {end}",
                what.name, manifest.wall_seconds
            );
        }
    }
    let mut forces: Vec<Vec<f64>> = Vec::new();
    let mut time = Vec::new();
    for i in 0..args.seeds.len() {
        let history = TaskDir(dir.join(format!("task-{i}")))
            .run()
            .join("history.csv");
        let force = ToolForce::read(&history, what.tool)?;
        if force.time_s.len() > time.len() {
            time = force.time_s.clone();
        }
        forces.push(match what.vertical_force {
            true => force.force_y,
            false => force.force_x,
        });
    }
    if let Some(filter) = &what.filter {
        let raw = cutting::repeatability::spread(&forces).context("no spread")?;
        let x: Vec<f64> = time.iter().map(|&t| (what.abscissa)(t)).collect();
        print_settled_cv(&what, "raw force", &raw.cv, &x);
        forces = forces.iter().map(|f| filter.apply(f)).collect();
    }
    chart_spread(&what, &forces, &time, &out, args.seeds.len())
}

/// The CV(t) of the settled cut (from `what.settled_from` on): its mean and how often it
/// exceeds 0.3, on standard output.
fn print_settled_cv(what: &Repeated, label: &str, cv: &[f64], x: &[f64]) {
    let settled: Vec<f64> = (0..cv.len())
        .filter(|&k| x[k] >= what.settled_from)
        .map(|k| cv[k])
        .filter(|c| c.is_finite())
        .collect();
    if let Some(m) = mean(&settled) {
        let above = settled.iter().filter(|&&c| c > 0.3).count();
        println!(
            "CV of the {label} from {} on ({}): mean {m:.3}, above 0.3 in {above} of {} samples",
            what.settled_from,
            what.abscissa_label,
            settled.len()
        );
    }
}

/// The mean, spread and CV(t) of `forces` over the seeds: `repeat.csv`, `repeat.png`,
/// `cv.png`, and the CV of the settled cut on standard output.
fn chart_spread(
    what: &Repeated,
    forces: &[Vec<f64>],
    time: &[f64],
    out: &Path,
    seeds: usize,
) -> Result<()> {
    let s = cutting::repeatability::spread(forces).context("no spread")?;
    let n = s.mean.len();
    let x: Vec<f64> = time[..n].iter().map(|&t| (what.abscissa)(t)).collect();
    let component = match (what.vertical_force, what.filter.is_some()) {
        (true, _) => "force_y",
        (false, false) => "force_x",
        (false, true) => "force_x_filtered",
    };
    let (first, factor) = match what.abscissa_column {
        Some((name, factor)) => (format!("{name},"), Some(factor)),
        None => (String::new(), None),
    };
    let mut csv = format!("{first}time_s,mean_{component}_n_per_m,std_{component}_n_per_m,cv\n");
    for k in 0..n {
        if let Some(factor) = factor {
            csv += &format!("{:e},", x[k] * factor);
        }
        csv += &format!(
            "{:e},{:e},{:e},{:e}\n",
            time[k], s.mean[k], s.std[k], s.cv[k]
        );
    }
    std::fs::write(out.join("repeat.csv"), csv)?;
    let band = |sign: f64| -> Vec<f64> { (0..n).map(|k| s.mean[k] + sign * s.std[k]).collect() };
    let ((lo, hi), off) = force_range(&[&band(1.0), &band(-1.0)]);
    LineChart::new(
        with_peak(
            format!(
                "{}: {} over {seeds} seeds",
                what.name,
                component.replace('_', " ")
            ),
            off,
        ),
        what.abscissa_label,
        what.force_label,
    )
    .y_range(lo * 1e-6, hi * 1e-6)
    .with(Series::scaled("mean", &x, &s.mean, 1.0, 1e-6))
    .with(Series::scaled("mean + std", &x, &band(1.0), 1.0, 1e-6))
    .with(Series::scaled("mean − std", &x, &band(-1.0), 1.0, 1e-6))
    .write_png(&out.join("repeat.png"))?;
    LineChart::new(
        format!(
            "{}: CV(t) of the {} over {seeds} seeds",
            what.name,
            component.replace('_', " ")
        ),
        what.abscissa_label,
        "coefficient of variation [-]",
    )
    .y_range(0.0, 1.0)
    .with(Series::scaled("CV", &x, &s.cv, 1.0, 1.0))
    .write_png(&out.join("cv.png"))?;
    let label = match what.filter {
        Some(_) => "filtered force",
        None => "force",
    };
    print_settled_cv(what, label, &s.cv, &x);
    println!(
        "repeat.csv, repeat.png, cv.png and each seed's scene in {}",
        out.display()
    );
    Ok(())
}
