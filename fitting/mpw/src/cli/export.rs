//! `mpw export --params report.toml [MATERIAL] --format abaqus|lsdyna|json --units SYSTEM`:
//! write a Johnson-Cook parameter set for another code (`fitting::export`);
//! `--format abaqus-table|lsdyna-table` writes any law as a table
//! (`fitting::tabulated_cards`). With a fit
//! report, the report's final parameters on the material it names, and the fit's covered
//! ranges and warnings (`fitting::fit::reports::origin`) as comment lines of the card and
//! on stderr; a material file given beside the report must hold the values the report
//! kept fixed. Without a report, the material file's own values.

use anyhow::{bail, Result};
use fitting::export::{abaqus, json, lsdyna, units, Provenance};
use fitting::fit::levels::model::Material;
use fitting::fit::reports::origin::FitOrigin;
use fitting::fit::reports::report::read_parameters;
use fitting::flow_table::TableRange;
use fitting::tabulated_cards::{abaqus_table, lsdyna_table};
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
    /// Card format: abaqus, lsdyna (*MAT_JOHNSON_COOK with its *EOS_LINEAR_POLYNOMIAL) or
    /// json for a Johnson-Cook law; abaqus-table (*PLASTIC, RATE= blocks) or lsdyna-table
    /// (*MAT_PIECEWISE_LINEAR_PLASTICITY with a *DEFINE_TABLE of curves) for any law.
    #[arg(long, default_value = "abaqus")]
    pub format: String,
    /// Tables: the largest plastic strain sampled.
    #[arg(long, default_value_t = 2.0)]
    pub max_strain: f64,
    /// Tables: the lowest and highest positive plastic strain rate [1/s], `MIN,MAX`; the
    /// table starts at rate 0.
    #[arg(long, default_value = "1e-4,1e5", value_name = "MIN,MAX")]
    pub rates: String,
    /// Tables: the temperature range [K], `MIN,MAX` (default: θ0 to θm for a law that
    /// softens in abaqus-table, θ0 alone otherwise; lsdyna-table takes one temperature).
    #[arg(long, value_name = "MIN,MAX")]
    pub temperatures: Option<String>,
    /// Tables: the largest error of the interpolated table as a fraction of the cold flow
    /// stress.
    #[arg(long, default_value_t = 5e-3)]
    pub tolerance: f64,
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

fn elasto_plastic(file: &Path) -> Result<Material> {
    match materials::load_material(file)?.model {
        AnyModel::ElastoPlastic(m) => Ok(m),
        _ => bail!(
            "{}: the material must be elasto-plastic (Johnson-Cook or a composed law)",
            file.display()
        ),
    }
}

/// The formats that write Johnson-Cook parameters rather than a table.
const JOHNSON_COOK_FORMATS: [&str; 3] = ["abaqus", "lsdyna", "json"];

/// Refuse a law a Johnson-Cook card cannot carry, naming the file it came from.
fn johnson_cook_card_carries(args: &Args, m: &Material, file: &Path) -> Result<()> {
    if JOHNSON_COOK_FORMATS.contains(&args.format.as_str()) && m.flow.as_johnson_cook().is_none() {
        bail!(
            "{}: the flow-stress law is {}: a Johnson-Cook card (--format {}) cannot carry it; --format abaqus-table or lsdyna-table writes it as a table",
            file.display(),
            m.flow.describe(),
            args.format
        );
    }
    Ok(())
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
        let m = elasto_plastic(file)?;
        johnson_cook_card_carries(args, &m, file)?;
        return Ok((m, about, stem(file)));
    };
    let origin = FitOrigin::read(report)?;
    let base = match &args.material {
        Some(file) => elasto_plastic(file)?,
        None => elasto_plastic(&origin.material_file).map_err(|e| {
            anyhow::anyhow!("{e}\nhint: the report {} names this material file; give the material file after `export`", report.display())
        })?,
    };
    johnson_cook_card_carries(args, &base, &origin.material_file)?;
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

/// `MIN,MAX` of option `name` as two numbers.
fn pair(name: &str, text: &str) -> Result<[f64; 2]> {
    let values: Vec<f64> = (text.split(','))
        .map(|v| v.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|e| anyhow::anyhow!("--{name} \"{text}\": {e}; expected MIN,MAX"))?;
    match values[..] {
        [lo, hi] => Ok([lo, hi]),
        [one] if name == "temperatures" => Ok([one, one]),
        _ => bail!("--{name} \"{text}\": expected two numbers MIN,MAX"),
    }
}

impl Args {
    /// The sampling of a tabulated card for `m`.
    fn table(&self, m: &Material) -> Result<TableRange> {
        let theta0 = m.param("theta0").expect("an elasto-plastic material");
        let theta_m = m.param("theta_m");
        let temperatures = match (&self.temperatures, theta_m) {
            (Some(text), _) => pair("temperatures", text)?,
            (None, Some(theta_m)) if self.format == "abaqus-table" => [theta0, theta_m],
            (None, _) => [theta0, theta0],
        };
        if self.format == "lsdyna-table" && temperatures[0] != temperatures[1] {
            bail!("--temperatures: *MAT_024 has no thermal softening; give one temperature (--temperatures {theta0}) for lsdyna-table");
        }
        Ok(TableRange {
            strain_max: self.max_strain,
            rates: pair("rates", &self.rates)?,
            temperatures,
            tolerance: self.tolerance,
        })
    }
}

pub fn run(args: Args) -> Result<()> {
    let units = units(&args.units)?;
    let (material, about, default_name) = material(&args)?;
    let name = args.name.clone().unwrap_or(default_name);
    let card = match args.format.as_str() {
        "abaqus" => abaqus(&material, &name, &about, &units)?,
        "lsdyna" => lsdyna(&material, &name, &about, &units, args.id)?,
        "json" => json(&material, &name, &about, &units)?,
        "abaqus-table" => abaqus_table(&material, &name, &about, &units, &args.table(&material)?)?,
        "lsdyna-table" => {
            let range = args.table(&material)?;
            lsdyna_table(&material, &name, &about, &units, args.id, &range)?
        }
        other => bail!("--format \"{other}\": expected \"abaqus\", \"lsdyna\", \"json\", \"abaqus-table\" or \"lsdyna-table\""),
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
