//! `mpw drive`: one material point along a canned load path (uniaxial tension or
//! compression at constant true or engineering rate with an optional hold, simple
//! shear, or the SHPB specimen under a length history from a CSV file). Writes
//! `drive.csv` (time, Hencky strains, Cauchy stresses, α, θ) and a stress-strain chart.

use crate::charts::{LineChart, Series};
use anyhow::{bail, Context, Result};
use clap::ValueEnum;
use materials::driver::{self, LoadPath, RateKind, Temperature};
use materials::{load_material, Model};
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum PathKind {
    Tension,
    Compression,
    Shear,
    /// Uniaxial stress under the length history L/L0 of `--length-history`.
    Shpb,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum RateArg {
    True,
    Engineering,
}

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material parameter file.
    #[arg(long, default_value = "data/materials/42crmo4_qt660.toml")]
    pub material: PathBuf,
    /// Load path.
    #[arg(long, value_enum, default_value_t = PathKind::Tension)]
    pub path: PathKind,
    /// Strain rate [1/s] (shear: γ̇).
    #[arg(long, default_value_t = 1e-3)]
    pub rate: f64,
    /// Whether --rate and --strain are true (logarithmic) or engineering measures.
    #[arg(long, value_enum, default_value_t = RateArg::True)]
    pub rate_kind: RateArg,
    /// End strain magnitude (true or engineering as --rate-kind; shear: γ).
    #[arg(long, default_value_t = 0.3)]
    pub strain: f64,
    /// Hold at the end strain [s].
    #[arg(long, default_value_t = 0.0)]
    pub hold: f64,
    /// Driver steps of the loading ramp (a hold continues with the same step size).
    #[arg(long, default_value_t = 300)]
    pub steps: usize,
    /// Fixed temperature [K] (default: the material's reference temperature θ0).
    #[arg(long, conflicts_with = "adiabatic")]
    pub temperature: Option<f64>,
    /// Let the model heat adiabatically (Taylor-Quinney) instead of a fixed temperature.
    #[arg(long)]
    pub adiabatic: bool,
    /// CSV with columns `time_s,length_ratio` for `--path shpb`.
    #[arg(long)]
    pub length_history: Option<PathBuf>,
    /// Initial specimen diameter [m] for `--path shpb`: adds the force F = σ A0 L0/L.
    #[arg(long, default_value_t = 8e-3)]
    pub specimen_diameter: f64,
    /// Output folder for drive.csv and drive.png.
    #[arg(long, default_value = "out/drive")]
    pub out: PathBuf,
}

fn read_length_history(path: &PathBuf) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut reader =
        csv::Reader::from_path(path).with_context(|| format!("{}: cannot open", path.display()))?;
    let headers = reader.headers()?.clone();
    let col = |name: &str| {
        headers
            .iter()
            .position(|h| h.trim() == name)
            .with_context(|| format!("{}: missing column `{name}`", path.display()))
    };
    let (it, il) = (col("time_s")?, col("length_ratio")?);
    let (mut t, mut l) = (Vec::new(), Vec::new());
    for (k, row) in reader.records().enumerate() {
        let row = row?;
        let parse = |i: usize, name: &str| -> Result<f64> {
            let v: f64 = row.get(i).unwrap_or("").trim().parse().with_context(|| {
                format!(
                    "{}: line {}: column `{name}` is not a number",
                    path.display(),
                    k + 2
                )
            })?;
            if !v.is_finite() {
                bail!(
                    "{}: line {}: column `{name}` is not finite",
                    path.display(),
                    k + 2
                );
            }
            Ok(v)
        };
        t.push(parse(it, "time_s")?);
        l.push(parse(il, "length_ratio")?);
    }
    Ok((t, l))
}

/// The load path of the arguments; `theta0` is the material's reference temperature.
pub fn build_path(args: &Args, theta0: f64) -> Result<LoadPath> {
    let temperature = if args.adiabatic {
        Temperature::Adiabatic
    } else {
        Temperature::Prescribed(driver::Ramp::constant(args.temperature.unwrap_or(theta0)))
    };
    let kind = match args.rate_kind {
        RateArg::True => RateKind::True,
        RateArg::Engineering => RateKind::Engineering,
    };
    if !(args.rate > 0.0 && args.strain > 0.0 && args.steps > 0 && args.hold >= 0.0) {
        bail!("--rate and --strain must be > 0, --steps ≥ 1, --hold ≥ 0");
    }
    let path = match args.path {
        PathKind::Tension => LoadPath::uniaxial(
            kind,
            args.strain,
            args.rate,
            args.hold,
            args.steps,
            temperature,
        ),
        PathKind::Compression => LoadPath::uniaxial(
            kind,
            -args.strain,
            args.rate,
            args.hold,
            args.steps,
            temperature,
        ),
        PathKind::Shear => LoadPath::simple_shear(args.strain, args.rate, args.steps, temperature),
        PathKind::Shpb => {
            let file = args
                .length_history
                .as_ref()
                .context("--path shpb needs --length-history FILE")?;
            let (t, l) = read_length_history(file)?;
            LoadPath::shpb_specimen(t, l)
        }
    };
    Ok(path?)
}

/// σ_xx (or σ_xy for shear) and the von Mises stress against the Hencky strain.
fn stress_strain_chart(name: &str, args: &Args, records: &[driver::Record]) -> Result<LineChart> {
    let (i, j, label) = match args.path {
        PathKind::Shear => (0, 1, "xy"),
        _ => (0, 0, "xx"),
    };
    let strain: Vec<f64> = records.iter().map(|r| r.hencky_strain()[(i, j)]).collect();
    let stress: Vec<f64> = records.iter().map(|r| r.sigma[(i, j)]).collect();
    let von_mises: Vec<f64> = records
        .iter()
        .map(|r| materials::tensor::von_mises(&r.sigma))
        .collect();
    Ok(LineChart::new(
        format!("{name}: {:?} path", args.path),
        format!("Hencky strain ε_{label} [-]"),
        "Cauchy stress [MPa]",
    )
    .with(Series::scaled(
        format!("σ_{label}"),
        &strain,
        &stress,
        1.0,
        1e-6,
    ))
    .with(Series::scaled(
        "von Mises σ_VM",
        &strain,
        &von_mises,
        1.0,
        1e-6,
    )))
}

/// Refuse a fixed temperature the model cannot take (at or below 0 K, at or above θm), and
/// say when `--adiabatic` cannot heat (γ_TQ = 0).
fn check_temperature(args: &Args, model: &materials::AnyModel) -> Result<()> {
    let file = args.material.display();
    if let Some(theta) = args.temperature {
        if !(theta > 0.0) {
            bail!("--temperature {theta}: an absolute temperature in K must be above 0 K");
        }
        if let Some(theta_m) = model.param("theta_m").filter(|&tm| theta >= tm) {
            bail!("--temperature {theta} K is at or above the melting temperature θm = {theta_m} K of {file}: the flow stress is zero there");
        }
    }
    if args.adiabatic && model.param("gamma_tq") == Some(0.0) {
        eprintln!("warning: --adiabatic with gamma_tq = 0 in {file}: no plastic work turns into heat, the temperature stays at θ0");
    }
    Ok(())
}

pub fn run(args: Args) -> Result<()> {
    let material = load_material(&args.material)?;
    check_temperature(&args, &material.model)?;
    let path = build_path(&args, material.model.initial_state().theta)?;
    let records = driver::run(&material.model, &path)?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let csv = args.out.join("drive.csv");
    let area = match args.path {
        PathKind::Shpb => Some(std::f64::consts::PI * 0.25 * args.specimen_diameter.powi(2)),
        _ => None,
    };
    driver::write_csv(&csv, &records, area)?;
    let last = records.last().unwrap();
    println!(
        "{}: {} steps, final σ_xx = {:.1} MPa, σ_xy = {:.1} MPa, α = {:.4}, θ = {:.1} K",
        material.name,
        records.len() - 1,
        last.sigma[(0, 0)] / 1e6,
        last.sigma[(0, 1)] / 1e6,
        last.state.alpha,
        last.state.theta
    );
    let png = args.out.join("drive.png");
    stress_strain_chart(&material.name, &args, &records)?.write_png(&png)?;
    println!("wrote {} and {}", csv.display(), png.display());
    Ok(())
}
