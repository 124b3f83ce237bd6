//! `mpw cut repeat`: the vertical cut once per grid-shift seed, each a `scene` task of an
//! executor (`--executor pool` runs them side by side); the punch force's mean, spread and
//! CV(t) over the seeds. Each seed's scene is in `seed_<s>/scene.toml`, its run in the
//! batch folder (`tasks/task-<i>/run`, or under Slurm's `work_dir`).

use super::pictures::{force_range, mean, with_peak};
use super::{absolute, same_scene, vertical_scene_text};
use crate::charts::{LineChart, Series};
use crate::cli::executor_args::ExecutorArgs;
use anyhow::{Context, Result};
use cutting::record::ToolForce;
use cutting::vertical::{discretization, VerticalCut};
use cutting::workpiece::RunOptions;
use runs::task::TaskDir;
use runs::{Batch, RunDescription};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct RepeatArgs {
    #[arg(long, default_value = "G0")]
    pub set: String,
    /// Grid-shift seeds, one run each (at least two).
    #[arg(long, value_delimiter = ',', default_value = "1,2,3,4,5")]
    pub seeds: Vec<u64>,
    #[arg(long, default_value_t = 1.2)]
    pub feed: f64,
    #[arg(long, default_value = "data/materials/al7075_t6.toml")]
    pub material: PathBuf,
    #[arg(long, default_value = "out/cut_repeat")]
    pub out: PathBuf,
    /// Chart the runs already in the output folder (each seed's scene must be this one).
    #[arg(long)]
    pub analyse_only: bool,
    #[command(flatten)]
    pub executor: ExecutorArgs,
}

pub fn repeat(args: RepeatArgs) -> Result<()> {
    let set = discretization(&args.set)
        .with_context(|| format!("--set {}: not a set of table 12.2", args.set))?;
    if args.seeds.len() < 2 {
        anyhow::bail!("--seeds: at least two seeds, to have a spread");
    }
    let cut = VerticalCut::default();
    let material = absolute(&args.material)?;
    let mut descriptions = Vec::new();
    for &seed in &args.seeds {
        let options = RunOptions {
            seed,
            snapshots: 2,
            ..RunOptions::new(&material)
        };
        let folder = args.out.join(format!("seed_{seed}"));
        let text = vertical_scene_text(&cut, &set, args.feed, &options)?;
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
    let (executor, dir) =
        args.executor
            .build("mpw-cut-repeat", &execute, args.out.join("tasks"))?;
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
                    "stopped at {:.1} % relative feed: {e}",
                    100.0 * cut.feed_at(time)
                ),
            };
            println!(
                "{} seed {seed}: {:.1} s, {end}",
                set.name, manifest.wall_seconds
            );
        }
    }
    let mut forces = Vec::new();
    let mut time = Vec::new();
    for i in 0..args.seeds.len() {
        let history = TaskDir(dir.join(format!("task-{i}")))
            .run()
            .join("history.csv");
        let force = ToolForce::read(&history, "punch")?;
        if force.time_s.len() > time.len() {
            time = force.time_s.clone();
        }
        forces.push(force.force_y);
    }
    let s = cutting::repeatability::spread(&forces).context("no spread")?;
    let n = s.mean.len();
    let feed: Vec<f64> = time[..n].iter().map(|&t| 100.0 * cut.feed_at(t)).collect();
    let mut csv =
        String::from("relative_feed,time_s,mean_force_y_n_per_m,std_force_y_n_per_m,cv\n");
    for k in 0..n {
        csv += &format!(
            "{:e},{:e},{:e},{:e},{:e}\n",
            feed[k] / 100.0,
            time[k],
            s.mean[k],
            s.std[k],
            s.cv[k]
        );
    }
    std::fs::write(args.out.join("repeat.csv"), csv)?;
    let band = |sign: f64| -> Vec<f64> { (0..n).map(|k| s.mean[k] + sign * s.std[k]).collect() };
    let ((lo, hi), off) = force_range(&[&band(1.0), &band(-1.0)]);
    LineChart::new(
        with_peak(
            format!(
                "vertical cut {}: punch force over {} seeds",
                set.name,
                args.seeds.len()
            ),
            off,
        ),
        "relative feed [%]",
        "punch force f_y [MN/m]",
    )
    .y_range(lo * 1e-6, hi * 1e-6)
    .with(Series::scaled("mean", &feed, &s.mean, 1.0, 1e-6))
    .with(Series::scaled("mean + std", &feed, &band(1.0), 1.0, 1e-6))
    .with(Series::scaled("mean − std", &feed, &band(-1.0), 1.0, 1e-6))
    .write_png(&args.out.join("repeat.png"))?;
    LineChart::new(
        format!(
            "vertical cut {}: CV(t) = std/mean over {} seeds",
            set.name,
            args.seeds.len()
        ),
        "relative feed [%]",
        "coefficient of variation [-]",
    )
    .y_range(0.0, 1.0)
    .with(Series::scaled("CV", &feed, &s.cv, 1.0, 1.0))
    .write_png(&args.out.join("cv.png"))?;
    let settled: Vec<f64> = (0..n)
        .filter(|&k| feed[k] >= 40.0)
        .map(|k| s.cv[k])
        .filter(|c| c.is_finite())
        .collect();
    if let Some(m) = mean(&settled) {
        let above = settled.iter().filter(|&&c| c > 0.3).count();
        println!(
            "CV of f_y from 40 % feed on: mean {m:.3}, above 0.3 in {above} of {} samples",
            settled.len()
        );
    }
    println!(
        "repeat.csv, repeat.png, cv.png and each seed's scene in {}",
        args.out.display()
    );
    Ok(())
}
