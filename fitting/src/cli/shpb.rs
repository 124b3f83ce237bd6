//! `mpw shpb EXPERIMENT.toml [--out DIR]`: process an SHPB record; write the face
//! histories as CSV (`shpb.csv`, compression positive, units in the column names), charts
//! of the pulses, forces, strain rate and stress-strain curve, and print a summary.

use crate::chart::{LineChart, Series};
use crate::experiment::ShpbExperiment;
use crate::shpb::{analyze, ShpbAnalysis};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Experiment TOML of kind "shpb".
    pub experiment: PathBuf,
    /// Output folder (default: out/shpb/<experiment file stem>).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

pub fn run(args: Args) -> Result<()> {
    let exp = ShpbExperiment::load(&args.experiment)?;
    let a = analyze(&exp)?;
    let out = args.out.unwrap_or_else(|| {
        let stem = args.experiment.file_stem().unwrap_or_default();
        Path::new("out/shpb").join(stem)
    });
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    a.write_csv(&out.join("shpb.csv"))?;
    charts(&a, &out)?;
    summary(&exp, &a);
    println!("wrote {}/shpb.csv and charts", out.display());
    Ok(())
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
    println!(
        "  plateau {:.1} .. {:.1} µs (strain {:.4} .. {:.4}): strain rate {:.1} 1/s (3-wave), {:.1} 1/s (1-wave)",
        q.range.start as f64 * dt * 1e6,
        (q.range.end - 1) as f64 * dt * 1e6,
        a.strain[q.range.start],
        a.strain[q.range.end - 1],
        q.strain_rate_3wave_per_s,
        q.strain_rate_1wave_per_s
    );
    println!(
        "  plateau stress (3-wave, engineering) {:.1} MPa, mean equilibrium ratio R = 2|F1 − F2|/|F1 + F2| {:.3}",
        q.stress_3wave_pa / 1e6,
        q.equilibrium_ratio
    );
}
