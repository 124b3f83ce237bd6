//! `mpw synth`: write a synthetic experiment set (quasi-static tension + SHPB at room and
//! elevated temperature) from a stated parameter set, noise level and seed; the truth is
//! in every file header. The defaults write the shipped `data/experiments/` set again,
//! into `out/synth` (the shipped files are only rewritten when `--out` names them).
//! `--shpb-3d FILE` writes instead the data of `verify`'s MPM-level synthetic (F2 of the
//! 3D quarter SHPB model with its truth, minutes); `data/experiments/mpm_synthetic_f2.csv`
//! is the shipped one.

use anyhow::{bail, Result};
use fitting::fit::synthetic::synth::{write_set, SynthSpec};
use materials::AnyModel;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material parameter file with the true parameters.
    #[arg(long, default_value = "data/materials/42crmo4_qt660.toml")]
    pub material: PathBuf,
    /// Output folder (experiments and the `default.toml` set); `--out data/experiments`
    /// regenerates the shipped set.
    #[arg(long, default_value = "out/synth")]
    pub out: PathBuf,
    /// Noise standard deviation as a fraction of each channel's peak.
    #[arg(long, default_value_t = 0.01)]
    pub noise: f64,
    /// Seed of the noise generator.
    #[arg(long, default_value_t = 42)]
    pub seed: u64,
    /// SHPB nominal strain rate [1/s].
    #[arg(long, default_value_t = 2660.0)]
    pub rate: f64,
    /// SHPB start temperatures [K], comma separated.
    #[arg(long, value_delimiter = ',', default_value = "293.15,573.15")]
    pub temperatures: Vec<f64>,
    /// Instead of the set: write F2 of the 3D quarter SHPB model with the MPM-level
    /// synthetic's truth (the data of verify's `fit/mpm-synthetic` rows) to this CSV;
    /// `data/experiments/mpm_synthetic_f2.csv` is the shipped file. Takes minutes.
    #[arg(long, conflicts_with_all = ["material", "out", "noise", "seed", "rate", "temperatures"])]
    pub shpb_3d: Option<PathBuf>,
}

/// `--shpb-3d`: the MPM-level synthetic's data, its truth from `data/materials` under the
/// working directory (the repository root).
fn write_shpb_3d(file: &std::path::Path) -> Result<()> {
    use crate::verify::{data::VerifyData, fit::synthetic_945_truth};
    use fitting::fit::synthetic::{mpm_synthetic, synthetic_data};
    let truth = synthetic_945_truth(&VerifyData::new("data"))?;
    let at = (mpm_synthetic::DATA, mpm_synthetic::KERNEL);
    eprintln!("running the {} model with {} (minutes)", at.0, at.1.name());
    let f2 = mpm_synthetic::data(&truth, at.0, at.1)?;
    synthetic_data::write(file, &f2, &truth, at)?;
    println!("wrote {}", file.display());
    Ok(())
}

pub fn run(args: Args) -> Result<()> {
    if let Some(file) = &args.shpb_3d {
        return write_shpb_3d(file);
    }
    if !(args.noise >= 0.0 && args.noise < 1.0) {
        bail!("--noise {}: expected a fraction in [0, 1)", args.noise);
    }
    let file = materials::load_material(&args.material)?;
    let AnyModel::ElastoPlastic(material) = file.model else {
        bail!(
            "{}: synthetic data needs a Johnson-Cook material",
            args.material.display()
        );
    };
    let out_abs = std::path::absolute(&args.out)?;
    let mat_abs = std::path::absolute(&args.material)?;
    let material_ref = match (out_abs.parent(), mat_abs.parent()) {
        (Some(o), Some(m)) if m == o.join("materials") => {
            format!(
                "../materials/{}",
                mat_abs.file_name().unwrap().to_string_lossy()
            )
        }
        _ => mat_abs.display().to_string(),
    };
    write_set(
        &args.out,
        &SynthSpec {
            material: &material,
            material_name: &file.name,
            material_ref: &material_ref,
            noise: args.noise,
            seed: args.seed,
            shpb_rate: args.rate,
            shpb_temperatures: &args.temperatures,
        },
    )?;
    println!(
        "wrote synthetic experiments and {}",
        args.out.join("default.toml").display()
    );
    Ok(())
}
