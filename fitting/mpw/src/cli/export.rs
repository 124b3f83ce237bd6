//! `mpw export MATERIAL [--params report.toml] --format abaqus|lsdyna|json --units SYSTEM`: write a
//! Johnson-Cook parameter set for another code (`fitting::export`): the material file's
//! values, with a fit report's `final_parameters` applied when `--params` is given.

use anyhow::{bail, Result};
use fitting::export::{abaqus, json, lsdyna, units};
use fitting::fit::reports::report::read_parameters;
use materials::AnyModel;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material file (Johnson-Cook) with the elastic and thermal constants.
    pub material: PathBuf,
    /// A fit report whose final parameters replace the material file's.
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// Card format: abaqus, lsdyna (*MAT_JOHNSON_COOK with its *EOS_LINEAR_POLYNOMIAL) or json.
    #[arg(long, default_value = "abaqus")]
    pub format: String,
    /// Unit system: si, mm-s-tonne (N, MPa) or mm-ms-kg (kN, GPa).
    #[arg(long, default_value = "si")]
    pub units: String,
    /// Material and equation-of-state identifier of an LS-DYNA card.
    #[arg(long, default_value_t = 1)]
    pub id: u32,
    /// Material name in the card (default: the material file's stem).
    #[arg(long)]
    pub name: Option<String>,
    /// Output file (default: standard output).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

pub fn run(args: Args) -> Result<()> {
    let units = units(&args.units)?;
    let base = match materials::load_material(&args.material)?.model {
        AnyModel::ElastoPlastic(m) => m,
        _ => bail!(
            "{}: the material must be Johnson-Cook",
            args.material.display()
        ),
    };
    let material = match &args.params {
        Some(report) => read_parameters(&base, report)?,
        None => base,
    };
    let source = match &args.params {
        Some(report) => format!(
            "{} with the fit {}",
            args.material.display(),
            report.display()
        ),
        None => args.material.display().to_string(),
    };
    let stem = args
        .material
        .file_stem()
        .unwrap_or_default()
        .to_string_lossy();
    let name = args.name.clone().unwrap_or_else(|| stem.to_uppercase());
    let card = match args.format.as_str() {
        "abaqus" => abaqus(&material, &name, &source, &units)?,
        "lsdyna" => lsdyna(&material, &name, &source, &units, args.id)?,
        "json" => json(&material, &name, &source, &units)?,
        other => bail!("--format \"{other}\": expected \"abaqus\", \"lsdyna\" or \"json\""),
    };
    match &args.out {
        Some(file) => {
            std::fs::write(file, &card)?;
            eprintln!(
                "{} card in {} ({})",
                args.format,
                file.display(),
                units.description
            );
        }
        None => print!("{card}"),
    }
    Ok(())
}
