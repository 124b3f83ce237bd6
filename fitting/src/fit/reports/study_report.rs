//! Reports of the studies around a fit: the bootstrap over records (`bootstrap.toml`) and
//! leave-one-group-out cross-validation (`cross_validation.toml`), each as a terminal
//! table and a TOML file.

use crate::fit::reports::report::show;
use crate::fit::sets::fit_set::FitSet;
use crate::fit::statistics::bootstrap::Bootstrap;
use crate::fit::statistics::cross_validation::Fold;
use anyhow::Result;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

#[derive(Serialize)]
struct IntervalRow {
    name: String,
    optimum: f64,
    bootstrap_mean: f64,
    bootstrap_sd: f64,
    lo95: f64,
    hi95: f64,
    jtj_std_error: f64,
    sd_over_jtj: f64,
}

#[derive(Serialize)]
struct BandRow {
    group: String,
    strain: Vec<f64>,
    model_mean_lo95: Vec<f64>,
    model_mean_hi95: Vec<f64>,
}

#[derive(Serialize)]
struct BootstrapFile {
    samples: usize,
    not_converged: usize,
    failed: usize,
    seed: u64,
    parameters: Vec<IntervalRow>,
    correlation: Vec<Vec<f64>>,
    bands: Vec<BandRow>,
    wall_time_s: f64,
}

pub fn bootstrap_table(b: &Bootstrap) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nBootstrap over records ({} samples, {} not converged, {} failed; {:.1} s):",
        b.samples, b.not_converged, b.failed, b.wall_s
    );
    let _ = writeln!(
        out,
        "  {:<6} {:>14} {:>30} {:>14} {:>14} {:>8}",
        "param", "optimum", "95 % interval", "bootstrap sd", "JᵀJ std error", "ratio"
    );
    for p in &b.params {
        let _ = writeln!(
            out,
            "  {:<6} {:>14} {:>30} {:>14} {:>14} {:>8.1}",
            p.name,
            show(&p.name, p.optimum),
            format!("[{}, {}]", show(&p.name, p.lo95), show(&p.name, p.hi95)),
            show(&p.name, p.sd),
            show(&p.name, p.jtj_std_error),
            p.sd / p.jtj_std_error
        );
    }
    let _ = writeln!(
        out,
        "  ratio = bootstrap sd / JᵀJ standard error: JᵀJ counts every sample as an independent measurement, the bootstrap resamples whole records"
    );
    out
}

pub fn write_bootstrap(dir: &Path, set: &FitSet, b: &Bootstrap) -> Result<()> {
    let file = BootstrapFile {
        samples: b.samples,
        not_converged: b.not_converged,
        failed: b.failed,
        seed: set.seed,
        parameters: b
            .params
            .iter()
            .map(|p| IntervalRow {
                name: p.name.clone(),
                optimum: p.optimum,
                bootstrap_mean: p.mean,
                bootstrap_sd: p.sd,
                lo95: p.lo95,
                hi95: p.hi95,
                jtj_std_error: p.jtj_std_error,
                sd_over_jtj: p.sd / p.jtj_std_error,
            })
            .collect(),
        correlation: b.correlation.clone(),
        bands: b
            .bands
            .iter()
            .map(|band| BandRow {
                group: band.group.clone(),
                strain: band.strain.clone(),
                model_mean_lo95: band.lo95.clone(),
                model_mean_hi95: band.hi95.clone(),
            })
            .collect(),
        wall_time_s: b.wall_s,
    };
    std::fs::create_dir_all(dir)?;
    std::fs::write(dir.join("bootstrap.toml"), toml::to_string(&file)?)?;
    Ok(())
}

#[derive(Serialize)]
struct FoldRow {
    left_out: String,
    records: usize,
    parameters: Vec<(String, f64)>,
    converged: bool,
    in_sample_rms_vs_mean_percent: f64,
    out_of_sample_rms_vs_mean_percent: f64,
    out_of_sample_rms_vs_records_percent: f64,
    cv_mean_percent: Option<f64>,
}

pub fn cross_validation_table(set: &FitSet, folds: &[Fold]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nLeave one group out (fit on the others, predict the one left out):"
    );
    let _ = writeln!(
        out,
        "  {:<26} {:>8} {:>12} {:>14} {:>16} {:>9}  parameters without it",
        "left out", "records", "in-sample %", "out-of-sample %", "vs records %", "CV %"
    );
    for f in folds {
        let values: Vec<String> = set
            .params
            .iter()
            .zip(&f.values)
            .map(|(p, &v)| format!("{} = {}", p.name, show(&p.name, v)))
            .collect();
        let _ = writeln!(
            out,
            "  {:<26} {:>8} {:>12.2} {:>14.2} {:>16.2} {:>9.2}  {}{}",
            f.left_out,
            f.out_of_sample.group.members.len(),
            100.0 * f.in_sample.rms_vs_mean,
            100.0 * f.out_of_sample.rms_vs_mean,
            100.0 * f.out_of_sample.rms_vs_records,
            100.0 * f.out_of_sample.cv_mean,
            values.join(", "),
            if f.converged { "" } else { " (NOT converged)" }
        );
    }
    let _ = writeln!(
        out,
        "  RMS against each group's mean curve, % of its mean stress; CV: the group's mean coefficient of variation"
    );
    out
}

pub fn write_cross_validation(dir: &Path, set: &FitSet, folds: &[Fold]) -> Result<()> {
    #[derive(Serialize)]
    struct File {
        folds: Vec<FoldRow>,
    }
    let rows = folds
        .iter()
        .map(|f| FoldRow {
            left_out: f.left_out.clone(),
            records: f.out_of_sample.group.members.len(),
            parameters: set
                .params
                .iter()
                .map(|p| p.name.clone())
                .zip(f.values.clone())
                .collect(),
            converged: f.converged,
            in_sample_rms_vs_mean_percent: 100.0 * f.in_sample.rms_vs_mean,
            out_of_sample_rms_vs_mean_percent: 100.0 * f.out_of_sample.rms_vs_mean,
            out_of_sample_rms_vs_records_percent: 100.0 * f.out_of_sample.rms_vs_records,
            cv_mean_percent: Some(100.0 * f.out_of_sample.cv_mean).filter(|c| c.is_finite()),
        })
        .collect();
    std::fs::create_dir_all(dir)?;
    std::fs::write(
        dir.join("cross_validation.toml"),
        toml::to_string(&File { folds: rows })?,
    )?;
    Ok(())
}
