//! `mpw export --params report.toml [MATERIAL] --format abaqus|lsdyna|json --units SYSTEM`:
//! write a Johnson-Cook parameter set for another code (`fitting::export`). With a fit
//! report, the report's final parameters on the material it names, and the fit's covered
//! ranges and warnings (`fitting::fit::reports::origin`) as comment lines of the card and
//! on stderr; a material file given beside the report must hold the values the report
//! kept fixed. Without a report, the material file's own values.

use anyhow::{bail, Result};
use fitting::export::{abaqus, json, lsdyna, units, Provenance};
use fitting::fit::levels::model::Material;
use fitting::fit::reports::origin::FitOrigin;
use fitting::fit::reports::report::read_parameters;
use materials::material::Model;
use materials::AnyModel;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Material file (Johnson-Cook); with --params optional (the report names its material),
    /// and when given it must hold the values the fit kept fixed.
    pub material: Option<PathBuf>,
    /// A fit report (report.toml) whose final parameters the card carries.
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

fn johnson_cook(file: &Path) -> Result<Material> {
    match materials::load_material(file)?.model {
        AnyModel::ElastoPlastic(m) if m.flow.as_johnson_cook().is_some() => Ok(m),
        AnyModel::ElastoPlastic(m) => bail!(
            "{}: the flow-stress law is {}: `mpw export` writes Johnson-Cook cards, which cannot carry it",
            file.display(),
            m.flow.describe()
        ),
        _ => bail!("{}: the material must be Johnson-Cook", file.display()),
    }
}

/// Every parameter the fit kept fixed must have the same value in `given` as in the
/// report's material `fitted`: else the card would mix two materials.
fn check_same_material(
    given: &Path,
    base: &Material,
    fitted: &Material,
    origin: &FitOrigin,
) -> Result<()> {
    let differ: Vec<String> = base
        .param_names()
        .iter()
        .filter(|n| !origin.fitted.iter().any(|f| f == *n))
        .filter_map(|n| {
            let (a, b) = (base.param(n)?, fitted.param(n)?);
            let same = (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
            (!same).then(|| format!("`{n}` = {a:e} in the file, {b:e} in the report"))
        })
        .collect();
    if !differ.is_empty() {
        bail!(
            "{}: not the material of the fit {} ({}): {}\nhint: leave the material out (the report names its own) or give the file the fit used",
            given.display(),
            origin.report.display(),
            origin.material_file.display(),
            differ.join("; ")
        );
    }
    Ok(())
}

/// The material to write, where it comes from, and its default name.
fn material(args: &Args) -> Result<(Material, Provenance, String)> {
    let stem = |file: &Path| {
        file.file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .to_uppercase()
    };
    let Some(report) = &args.params else {
        let Some(file) = &args.material else {
            bail!("nothing to export: give a fit report (--params report.toml) or a material file");
        };
        let about = Provenance::named(&file.display().to_string());
        return Ok((johnson_cook(file)?, about, stem(file)));
    };
    let origin = FitOrigin::read(report)?;
    let base = match &args.material {
        Some(file) => johnson_cook(file)?,
        None => johnson_cook(&origin.material_file).map_err(|e| {
            anyhow::anyhow!("{e}\nhint: the report {} names this material file; give the material file after `export`", report.display())
        })?,
    };
    let fitted = read_parameters(&base, report)?;
    if let Some(file) = &args.material {
        check_same_material(file, &base, &fitted, &origin)?;
    }
    let about = Provenance {
        source: format!(
            "{} with the fit {}",
            origin.material_file.display(),
            report.display()
        ),
        caveats: origin.caveats(),
    };
    if origin.has_warnings() {
        for caveat in about.caveats.iter().filter(|c| c.starts_with("WARNING")) {
            eprintln!("warning: {}", &caveat["WARNING: ".len()..]);
        }
    }
    eprintln!("note: {}", origin.coverage());
    let name = origin.material_name.replace(' ', "_").to_uppercase();
    Ok((fitted, about, name))
}

pub fn run(args: Args) -> Result<()> {
    let units = units(&args.units)?;
    let (material, about, default_name) = material(&args)?;
    let name = args.name.clone().unwrap_or(default_name);
    let card = match args.format.as_str() {
        "abaqus" => abaqus(&material, &name, &about, &units)?,
        "lsdyna" => lsdyna(&material, &name, &about, &units, args.id)?,
        "json" => json(&material, &name, &about, &units)?,
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
