//! `mpw cut map`: where each method fails. One run per variant × grid spacing × points over
//! the height, each a `scene` task of an executor (`--executor pool` runs them side by
//! side, `slurm` on a cluster), charted as a map per variant: for the vertical cut the
//! relative feed reached, for the orthogonal cut (`--cut orthogonal`, the thesis's
//! sensitivity matrix) the time reached with the steady cutting force, each with the run's
//! wall time.
//!
//! Every cell keeps its run in its own folder (`<variant>_dx<spacing>_ny<points>`: scene,
//! history, snapshots, `run.toml`); a cell whose folder already holds a finished run of the
//! same scene is not run again, so a map can be resumed, or completed from runs made one
//! by one with `mpw cut vertical` / `mpw cut orthogonal --out` into those folders;
//! `--analyse-only` draws the cells already run and runs none.

use super::{absolute, orthogonal_scene_text, vertical_scene_text};
use crate::cli::executor_args::ExecutorArgs;
use crate::cli::progress::ProgressLine;
use anyhow::{Context, Result};
use cutting::orthogonal::{OrthogonalCut, Resolution};
use cutting::record::RunRecord;
use cutting::vertical::{Discretization, VerticalCut};
use cutting::workpiece::RunOptions;
use runs::{Batch, RunDescription};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct MapArgs {
    /// Which cut: vertical (feed reached) or orthogonal (time reached, steady f_x).
    #[arg(long, default_value = "vertical")]
    pub cut: String,
    /// Grid spacings [m] (default: vertical 1e-4,6.25e-5,5e-5; orthogonal 2e-4,1e-4,8e-5).
    #[arg(long, value_delimiter = ',')]
    pub spacings: Vec<f64>,
    /// Points over the height (default: vertical 60,100,200; orthogonal 80,100,150).
    #[arg(long, value_delimiter = ',')]
    pub points: Vec<usize>,
    /// Variants: a shape function, for the vertical cut `+shift` for the grid shift with
    /// springs (default: vertical linear,linear+shift,cpdi,cpdi+shift; orthogonal, which
    /// always shifts the grid, linear).
    #[arg(long, value_delimiter = ',')]
    pub variants: Vec<String>,
    /// Vertical cut: the relative feed at which each run ends.
    #[arg(long, default_value_t = 1.2)]
    pub feed: f64,
    /// Orthogonal cut: the run time [s].
    #[arg(long, default_value_t = 80e-6)]
    pub end: f64,
    /// Material file (default: the cut's material in data/materials).
    #[arg(long)]
    pub material: Option<PathBuf>,
    /// Draw the map from the cells already run; the others show as not run.
    #[arg(long)]
    pub analyse_only: bool,
    /// Output folder (default out/cut_map, or out/cut_map_orthogonal).
    #[arg(long)]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub executor: ExecutorArgs,
}

/// The cut a map is drawn for.
enum Cut {
    Vertical { cut: VerticalCut, end_feed: f64 },
    Orthogonal(OrthogonalCut),
}

impl Cut {
    fn name(&self) -> &'static str {
        match self {
            Cut::Vertical { .. } => "vertical",
            Cut::Orthogonal(_) => "orthogonal",
        }
    }

    /// The simulated time every cell runs to [s].
    fn end(&self) -> f64 {
        match self {
            Cut::Vertical { cut, end_feed } => end_feed * cut.full_feed_time,
            Cut::Orthogonal(cut) => cut.end,
        }
    }

    /// The scene text of one cell.
    fn scene(
        &self,
        variant: &str,
        spacing: f64,
        points_y: usize,
        material: &str,
    ) -> Result<String> {
        let (kernel, shift) = match variant.split_once('+') {
            Some((k, "shift")) => (k, true),
            None => (variant, false),
            Some(_) => {
                anyhow::bail!("--variants {variant}: expected a shape function, optionally +shift")
            }
        };
        match self {
            Cut::Vertical { cut, end_feed } => {
                let set = Discretization {
                    name: "map",
                    spacing,
                    points_y,
                    shift,
                };
                let options = RunOptions {
                    shape_function: kernel.to_string(),
                    snapshots: 2,
                    ..RunOptions::new(material)
                };
                vertical_scene_text(cut, &set, *end_feed, &options)
            }
            Cut::Orthogonal(cut) => {
                if shift {
                    anyhow::bail!("--variants {variant}: the orthogonal cut always shifts the grid; give the shape function alone");
                }
                let options = RunOptions {
                    shape_function: kernel.to_string(),
                    ..RunOptions::new(material)
                };
                let resolution = Resolution { spacing, points_y };
                orthogonal_scene_text(cut, &resolution, &options)
            }
        }
    }

    /// The columns `measure` adds to `map.csv`.
    fn columns(&self) -> &'static str {
        match self {
            Cut::Vertical { .. } => "relative_feed_reached",
            Cut::Orthogonal(_) => {
                "steady_force_x_n_per_m,shear_angle_chip_flow_deg,shear_angle_chip_thickness_deg"
            }
        }
    }

    /// How far a run got as a fraction of its end, the cell's text and the run's values
    /// for `map.csv` (`columns`).
    fn measure(&self, folder: &Path, record: &RunRecord) -> Result<(f64, String, String)> {
        let wall = format!("{:.0} s", record.wall_s);
        Ok(match self {
            Cut::Vertical { cut, end_feed } => {
                let feed = match record.failure {
                    None => *end_feed,
                    Some(_) => cut.feed_at(record.time_reached_s),
                };
                let text = match record.failure {
                    None => format!("ran through\n{wall}"),
                    Some(_) => format!("{:.0} %\n{wall}", 100.0 * feed),
                };
                (feed / end_feed, text, format!("{feed:e}"))
            }
            Cut::Orthogonal(cut) => {
                let result = crate::cut_forces::orthogonal_result(folder, cut)?;
                let fx = result.steady_force().map_or(f64::NAN, |[fx, _]| fx);
                let phi = result.shear_angle().map_or(f64::NAN, |(phi, _)| phi);
                let thickness =
                    (result.shear_angle_from_thickness()).map_or(f64::NAN, |(phi, _)| phi);
                let reach = match record.failure {
                    None => "ran through".to_string(),
                    Some(_) => format!("{:.1} µs", record.time_reached_s * 1e6),
                };
                let force = match fx.is_finite() {
                    true => format!("f_x {:.2} MN/m", fx * 1e-6),
                    false => "no steady f_x".to_string(),
                };
                let text = format!("{reach}\n{force}\n{wall}");
                let fraction = record.time_reached_s / record.end_s;
                (fraction, text, format!("{fx:e},{phi:e},{thickness:e}"))
            }
        })
    }
}

/// One cell of a map.
struct Cell {
    variant: String,
    spacing: f64,
    points: usize,
    folder: PathBuf,
    record: Option<RunRecord>,
    /// Why the cell has no run.
    error: Option<String>,
}

pub fn map(mut args: MapArgs) -> Result<()> {
    let cut = defaults(&mut args)?;
    let out = (args.out.clone()).unwrap_or_else(|| match cut {
        Cut::Vertical { .. } => PathBuf::from("out/cut_map"),
        Cut::Orthogonal(_) => PathBuf::from("out/cut_map_orthogonal"),
    });
    let material = absolute(args.material.as_deref().expect("defaulted"))?;
    let mut cells = Vec::new();
    let mut to_run = Vec::new();
    for variant in &args.variants {
        for &spacing in &args.spacings {
            for &points in &args.points {
                let folder = out.join(format!("{variant}_dx{spacing}_ny{points}"));
                let text = cut.scene(variant, spacing, points, &material)?;
                let record = finished_run(&folder, &text);
                if record.is_none() && !args.analyse_only {
                    prepare(&folder, &text)?;
                    to_run.push(cells.len());
                }
                cells.push(Cell {
                    variant: variant.clone(),
                    spacing,
                    points,
                    folder,
                    record,
                    error: None,
                });
            }
        }
    }
    let done = cells.iter().filter(|c| c.record.is_some()).count();
    println!("{} cells, {done} of them already run", cells.len());
    if !to_run.is_empty() {
        run_cells(&mut cells, &to_run, cut.end(), &args.executor, &out)?;
    }
    report(&cut, &args, &cells, &out)
}

/// The cut of `args.cut`, with the defaults of that cut filled into `args`.
fn defaults(args: &mut MapArgs) -> Result<Cut> {
    let (cut, spacings, points, variants, material): (Cut, &[f64], &[usize], &[&str], _) =
        match args.cut.as_str() {
            "vertical" => (
                Cut::Vertical {
                    cut: VerticalCut::default(),
                    end_feed: args.feed,
                },
                &[1e-4, 6.25e-5, 5e-5],
                &[60, 100, 200],
                &["linear", "linear+shift", "cpdi", "cpdi+shift"],
                "data/materials/al7075_t6.toml",
            ),
            "orthogonal" => (
                Cut::Orthogonal(OrthogonalCut {
                    end: args.end,
                    ..OrthogonalCut::default()
                }),
                &[2e-4, 1e-4, 8e-5],
                &[80, 100, 150],
                &["linear"],
                "data/materials/42crmo4_qt660.toml",
            ),
            other => anyhow::bail!("--cut \"{other}\": expected \"vertical\" or \"orthogonal\""),
        };
    if args.spacings.is_empty() {
        args.spacings = spacings.to_vec();
    }
    if args.points.is_empty() {
        args.points = points.to_vec();
    }
    if args.variants.is_empty() {
        args.variants = variants.iter().map(|v| v.to_string()).collect();
    }
    args.material.get_or_insert_with(|| PathBuf::from(material));
    Ok(cut)
}

/// The record of a finished run of scene `text` in `folder`, if there is one.
fn finished_run(folder: &Path, text: &str) -> Option<RunRecord> {
    let written = std::fs::read_to_string(folder.join("scene.toml")).ok()?;
    (written == text)
        .then(|| RunRecord::read(folder).ok())
        .flatten()
}

/// An empty `folder` with the scene `text` (a run of another scene, or an unfinished one,
/// is removed first: none of its files may be read as this run's).
fn prepare(folder: &Path, text: &str) -> Result<()> {
    if folder.exists() {
        println!(
            "{}: removing an unfinished run or a run of another scene",
            folder.display()
        );
        std::fs::remove_dir_all(folder)
            .with_context(|| format!("{}: cannot clear", folder.display()))?;
    }
    std::fs::create_dir_all(folder)
        .with_context(|| format!("{}: cannot create", folder.display()))?;
    std::fs::write(folder.join("scene.toml"), text)
        .with_context(|| format!("{}: cannot write the scene", folder.display()))
}

/// Run the cells `to_run` (to `end_s` [s]) through the executor; each run's output is
/// moved into its cell's folder with its record.
fn run_cells(
    cells: &mut [Cell],
    to_run: &[usize],
    end_s: f64,
    executor: &ExecutorArgs,
    out: &Path,
) -> Result<()> {
    let mut descriptions = Vec::new();
    for &i in to_run {
        let scene = cells[i].folder.join("scene.toml").canonicalize()?;
        let mut d = RunDescription::new("scene", &scene);
        d.returns = ["run.time", "run.steps", "run.dt", "run.particles"]
            .map(String::from)
            .to_vec();
        descriptions.push(d);
    }
    let stop = crate::cli::interrupt::interrupt_flag()?;
    let execute = |d: &RunDescription, dir: &Path| crate::tasks::execute(d, dir, Some(&stop));
    let (executor, dir) = executor.build("mpw-cut-map", &execute, out.join("tasks"))?;
    let batch = Batch::create(&dir, &descriptions)?;
    println!(
        "{} runs ({}) in {}",
        to_run.len(),
        executor.describe(),
        batch.dir.display()
    );
    let line = ProgressLine::default();
    let reports = executor.run(&batch, &stop, &|state| line.show("map", &state.to_string()))?;
    line.finish();
    for (report, &i) in reports.into_iter().zip(to_run) {
        let cell = &mut cells[i];
        match report.result {
            Err(f) => cell.error = Some(format!("not run: {f}")),
            Ok((outcome, manifest)) => {
                let value = |name: &str| outcome.value(name).unwrap_or(f64::NAN);
                let record = RunRecord {
                    points: value("run.particles") as usize,
                    steps: value("run.steps") as usize,
                    dt_s: value("run.dt"),
                    wall_s: manifest.wall_seconds,
                    threads: manifest.threads,
                    time_reached_s: value("run.time"),
                    end_s,
                    failure: outcome.failure,
                };
                move_output(&batch.task(report.index).run(), &cell.folder)?;
                record.write(&cell.folder)?;
                cell.record = Some(record);
            }
        }
    }
    Ok(())
}

/// Every file of the run folder `from` into `to` (the scene there stays).
fn move_output(from: &Path, to: &Path) -> Result<()> {
    for entry in
        std::fs::read_dir(from).with_context(|| format!("{}: no run output", from.display()))?
    {
        let path = entry?.path();
        let name = path.file_name().expect("a file");
        if name != "scene.toml" {
            std::fs::rename(&path, to.join(name))
                .with_context(|| format!("cannot move {} into {}", path.display(), to.display()))?;
        }
    }
    Ok(())
}

/// Print each cell, write `map.csv` and one chart per variant.
fn report(cut: &Cut, args: &MapArgs, cells: &[Cell], out: &Path) -> Result<()> {
    let mut csv = format!(
        "variant,spacing_m,points_y,{},time_reached_s,wall_s,threads,particle_steps_per_s,stop\n",
        cut.columns()
    );
    let mut drawn = Vec::new();
    for c in cells {
        let (fraction, text, values) = match (&c.record, &c.error) {
            (Some(r), _) => cut.measure(&c.folder, r)?,
            (None, e) => (
                f64::NAN,
                e.clone().unwrap_or_else(|| "not run".into()),
                String::new(),
            ),
        };
        println!(
            "{}, dx = {} m, {} points over the height: {}",
            c.variant,
            c.spacing,
            c.points,
            text.replace('\n', ", ")
        );
        if let Some(r) = &c.record {
            csv += &format!(
                "{},{:e},{},{values},{:e},{:e},{},{:e},\"{}\"\n",
                c.variant,
                c.spacing,
                c.points,
                r.time_reached_s,
                r.wall_s,
                r.threads,
                r.throughput(),
                r.failure
                    .as_deref()
                    .unwrap_or("ran through")
                    .replace('"', "'")
            );
        }
        drawn.push((fraction, text));
    }
    std::fs::create_dir_all(out)?;
    std::fs::write(out.join("map.csv"), csv)?;
    for variant in &args.variants {
        chart(cut, args, cells, &drawn, variant, out)?;
    }
    println!("map.csv and one chart per variant in {}", out.display());
    Ok(())
}

fn chart(
    cut: &Cut,
    args: &MapArgs,
    cells: &[Cell],
    drawn: &[(f64, String)],
    variant: &str,
    out: &Path,
) -> Result<()> {
    let what = match cut {
        Cut::Vertical { .. } => "relative feed reached (wall time)",
        Cut::Orthogonal(_) => "time reached, steady f_x (wall time)",
    };
    crate::charts::cell_map::CellMap {
        title: format!("{} cut, {variant}: {what}", cut.name()),
        x_label: "grid spacing [mm]".into(),
        y_label: "points over the height".into(),
        columns: args
            .spacings
            .iter()
            .map(|s| format!("{}", s * 1e3))
            .collect(),
        rows: args.points.iter().map(|n| n.to_string()).collect(),
        cells: cells
            .iter()
            .zip(drawn)
            .filter(|(c, _)| c.variant == variant)
            .map(|(c, (fraction, text))| {
                let column = args.spacings.iter().position(|&s| s == c.spacing).unwrap();
                let row = args.points.iter().position(|&n| n == c.points).unwrap();
                (column, row, *fraction, text.clone())
            })
            .collect(),
    }
    .write_png(&out.join(format!("map_{}.png", variant.replace('+', "_"))))
}
