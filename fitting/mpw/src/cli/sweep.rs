//! `mpw sweep SCENE --vary FIELD=V1,V2,... [--vary FIELD=...] [--seeds 1..5]`: a study over
//! one or two fields of a scene and over seeds, every combination one run, through an
//! executor (`--executor in-process|pool|slurm`); the results as one CSV, `results.csv`,
//! one row per run: its index, the varied values, the seed, `status` (`ok` or `failed`,
//! a failure of the task), `failure` (the simulation's own early stop), then the returned
//! results as `name_unit` columns. The CSV is the same, byte for byte, whichever executor
//! ran the study.
//!
//! `--chart RESULT` draws a result against the first varied field, one line per value of
//! the second and per seed. A failed task is listed with its log at the end, and the
//! command then fails.

use super::executor_args::ExecutorArgs;
use super::progress::ProgressLine;
use anyhow::{bail, Context, Result};
use runs::{Batch, RunDescription, TaskReport};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The MPM scene (TOML).
    pub scene: PathBuf,
    /// A field of the scene and its values, e.g. `grid.spacing=1e-3,5e-4` or
    /// `bodies[0].velocity=[0,-100],[0,-200]` (at most two --vary).
    #[arg(long, value_name = "FIELD=V1,V2,...")]
    pub vary: Vec<String>,
    /// Seeds (the scene's grid.seed): a list `1,4,9` or a range `1..5` (1 to 5).
    #[arg(long)]
    pub seeds: Option<String>,
    /// The named results to keep (default: all the scene gives).
    #[arg(long, value_delimiter = ',')]
    pub returns: Vec<String>,
    /// Chart these results (`bar.z_max`, ...) against the first varied field, one line per
    /// value of the second field and seed: `<result>.png` in the output folder.
    #[arg(long, value_delimiter = ',')]
    pub chart: Vec<String>,
    /// Output folder: results.csv, and the runs' folders in tasks/ (Slurm: in the config's
    /// work_dir).
    #[arg(long)]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub executor: ExecutorArgs,
}

/// One varied field: its path and values.
#[derive(Debug, Clone, PartialEq)]
pub struct Varied {
    pub field: String,
    pub values: Vec<toml::Value>,
}

pub fn run(args: Args) -> Result<()> {
    let varied = args
        .vary
        .iter()
        .map(|v| parse_vary(v))
        .collect::<Result<Vec<_>>>()?;
    if varied.len() > 2 {
        bail!("--vary: at most two fields (a study over more is more than one sweep)");
    }
    let seeds = match &args.seeds {
        Some(s) => Some(parse_seeds(s)?),
        None => None,
    };
    let scene = args
        .scene
        .canonicalize()
        .with_context(|| format!("cannot find the scene {}", args.scene.display()))?;
    let name = scene
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new("out/sweep").join(&name));
    let descriptions = descriptions(&scene, &varied, seeds.as_deref(), &args.returns);
    // every description is checked here, so that a typo fails before anything is queued
    for d in &descriptions {
        let changed = crate::tasks::changed_scene(d)?;
        let shifted = changed.get("grid").and_then(|g| g.get("shift")).is_some();
        if d.seed.is_some() && !shifted {
            bail!(
                "--seeds: {} has no grid.shift, so its seed (grid.seed, the shift sequence) changes nothing; give the scene a [grid] shift or --vary grid.shift=...",
                scene.display()
            );
        }
    }
    let stop = super::interrupt::interrupt_flag()?;
    let execute = |d: &RunDescription, dir: &Path| crate::tasks::execute(d, dir, Some(&stop));
    let job_name = format!("mpw-sweep-{name}");
    let (executor, batch_dir) = args
        .executor
        .build(&job_name, &execute, out.join("tasks"))?;
    let batch = Batch::create(&batch_dir, &descriptions)?;
    eprintln!(
        "{} runs of {} ({}) in {}",
        descriptions.len(),
        scene.display(),
        executor.describe(),
        batch.dir.display()
    );
    let line = ProgressLine::default();
    let start = Instant::now();
    let reports = executor.run(&batch, &stop, &|state| {
        line.show(
            "sweep",
            &format!("{state}, {:.1} s", start.elapsed().as_secs_f64()),
        )
    })?;
    line.finish();
    let wall = start.elapsed().as_secs_f64();
    std::fs::create_dir_all(&out)?;
    let csv = out.join("results.csv");
    std::fs::write(
        &csv,
        table(&varied, seeds.is_some(), &descriptions, &reports)?,
    )
    .with_context(|| format!("cannot write {}", csv.display()))?;
    for name in &args.chart {
        chart(name, &varied, &descriptions, &reports, &out)?;
    }
    summarize(&reports, wall, &csv)
}

/// `FIELD=V1,V2,...`; values split at commas outside brackets and quotes.
pub fn parse_vary(text: &str) -> Result<Varied> {
    let Some((field, values)) = text.split_once('=') else {
        bail!("--vary `{text}`: expected FIELD=V1,V2,... (e.g. grid.spacing=1e-3,5e-4)");
    };
    let mut parts = Vec::new();
    let (mut depth, mut quoted, mut current) = (0i32, false, String::new());
    for c in values.chars() {
        match c {
            '"' => quoted = !quoted,
            '[' | '{' if !quoted => depth += 1,
            ']' | '}' if !quoted => depth -= 1,
            ',' if depth == 0 && !quoted => {
                parts.push(std::mem::take(&mut current));
                continue;
            }
            _ => {}
        }
        current.push(c);
    }
    parts.push(current);
    if parts.iter().any(|p| p.trim().is_empty()) {
        bail!("--vary `{text}`: an empty value");
    }
    Ok(Varied {
        field: field.trim().to_string(),
        values: parts
            .iter()
            .map(|p| runs::changes::parse_value(p))
            .collect(),
    })
}

/// `1,4,9` or `1..5` (inclusive).
pub fn parse_seeds(text: &str) -> Result<Vec<u64>> {
    let number = |s: &str| {
        s.trim()
            .parse::<u64>()
            .with_context(|| format!("--seeds `{text}`: `{s}` is not a seed (a whole number)"))
    };
    let seeds = match text.split_once("..") {
        Some((a, b)) => (number(a)?..=number(b)?).collect::<Vec<_>>(),
        None => text.split(',').map(number).collect::<Result<_>>()?,
    };
    if seeds.is_empty() {
        bail!("--seeds `{text}`: no seeds");
    }
    Ok(seeds)
}

/// Every combination of the varied values (the first field slowest) and the seeds.
pub fn descriptions(
    scene: &Path,
    varied: &[Varied],
    seeds: Option<&[u64]>,
    returns: &[String],
) -> Vec<RunDescription> {
    let mut base = RunDescription::new("scene", scene);
    base.returns = returns.to_vec();
    let mut all = vec![base];
    for v in varied {
        all = all
            .iter()
            .flat_map(|d| {
                v.values.iter().map(move |value| {
                    let mut d = d.clone();
                    d.set.insert(v.field.clone(), value.clone());
                    d
                })
            })
            .collect();
    }
    if let Some(seeds) = seeds {
        all = all
            .iter()
            .flat_map(|d| {
                seeds.iter().map(move |&s| RunDescription {
                    seed: Some(s),
                    ..d.clone()
                })
            })
            .collect();
    }
    all
}

/// The results table, one row per run in task order.
fn table(
    varied: &[Varied],
    seeded: bool,
    descriptions: &[RunDescription],
    reports: &[TaskReport],
) -> Result<String> {
    let names: Vec<(String, String)> = reports
        .iter()
        .find_map(|r| r.result.as_ref().ok())
        .map(|(o, _)| {
            o.values
                .iter()
                .map(|v| (v.name.clone(), v.unit.clone()))
                .collect()
        })
        .unwrap_or_default();
    let mut header = vec!["task".to_string()];
    header.extend(
        varied
            .iter()
            .map(|v| v.field.replace('[', "_").replace(']', "")),
    );
    if seeded {
        header.push("seed".into());
    }
    header.extend(["status".into(), "failure".into()]);
    header.extend(names.iter().map(|(n, u)| column(n, u)));
    let mut text = header.join(",") + "\n";
    for (r, d) in reports.iter().zip(descriptions) {
        let mut row = vec![r.index.to_string()];
        row.extend(varied.iter().map(|v| quote(&d.set[&v.field].to_string())));
        if seeded {
            row.push(d.seed.map_or(String::new(), |s| s.to_string()));
        }
        match &r.result {
            Ok((outcome, _)) => {
                row.push("ok".into());
                row.push(quote(outcome.failure.as_deref().unwrap_or("")));
                for (n, _) in &names {
                    let value = outcome
                        .value(n)
                        .with_context(|| format!("task {}: no result `{n}`", r.index))?;
                    row.push(number(value));
                }
            }
            Err(_) => {
                row.push("failed".into());
                row.push(String::new());
                row.extend(names.iter().map(|_| String::new()));
            }
        }
        writeln!(text, "{}", row.join(",")).expect("writing to a string");
    }
    Ok(text)
}

/// The result `name` of every run that gave it against the first varied field, one line
/// per value of the other coordinates (second field, seed), into `out/<name>.png`.
fn chart(
    name: &str,
    varied: &[Varied],
    descriptions: &[RunDescription],
    reports: &[TaskReport],
    out: &Path,
) -> Result<()> {
    let Some(first) = varied.first() else {
        bail!("--chart {name}: a chart needs a --vary field for its abscissa");
    };
    let mut lines: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    let mut unit = String::new();
    for (d, r) in descriptions.iter().zip(reports) {
        let Ok((outcome, _)) = &r.result else {
            continue;
        };
        let Some(v) = outcome.values.iter().find(|v| v.name == name) else {
            bail!("--chart {name}: the runs give no result `{name}`");
        };
        unit.clone_from(&v.unit);
        let x = match &d.set[&first.field] {
            toml::Value::Float(x) => *x,
            toml::Value::Integer(i) => *i as f64,
            other => bail!(
                "--chart: `{}` = {other} is not a number to chart against",
                first.field
            ),
        };
        let mut key: Vec<String> = varied[1..]
            .iter()
            .map(|v| format!("{} = {}", v.field, d.set[&v.field]))
            .collect();
        key.extend(d.seed.map(|s| format!("seed {s}")));
        let key = key.join(", ");
        match lines.iter_mut().find(|(k, _)| *k == key) {
            Some((_, points)) => points.push((x, v.value)),
            None => lines.push((key, vec![(x, v.value)])),
        }
    }
    let unit = match unit.as_str() {
        "-" | "" => String::new(),
        u => format!(" [{u}]"),
    };
    let mut c = crate::charts::LineChart::new(
        format!("sweep: {name}"),
        first.field.clone(),
        format!("{name}{unit}"),
    );
    for (key, mut points) in lines {
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        let label = if key.is_empty() {
            name.to_string()
        } else {
            key
        };
        c = c.with(crate::charts::Series { label, points });
    }
    c.write_png(&out.join(format!("{name}.png")))
}

/// A result's column: its name and unit, `bar.z_max_m`, `bar.kinetic_energy_j`,
/// `run.steps` (no unit).
fn column(name: &str, unit: &str) -> String {
    match unit {
        "-" | "" => name.to_string(),
        u => format!("{name}_{}", u.to_lowercase().replace('/', "_per_")),
    }
}

/// A value in its shortest form that reads back to the same bits: plain between 1e-4 and
/// 1e15 (`456`, `0.3837821021340549`), else with an exponent (`1.5e-9`).
fn number(value: f64) -> String {
    match value.abs() {
        a if a == 0.0 || (1e-4..1e15).contains(&a) => format!("{value}"),
        _ => format!("{value:e}"),
    }
}

/// A CSV field, quoted when it holds a comma or a quote.
fn quote(text: &str) -> String {
    match text.contains([',', '"', '\n']) {
        true => format!("\"{}\"", text.replace('"', "\"\"")),
        false => text.to_string(),
    }
}

/// Print what ran, how long it took and every failure with its log's last lines; fail
/// when a task failed.
fn summarize(reports: &[TaskReport], wall: f64, csv: &Path) -> Result<()> {
    let ok: Vec<_> = reports
        .iter()
        .filter_map(|r| r.result.as_ref().ok())
        .collect();
    let run_seconds: f64 = ok.iter().map(|(_, m)| m.wall_seconds).sum();
    let stopped = ok.iter().filter(|(o, _)| o.failure.is_some()).count();
    println!(
        "{} of {} runs gave results ({stopped} of them stopped early, see `failure`); {wall:.2} s wall, the runs' own time {run_seconds:.2} s; {}",
        ok.len(),
        reports.len(),
        csv.display()
    );
    let failed: Vec<_> = reports
        .iter()
        .filter_map(|r| r.result.as_ref().err())
        .collect();
    for f in &failed {
        eprintln!("{f}");
        if let Some(log) = &f.log {
            let text = std::fs::read_to_string(log).unwrap_or_default();
            let lines: Vec<&str> = text.lines().collect();
            for l in &lines[lines.len().saturating_sub(5)..] {
                eprintln!("    | {l}");
            }
        }
    }
    if !failed.is_empty() {
        bail!("{} of {} runs failed", failed.len(), reports.len());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn varied_values_split_outside_brackets_and_quotes() {
        let v = parse_vary("bodies[0].velocity=[0,-100],[0, -200]").unwrap();
        assert_eq!(v.field, "bodies[0].velocity");
        assert_eq!(v.values.len(), 2);
        assert_eq!(v.values[1].as_array().unwrap()[1].as_integer(), Some(-200));
        let v = parse_vary("time.scheme=usl,\"m,usl\"").unwrap();
        assert_eq!(v.values[1].as_str(), Some("m,usl"));
        assert!(parse_vary("grid.spacing").is_err());
        assert!(parse_vary("grid.spacing=1,,2").is_err());
    }

    #[test]
    fn numbers_are_short_and_read_back_to_the_same_bits() {
        assert_eq!(number(456.0), "456");
        assert_eq!(number(0.1 + 0.2), "0.30000000000000004");
        assert_eq!(number(-1.5e-9), "-1.5e-9");
        assert_eq!(number(f64::NAN), "NaN");
        for v in [1.0 / 3.0, 6.02214076e23, 5e-324, 123456.789e-3, -0.0] {
            assert_eq!(
                number(v).parse::<f64>().unwrap().to_bits(),
                v.to_bits(),
                "{v}"
            );
        }
    }

    #[test]
    fn seeds_are_lists_or_inclusive_ranges() {
        assert_eq!(parse_seeds("1..4").unwrap(), vec![1, 2, 3, 4]);
        assert_eq!(parse_seeds("9,2").unwrap(), vec![9, 2]);
        assert!(parse_seeds("1,x")
            .unwrap_err()
            .to_string()
            .contains("`x` is not a seed"));
    }

    #[test]
    fn every_combination_is_one_run_the_first_field_slowest() {
        let a = parse_vary("grid.spacing=1,2").unwrap();
        let b = parse_vary("time.safety=0.1,0.2,0.3").unwrap();
        let d = descriptions(Path::new("/s.toml"), &[a, b], Some(&[5, 6]), &[]);
        assert_eq!(d.len(), 12);
        assert_eq!(d[0].set["grid.spacing"].as_integer(), Some(1));
        assert_eq!(d[6].set["grid.spacing"].as_integer(), Some(2));
        assert_eq!(d[2].set["time.safety"].as_float(), Some(0.2));
        assert_eq!((d[0].seed, d[1].seed), (Some(5), Some(6)));
    }
}
