//! `mpw verify`: every verification case of the project, one table row each (case,
//! measured, reference, tolerance, pass/fail); exits non-zero if any case fails.
//! `--charts DIR` also draws the figure 4.5 reproduction, the iso-error maps, the
//! energy histories of USL, USF and MUSL on Bardenhagen's bar (energies and total drift)
//! and the truss displacement per kernel.

use crate::charts::heatmap::HeatMap;
use crate::charts::{LineChart, Series};
use crate::cli::progress::ProgressLine;
use crate::verify::data::VerifyData;
use crate::verify::materials::{self as studies, figure_4_5, iso_error};
use crate::verify::row::{Row, Verdict};
use crate::verify::Inputs;
use anyhow::{bail, Result};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Full-size cases (finer iso-error map, full-size MPM benchmarks).
    #[arg(long)]
    pub full: bool,
    /// Write the verification charts (PNG) into this folder.
    #[arg(long)]
    pub charts: Option<PathBuf>,
    /// Reference data folder: materials/ (parameter sets of every material and MPM case)
    /// and experiments/ (the default set, the 304L and 945 experiment files, whose real
    /// records lie in DIR/../../shared/data), so a copied binary runs the table from
    /// anywhere.
    #[arg(long, default_value = "data")]
    pub data: PathBuf,
    /// Fail when the rows on the shared real data (DIR/../../shared/data) did not run.
    #[arg(long)]
    pub require_data: bool,
    /// Also write every row (case, measured and reference to full precision, result) to
    /// this CSV file, to compare two builds value by value.
    #[arg(long)]
    pub values: Option<PathBuf>,
    /// Where the catalogue's parts run: in this process (one after another), or each part
    /// a task of a local process pool or a Slurm job array (their runs in
    /// out/verify_runs, or under Slurm's work_dir).
    #[command(flatten)]
    pub executor: super::executor_args::ExecutorArgs,
    /// Only these parts of the table, comma separated (materials, shpb, fit, fit-mpm,
    /// fit-real, mpm, shpb-model, shpb-derivatives, cutting, cutting-orthogonal,
    /// cutting-derivatives); every part when not given.
    #[arg(long, value_delimiter = ',')]
    pub part: Vec<String>,
}

/// The catalogue's `parts` as tasks of `executor`, the rows read back in table order.
fn table_through(
    executor: &dyn runs::Executor,
    dir: &Path,
    (data, full): (&Path, bool),
    parts: &[&str],
) -> Result<Vec<Row>> {
    use crate::tasks::{VerifyRows, ROWS_FILE, VERIFY_PART};
    let data = data
        .canonicalize()
        .map_err(|e| anyhow::anyhow!("{}: {e}", data.display()))?;
    let descriptions: Vec<runs::RunDescription> = parts
        .iter()
        .map(|part| {
            let mut d = runs::RunDescription::new(VERIFY_PART, &data);
            d.set
                .insert("part".into(), toml::Value::String(part.to_string()));
            d.set.insert("full".into(), toml::Value::Boolean(full));
            d
        })
        .collect();
    let batch = runs::Batch::create(dir, &descriptions)?;
    eprintln!(
        "{} parts ({}) in {}",
        descriptions.len(),
        executor.describe(),
        batch.dir.display()
    );
    let stop = crate::cli::interrupt::interrupt_flag()?;
    let (line, start) = (ProgressLine::default(), Instant::now());
    let reports = executor.run(&batch, &stop, &|state| {
        let text = format!("{state}, {:.0} s", start.elapsed().as_secs_f64());
        line.show("verify", &text)
    })?;
    line.finish();
    let mut rows = Vec::new();
    for report in reports {
        report.result.map_err(|f| anyhow::anyhow!("{f}"))?;
        let file = batch.task(report.index).run().join(ROWS_FILE);
        let text = std::fs::read_to_string(&file)
            .map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))?;
        let part: VerifyRows =
            toml::from_str(&text).map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))?;
        rows.extend(part.rows);
    }
    crate::verify::unique(rows)
}

/// Every row with its numbers in shortest round-trip form.
fn write_values(path: &Path, cases: &[Row]) -> Result<()> {
    let mut text = String::from("case,measured,reference,result,note\n");
    for c in cases {
        let result = match c.verdict {
            Verdict::Info => "info",
            Verdict::Pass => "pass",
            Verdict::Fail => "fail",
        };
        let quoted = |s: &str| format!("\"{}\"", s.replace('"', "\"\""));
        text += &format!(
            "{},{:e},{:e},{result},{}\n",
            quoted(&c.name),
            c.measured,
            c.reference,
            quoted(&c.note)
        );
    }
    std::fs::write(path, text).map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", path.display()))
}

/// Thesis figure 4.5: σ_xx against engineering strain for the four rate/temperature pairs.
fn figure_4_5_chart(materials: &Path, out: &Path) -> Result<()> {
    let m = materials::load_elasto_plastic(materials.join("aisi_4340.toml"))?;
    let mut chart = LineChart::new(
        "Johnson-Cook AISI 4340, uniaxial tension then hold (thesis fig. 4.5)",
        "engineering strain ε_xx [-]",
        "Cauchy stress σ_xx [MPa]",
    );
    for c in figure_4_5::run(&m)? {
        // The hold shows as the vertical drop at ε_xx = 0.6.
        let x: Vec<f64> = c.records.iter().map(|r| r.f[(0, 0)] - 1.0).collect();
        let y: Vec<f64> = c.records.iter().map(|r| r.sigma[(0, 0)]).collect();
        chart = chart.with(Series::scaled(
            format!("ε̇ = {} 1/s, θ = {} K", c.rate, c.theta),
            &x,
            &y,
            1.0,
            1e-6,
        ));
    }
    chart.write_png(&out.join("figure_4_5.png"))
}

fn iso_error_charts(materials: &Path, out: &Path) -> Result<()> {
    let multiples: Vec<f64> = (0..=20).map(|k| 5.0 * k as f64).collect();
    let j2 = studies::j2_voce(materials)?;
    let jc = materials::load_elasto_plastic(materials.join("42crmo4_qt660.toml"))?;
    for (name, m) in [("j2", j2), ("johnson_cook", jc)] {
        let map = iso_error::run(&m, &multiples);
        HeatMap {
            title: format!(
                "{name}: one-step stress error vs {} sub-steps",
                iso_error::SUBSTEPS
            ),
            x_label: "increment along the loading direction n1 [yield strains]".into(),
            y_label: "increment along the tangential direction n2 [yield strains]".into(),
            x: map.a.clone(),
            y: map.b.clone(),
            value: map.error.clone(),
            log10_range: (-4.0, 0.0),
            value_label: "relative stress error [-]".into(),
            missing_label: "the one-step update failed".into(),
        }
        .write_png(&out.join(format!("iso_error_{name}.png")))?;
    }
    Ok(())
}

/// Bardenhagen's bar (2002): kinetic, strain (stress work) and total energy of USL, USF
/// and MUSL side by side, the energy behaviour the thesis compares in chapter 2.
fn bar_energy_chart(out: &Path) -> Result<()> {
    use crate::verify::mpm::vibration;
    use mpm_core::Scheme;
    let mut chart = LineChart::new(
        "Continuum bar (Bardenhagen 2002), 25 cells: energy per update scheme",
        "t [s]",
        "energy per metre of thickness [J/m]",
    );
    // the curves of the three schemes nearly coincide; the relative drift of the total
    // (K + W_int)/E0 − 1 shows where they differ
    let mut drift = LineChart::new(
        "Continuum bar (Bardenhagen 2002), 25 cells: total energy drift per update scheme",
        "t [s]",
        "(K + W_int) / E0 - 1 [-]",
    );
    for (name, scheme) in [
        ("USL", Scheme::Usl),
        ("USF", Scheme::Usf),
        ("MUSL", Scheme::Musl),
    ] {
        let e = vibration::bar(scheme, 25).energy;
        let e0 = e[0].1 + e[0].2;
        drift = drift.with(Series {
            label: name.into(),
            points: e.iter().map(|&(t, k, w)| (t, (k + w) / e0 - 1.0)).collect(),
        });
        let series = |what: &str, f: &dyn Fn(f64, f64) -> f64| Series {
            label: format!("{name} {what}"),
            points: e.iter().map(|&(t, k, w)| (t, f(k, w))).collect(),
        };
        chart = chart
            .with(series("total K + W_int", &|k, w| k + w))
            .with(series("kinetic K", &|k, _| k))
            .with(series("strain W_int", &|_, w| w));
    }
    chart.write_png(&out.join("bar_energy_schemes.png"))?;
    drift.write_png(&out.join("bar_energy_drift.png"))
}

/// Truss benchmark (thesis §10.2, plane strain, 0.5 m cells): displacement of the top
/// centre A against time per kernel; a separated run leaves the chart (its upper part
/// falls away without bound).
fn truss_chart(scenes: &Path, out: &Path) -> Result<()> {
    use crate::verify::mpm::truss::truss;
    use mpm_core::shape::ShapeFunction::{CpGimp, CpGimpAnalytic, Cpdi, Linear, UGimp};
    const SHOWN: f64 = 4.0; // m
    let mut chart = LineChart::new(
        "Truss, plane strain, 0.5 m cells: top-centre displacement per kernel (thesis fig. 10.9)",
        "t [s]",
        "displacement of A along the pull [m]",
    );
    let plane = scenes.join("truss.toml");
    for (kernel, n) in [
        (Linear, 6),
        (UGimp, 6),
        (CpGimpAnalytic, 6),
        (CpGimp, 6),
        (Cpdi, 6),
        (Linear, 10),
        (Cpdi, 40),
    ] {
        let run = truss(&plane, kernel, 0.5, n);
        let separated = run.a_peak() > SHOWN;
        chart = chart.with(Series {
            label: format!(
                "{} n = {n}{}",
                kernel.name(),
                if separated {
                    " (separates: leaves the chart)"
                } else {
                    ""
                }
            ),
            points: run
                .history
                .iter()
                .map(|h| (h.t, if h.a > SHOWN { f64::NAN } else { h.a }))
                .collect(),
        });
    }
    chart.write_png(&out.join("truss_displacement.png"))
}

/// Taylor bar derivatives: the central differences' error against the step (the noise
/// curve), and how each Johnson-Cook parameter moves the length and the footprint
/// through the impact (exact derivatives, scaled by the parameter).
fn taylor_derivative_charts(materials: &Path, out: &Path) -> Result<()> {
    use crate::verify::mpm::taylor_derivatives::{Study, FREE, QUANTITIES, STEPS};
    let study = Study::run(materials, &STEPS)?;
    for (q, file) in [(0, "length"), (2, "footprint")] {
        let mut noise = LineChart::new(
            format!(
                "Taylor bar, dx 0.635 mm, 80 µs: central differences of {} against the exact derivative",
                QUANTITIES[q]
            ),
            "log10 of the relative step h/p [-]",
            "log10 of |central − exact| · p / (largest |p ∂q/∂p|) [-]",
        )
        .markers();
        let mut history = LineChart::new(
            format!(
                "Taylor bar, dx 0.635 mm: sensitivity of {} to each Johnson-Cook parameter (exact)",
                QUANTITIES[q]
            ),
            "t [µs]",
            "p ∂q/∂p [mm]",
        );
        for (k, parameter) in FREE.iter().enumerate() {
            noise = noise.with(Series {
                label: (*parameter).into(),
                points: (0..STEPS.len())
                    .map(|j| (STEPS[j].log10(), study.error(q, k, j).log10()))
                    .collect(),
            });
            history = history.with(Series {
                label: (*parameter).into(),
                points: (study.exact.history.iter())
                    .map(|(t, d)| (t * 1e6, d[q][k] * 1e3))
                    .collect(),
            });
        }
        noise.write_png(&out.join(format!("taylor_derivatives_{file}_central_error.png")))?;
        history.write_png(&out.join(format!("taylor_derivatives_{file}_history.png")))?;
    }
    Ok(())
}

pub fn run(args: Args) -> Result<()> {
    let data = VerifyData::new(&args.data);
    let materials = data.materials();
    let inputs = Inputs {
        data: &data,
        full: args.full,
    };
    let subprocesses = args
        .executor
        .subprocesses("mpw-verify", PathBuf::from("out/verify_runs"))?;
    let parts = crate::verify::selected(&args.part)?;
    let cases = match subprocesses {
        None => crate::verify::table(&inputs, &parts)?,
        Some((executor, dir)) => {
            table_through(executor.as_ref(), &dir, (&args.data, args.full), &parts)?
        }
    };
    println!(
        "{:<60} {:>14} {:>14} {:>12} result",
        "case", "measured", "reference", "tolerance"
    );
    for c in &cases {
        println!("{c}");
    }
    if let Some(path) = &args.values {
        write_values(path, &cases)?;
    }
    if let Some(dir) = &args.charts {
        std::fs::create_dir_all(dir)?;
        figure_4_5_chart(&materials, dir)?;
        iso_error_charts(&materials, dir)?;
        bar_energy_chart(dir)?;
        truss_chart(&data.scenes(), dir)?;
        taylor_derivative_charts(&materials, dir)?;
        println!("charts written to {}", dir.display());
    }
    let count = |v: Verdict| cases.iter().filter(|c| c.verdict == v).count();
    let (failed, info) = (count(Verdict::Fail), count(Verdict::Info));
    println!(
        "{} cases, {} passed, {} failed, {} reported (info)",
        cases.len(),
        cases.len() - failed - info,
        failed,
        info
    );
    let missing_945 = data.steel_945().is_none();
    let missing_304l = data.ss304l_set().is_none();
    if missing_945 || missing_304l {
        println!(
            "note: the real-data rows did not run ({}): the shared data folder {} is not there",
            [
                (missing_945, "945 SHPB pairs"),
                (missing_304l, "304L leave-one-rate-out")
            ]
            .iter()
            .filter(|(missing, _)| *missing)
            .map(|(_, rows)| *rows)
            .collect::<Vec<_>>()
            .join(", "),
            data.shared_root().display()
        );
        if args.require_data {
            bail!("--require-data: the real-data rows did not run");
        }
    }
    if failed > 0 {
        bail!("{failed} verification case(s) failed");
    }
    Ok(())
}
