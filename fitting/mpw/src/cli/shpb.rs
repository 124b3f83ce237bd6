//! `mpw shpb EXPERIMENT.toml|FOLDER [--out DIR]`: process an SHPB record; write the face
//! histories as CSV (`shpb.csv`, compression positive, units in the column names), charts
//! of the pulses, forces, strain rate, stress-strain curve and equilibrium ratio, and
//! print a summary: whether the test held a constant rate, the histories across the
//! plateau, and every processing's shifts, equilibrium and F1 oscillation. A folder
//! processes every SHPB TOML in it (sorted by name), each into its own subfolder, and
//! writes one table of all (`summary.csv`, also printed): plateau rate, final strain,
//! true flow stress at fixed true strains, median equilibrium ratio over the plateau, rate
//! trend and the constant-rate verdict. A record that cannot be processed is listed with
//! its error; the run then exits 1.

use crate::charts::{LineChart, Series};
use anyhow::{Context, Result};
use fitting::experiment::ShpbExperiment;
use fitting::shpb::plateau::{MIN_IN_BAND, TOLERANCE as PLATEAU_TOLERANCE};
use fitting::shpb::pulses::smoothing_width;
use fitting::shpb::signal::moving_average;
use fitting::shpb::{analyze, analyze_with, Alignment, Processing, ShpbAnalysis};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Experiment TOML of kind "shpb", or a folder of them.
    pub experiment: PathBuf,
    /// Output folder (default: out/shpb/<experiment file or folder stem>).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

pub fn run(args: Args) -> Result<()> {
    let out = args.out.unwrap_or_else(|| {
        let stem = args.experiment.file_stem().unwrap_or_default();
        Path::new("out/shpb").join(stem)
    });
    if args.experiment.is_dir() {
        return run_folder(&args.experiment, &out);
    }
    let (exp, a) = process(&args.experiment, &out)?;
    summary(&exp, &a);
    alignments(&exp);
    println!("wrote {}/shpb.csv and charts", out.display());
    Ok(())
}

/// Load, analyze and write one record into `out`.
fn process(toml_file: &Path, out: &Path) -> Result<(ShpbExperiment, ShpbAnalysis)> {
    let exp = ShpbExperiment::load(toml_file)?;
    let a = analyze(&exp)?;
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    a.write_csv(&out.join("shpb.csv"))?;
    charts(&a, out)?;
    Ok((exp, a))
}

/// True strains at which the folder table gives the true flow stress.
const TABLE_STRAINS: [f64; 3] = [0.05, 0.10, 0.15];

/// Every SHPB TOML of `folder`, each into `out/<stem>`, and the table of all.
fn run_folder(folder: &Path, out: &Path) -> Result<()> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(folder)
        .with_context(|| format!("cannot read {}", folder.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    if files.is_empty() {
        anyhow::bail!("{}: no experiment TOML in this folder", folder.display());
    }
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let strains: Vec<String> = TABLE_STRAINS
        .iter()
        .map(|e| format!("true_stress_at_{e}_pa"))
        .collect();
    let mut csv = format!(
        "record,plateau_rate_per_s,final_strain,{},median_r,rate_trend_start_per_s,rate_trend_end_per_s,in_band_fraction,constant_rate,error\n",
        strains.join(",")
    );
    let head: String = TABLE_STRAINS
        .iter()
        .map(|e| format!(" {:>12}", format!("σ({e:.2}) MPa")))
        .collect();
    println!(
        "{:<12} {:>10} {:>8}{head} {:>9} {:>16} {:>8}",
        "record", "rate 1/s", "ε final", "median R", "trend 1/s", "in band"
    );
    let mut failed = 0;
    for file in &files {
        let stem = file
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        match process(file, &out.join(&stem)) {
            Ok((_, a)) => {
                let row = TableRow::of(&a);
                let cells: String = row
                    .stress_pa
                    .iter()
                    .map(|s| format!(" {:>12}", fixed(s.map(|v| v * 1e-6), 1)))
                    .collect();
                let q = &a.plateau;
                println!(
                    "{stem:<12} {:>10.1} {:>8.4}{cells} {:>9.3} {:>16} {:>7.0}%{}",
                    row.rate,
                    row.final_strain,
                    row.median_r,
                    format!("{:.0} -> {:.0}", q.rate_trend_per_s.0, q.rate_trend_per_s.1),
                    100.0 * q.in_band_fraction,
                    if q.is_constant_rate() {
                        ""
                    } else {
                        " no constant-rate plateau"
                    }
                );
                let stresses: Vec<String> = row
                    .stress_pa
                    .iter()
                    .map(|s| s.map_or(String::new(), |v| format!("{v:e}")))
                    .collect();
                csv += &format!(
                    "{stem},{},{},{},{},{},{},{},{},\n",
                    row.rate,
                    row.final_strain,
                    stresses.join(","),
                    row.median_r,
                    a.plateau.rate_trend_per_s.0,
                    a.plateau.rate_trend_per_s.1,
                    a.plateau.in_band_fraction,
                    a.plateau.is_constant_rate()
                );
            }
            Err(e) => {
                failed += 1;
                println!("{stem:<12} failed: {e:#}");
                csv += &format!(
                    "{stem},,,{},,,,,,\"{}\"\n",
                    ",".repeat(TABLE_STRAINS.len() - 1),
                    format!("{e:#}").replace('"', "'")
                );
            }
        }
    }
    println!("R: equilibrium ratio 2|F1 − F2|/|F1 + F2|, median over the plateau; σ: true 3-wave stress at that true strain on loading (- if not reached); trend: least-squares line through the rate across the plateau, start -> end; in band: share of the loading phase within ±{:.0} % of the plateau rate ({:.0} % needed for a constant-rate plateau)", 100.0 * PLATEAU_TOLERANCE, 100.0 * MIN_IN_BAND);
    std::fs::write(out.join("summary.csv"), csv)?;
    println!(
        "wrote {}/summary.csv and one folder per record",
        out.display()
    );
    if failed > 0 {
        anyhow::bail!(
            "{failed} of {} records could not be processed (listed above)",
            files.len()
        );
    }
    Ok(())
}

/// Each alignment's shifts, with and without the dispersion correction (when the bar's
/// Poisson ratio is known), and the equilibrium and rate they give (the record is
/// processed as its TOML asks).
fn alignments(exp: &ShpbExperiment) {
    println!(
        "  processing                  reflected δ  transmitted δ  median R  F1 osc.  plateau rate"
    );
    let corrections: &[bool] = if exp.bar.poisson_ratio.is_some() {
        &[false, true]
    } else {
        &[false]
    };
    for &dispersion in corrections {
        for alignment in Alignment::ALL {
            let processing = Processing {
                alignment,
                dispersion,
                ..exp.processing
            };
            match analyze_with(exp, processing) {
                Ok(a) => println!(
                    "  {:<27} {:>+9.2} µs   {:>+9.2} µs   {:>7.3}   {:>5.1} %  {:>8.1} 1/s{}",
                    processing.to_string(),
                    a.shifts.reflected_s * 1e6,
                    a.shifts.transmitted_s * 1e6,
                    a.median_equilibrium_ratio(),
                    100.0 * a.force_front_oscillation(),
                    a.plateau.strain_rate_3wave_per_s,
                    if processing == exp.processing {
                        "  (used)"
                    } else {
                        ""
                    }
                ),
                Err(e) => println!("  {processing:<27} failed: {e}"),
            }
        }
    }
}

fn fixed(v: Option<f64>, decimals: usize) -> String {
    v.map_or("-".into(), |x| format!("{x:.decimals$}"))
}

/// One line of the folder table.
struct TableRow {
    rate: f64,
    final_strain: f64,
    /// True 3-wave stress at `TABLE_STRAINS` on loading [Pa], `None` where not reached.
    stress_pa: Vec<Option<f64>>,
    median_r: f64,
}

impl TableRow {
    fn of(a: &ShpbAnalysis) -> TableRow {
        let q = &a.plateau;
        let peak = (0..a.true_strain.len())
            .max_by(|&i, &j| a.true_strain[i].total_cmp(&a.true_strain[j]))
            .unwrap_or(0);
        let loading = &a.true_strain[..=peak];
        let stress_pa = TABLE_STRAINS
            .iter()
            .map(|&e| {
                let k = loading.iter().position(|&x| x >= e).filter(|&k| k > 0)?;
                let w = (e - loading[k - 1]) / (loading[k] - loading[k - 1]);
                let s = &a.true_stress_pa;
                Some(s[k - 1] + w * (s[k] - s[k - 1]))
            })
            .collect();
        TableRow {
            rate: q.strain_rate_3wave_per_s,
            final_strain: a.strain.iter().cloned().fold(0.0, f64::max),
            stress_pa,
            median_r: a.median_equilibrium_ratio(),
        }
    }
}

fn charts(a: &ShpbAnalysis, out: &Path) -> Result<()> {
    let t = &a.time_s;
    let us = 1e6;
    let face = "time at the specimen faces since window start [µs]";
    LineChart::new(
        format!("{}: bar strains at the specimen faces", a.name),
        face,
        "bar strain, compression positive [µε]",
    )
    .with(Series::scaled("incident ε_i", t, &a.incident, us, 1e6))
    .with(Series::scaled("reflected ε_r", t, &a.reflected, us, 1e6))
    .with(Series::scaled(
        "transmitted ε_t",
        t,
        &a.transmitted,
        us,
        1e6,
    ))
    .write_png(&out.join("pulses.png"))?;
    LineChart::new(
        format!("{}: face forces", a.name),
        face,
        "force, compression positive [kN]",
    )
    .with(Series::scaled(
        "F1 = E A (ε_i + ε_r)",
        t,
        &a.force_front_n,
        us,
        1e-3,
    ))
    .with(Series::scaled("F2 = E A ε_t", t, &a.force_back_n, us, 1e-3))
    .write_png(&out.join("forces.png"))?;
    LineChart::new(
        format!("{}: strain rate", a.name),
        face,
        "strain rate, compression positive [1/s]",
    )
    .with(Series::scaled(
        "3-wave",
        t,
        &a.strain_rate_3wave_per_s,
        us,
        1.0,
    ))
    .with(Series::scaled(
        "1-wave (reflected)",
        t,
        &a.strain_rate_1wave_per_s,
        us,
        1.0,
    ))
    .write_png(&out.join("strain_rate.png"))?;
    let e = &a.strain;
    LineChart::new(
        format!("{}: stress-strain", a.name),
        "strain, compression positive [-]",
        "stress, compression positive [MPa]",
    )
    .with(Series::scaled(
        "3-wave engineering",
        e,
        &a.stress_3wave_pa,
        1.0,
        1e-6,
    ))
    .with(Series::scaled(
        "1-wave (back face) engineering",
        e,
        &a.stress_1wave_pa,
        1.0,
        1e-6,
    ))
    .with(Series::scaled(
        "2-wave (front face) engineering",
        e,
        &a.stress_2wave_pa,
        1.0,
        1e-6,
    ))
    .with(Series::scaled(
        "3-wave true (vs true strain)",
        &a.true_strain,
        &a.true_stress_pa,
        1.0,
        1e-6,
    ))
    .write_png(&out.join("stress_strain.png"))?;
    let on = a.plateau.range.clone();
    LineChart::new(
        format!("{}: equilibrium over the plateau", a.name),
        face,
        "R = 2|F1 − F2| / |F1 + F2| [-]",
    )
    .with(Series::scaled(
        "R",
        &t[on.clone()],
        &a.equilibrium_ratio[on],
        us,
        1.0,
    ))
    .write_png(&out.join("equilibrium.png"))?;
    Ok(())
}

fn summary(exp: &ShpbExperiment, a: &ShpbAnalysis) {
    let p = &a.pulses;
    let q = &a.plateau;
    let dt = a.time_s[1] - a.time_s[0];
    println!("{}  ({})", a.name, exp.data_file.display());
    for note in &exp.notes {
        println!("  note: {note}");
    }
    let source = match exp.bar.incident_delay_calibrated_s.is_some()
        || exp.bar.transmitted_delay_calibrated_s.is_some()
    {
        true => "as calibrated where stated, else distance / c0",
        false => "distance / c0",
    };
    println!(
        "  bar c0 {:.1} m/s, delays gauge→face {:.2} µs (incident), {:.2} µs (transmitted), {source}",
        exp.bar.wave_speed_m_per_s(),
        p.delay_incident_s * 1e6,
        p.delay_transmitted_s * 1e6
    );
    println!(
        "  baselines {:.2} / {:.2} µε, noise {:.2} / {:.2} µε (incident / transmitted gauge)",
        p.baseline_incident * 1e6,
        p.baseline_transmitted * 1e6,
        p.noise_incident * 1e6,
        p.noise_transmitted * 1e6
    );
    println!(
        "  incident pulse {:.1} µε, at the gauge {:.2} .. {:.2} µs; arrival offsets (measured − predicted): reflected {:+.2} µs, transmitted {:+.2} µs",
        p.incident_amplitude * 1e6,
        p.incident_at_gauge_s.0 * 1e6,
        p.incident_at_gauge_s.1 * 1e6,
        p.reflected_arrival_offset_s * 1e6,
        p.transmitted_arrival_offset_s * 1e6
    );
    let (label, caveat) = if q.is_constant_rate() {
        ("plateau", "")
    } else {
        ("window", " (means over a changing rate)")
    };
    println!(
        "  {label} {:.1} .. {:.1} µs (strain {:.4} .. {:.4}): strain rate {:.1} 1/s (3-wave), {:.1} 1/s (1-wave){caveat}",
        q.range.start as f64 * dt * 1e6,
        (q.range.end - 1) as f64 * dt * 1e6,
        a.strain[q.range.start],
        a.strain[q.range.end - 1],
        q.strain_rate_3wave_per_s,
        q.strain_rate_1wave_per_s
    );
    println!(
        "  {label} stress (3-wave, engineering) {:.1} MPa, equilibrium ratio R = 2|F1 − F2|/|F1 + F2| median {:.3}, mean {:.3}",
        q.stress_3wave_pa / 1e6,
        a.median_equilibrium_ratio(),
        q.equilibrium_ratio
    );
    let verdict = if q.is_constant_rate() {
        "a constant-rate plateau"
    } else {
        "NO constant-rate plateau: read the histories, not the means"
    };
    println!(
        "  {:.0} % of the loading phase within ±{:.0} % of {:.1} 1/s (at least {:.0} % needed): {verdict}; rate trend across the {label} {:.1} -> {:.1} 1/s ({:+.0} %)",
        100.0 * q.in_band_fraction,
        100.0 * PLATEAU_TOLERANCE,
        q.median_rate_per_s,
        100.0 * MIN_IN_BAND,
        q.rate_trend_per_s.0,
        q.rate_trend_per_s.1,
        100.0 * q.rate_change()
    );
    histories(a);
}

/// Rate, strain, stress and equilibrium across the plateau (or window) at every tenth of
/// it, on the 1 µs averages: the time-resolved account of the test.
fn histories(a: &ShpbAnalysis) {
    let range = a.plateau.range.clone();
    let width = smoothing_width(a.time_s[1] - a.time_s[0]);
    let [rate, stress, ratio] = [
        &a.strain_rate_3wave_per_s,
        &a.true_stress_pa,
        &a.equilibrium_ratio,
    ]
    .map(|v| moving_average(v, width));
    println!("     t µs   rate 1/s   true ε   true σ MPa       R");
    for tenth in 0..=10 {
        let k = range.start + tenth * (range.len() - 1) / 10;
        println!(
            "  {:>7.1} {:>10.1} {:>8.4} {:>12.1} {:>7.3}",
            a.time_s[k] * 1e6,
            rate[k],
            a.true_strain[k],
            stress[k] / 1e6,
            ratio[k]
        );
    }
}
