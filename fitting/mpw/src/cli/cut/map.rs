//! `mpw cut map`: the vertical cut's stability map: one run per variant × grid spacing ×
//! points over the thickness, each a `scene` task of an executor (`--executor pool` runs
//! them side by side, `slurm` on a cluster); the feed each reached and its wall time.

use super::{absolute, vertical_scene_text};
use crate::cli::executor_args::ExecutorArgs;
use crate::cli::progress::ProgressLine;
use anyhow::{Context, Result};
use cutting::vertical::{Discretization, VerticalCut};
use cutting::workpiece::RunOptions;
use runs::{Batch, RunDescription};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct MapArgs {
    /// Grid spacings [m].
    #[arg(long, value_delimiter = ',', default_value = "1e-4,6.25e-5,5e-5")]
    pub spacings: Vec<f64>,
    /// Points over the sheet's thickness.
    #[arg(long, value_delimiter = ',', default_value = "60,100,200")]
    pub points: Vec<usize>,
    /// Variants: a shape function, `+shift` for the grid shift with springs
    /// (linear, linear+shift, cpdi, cpdi+shift, ...).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "linear,linear+shift,cpdi,cpdi+shift"
    )]
    pub variants: Vec<String>,
    /// Relative feed at which each run ends.
    #[arg(long, default_value_t = 1.2)]
    pub feed: f64,
    #[arg(long, default_value = "data/materials/al7075_t6.toml")]
    pub material: PathBuf,
    /// Output folder.
    #[arg(long, default_value = "out/cut_map")]
    pub out: PathBuf,
    #[command(flatten)]
    pub executor: ExecutorArgs,
}

/// One cell of the stability map.
struct Cell {
    variant: String,
    spacing: f64,
    points: usize,
    feed: f64,
    wall_s: f64,
    stop: String,
}

pub fn map(args: MapArgs) -> Result<()> {
    let material = absolute(&args.material)?;
    let cut = VerticalCut::default();
    let mut cells = Vec::new();
    let mut descriptions = Vec::new();
    for variant in &args.variants {
        let (kernel, shift) = match variant.split_once('+') {
            Some((k, "shift")) => (k, true),
            None => (variant.as_str(), false),
            Some(_) => {
                anyhow::bail!("--variants {variant}: expected a shape function, optionally +shift")
            }
        };
        for &spacing in &args.spacings {
            for &points_y in &args.points {
                let set = Discretization {
                    name: "map",
                    spacing,
                    points_y,
                    shift,
                };
                let options = RunOptions {
                    shape_function: kernel.to_string(),
                    snapshots: 2,
                    ..RunOptions::new(&material)
                };
                let scene = args
                    .out
                    .join(format!("{variant}_dx{spacing}_ny{points_y}"))
                    .join("scene.toml");
                std::fs::create_dir_all(scene.parent().expect("a folder"))?;
                std::fs::write(
                    &scene,
                    vertical_scene_text(&cut, &set, args.feed, &options)?,
                )
                .with_context(|| format!("cannot write {}", scene.display()))?;
                let mut d = RunDescription::new("scene", &scene.canonicalize()?);
                d.returns = vec![
                    "run.time".into(),
                    "run.steps".into(),
                    "run.particles".into(),
                ];
                descriptions.push(d);
                cells.push(Cell {
                    variant: variant.clone(),
                    spacing,
                    points: points_y,
                    feed: f64::NAN,
                    wall_s: f64::NAN,
                    stop: String::new(),
                });
            }
        }
    }
    let stop = crate::cli::interrupt::interrupt_flag()?;
    let execute = |d: &RunDescription, dir: &Path| crate::tasks::execute(d, dir, Some(&stop));
    let (executor, dir) = args
        .executor
        .build("mpw-cut-map", &execute, args.out.join("tasks"))?;
    let batch = Batch::create(&dir, &descriptions)?;
    println!(
        "{} runs ({}), their output in {}",
        cells.len(),
        executor.describe(),
        batch.dir.display()
    );
    let line = ProgressLine::default();
    let reports = executor.run(&batch, &stop, &|state| line.show("map", &state.to_string()))?;
    line.finish();
    for (cell, report) in cells.iter_mut().zip(reports) {
        match report.result {
            Err(f) => cell.stop = format!("not run: {f}"),
            Ok((outcome, manifest)) => {
                let time = outcome.value("run.time").unwrap_or(f64::NAN);
                cell.wall_s = manifest.wall_seconds;
                (cell.feed, cell.stop) = match outcome.failure {
                    None => (args.feed, "ran through".to_string()),
                    Some(failure) => (cut.feed_at(time), failure),
                };
            }
        }
        println!(
            "{}, dx = {} m, {} points over the thickness: {} ({:.0} s)",
            cell.variant, cell.spacing, cell.points, cell.stop, cell.wall_s
        );
    }
    let mut csv = String::from("variant,spacing_m,points_y,relative_feed_reached,wall_s,stop\n");
    for c in &cells {
        csv += &format!(
            "{},{:e},{},{:e},{:e},\"{}\"\n",
            c.variant,
            c.spacing,
            c.points,
            c.feed,
            c.wall_s,
            c.stop.replace('"', "'")
        );
    }
    std::fs::create_dir_all(&args.out)?;
    std::fs::write(args.out.join("map.csv"), csv)?;
    for variant in &args.variants {
        let of: Vec<&Cell> = cells.iter().filter(|c| &c.variant == variant).collect();
        crate::charts::cell_map::CellMap {
            title: format!("vertical cut, {variant}: relative feed reached (wall time)"),
            x_label: "grid spacing [mm]".into(),
            y_label: "points over the thickness".into(),
            columns: args
                .spacings
                .iter()
                .map(|s| format!("{}", s * 1e3))
                .collect(),
            rows: args.points.iter().map(|n| n.to_string()).collect(),
            cells: of
                .iter()
                .map(|c| {
                    let column = args.spacings.iter().position(|&s| s == c.spacing).unwrap();
                    let row = args.points.iter().position(|&n| n == c.points).unwrap();
                    let text = match c.feed >= args.feed {
                        _ if c.feed.is_nan() => "not run".to_string(),
                        true => format!("ran through\n{:.0} s", c.wall_s),
                        false => format!("{:.0} %\n{:.0} s", 100.0 * c.feed, c.wall_s),
                    };
                    (column, row, c.feed.max(0.0) / args.feed, text)
                })
                .collect(),
        }
        .write_png(
            &args
                .out
                .join(format!("map_{}.png", variant.replace('+', "_"))),
        )?;
    }
    println!(
        "map.csv and one chart per variant in {}",
        args.out.display()
    );
    Ok(())
}
