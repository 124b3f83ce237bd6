//! `mpw predict SET [--params FILE]`: evaluate an experiment set with given parameters,
//! no optimizer. The parameters are the set's material with its `[fixed]` overrides, or
//! those of `--params`: a fit report (`report.toml`, its `final_parameters` applied to the
//! set's material) or a material file (used as it is). Same report, CSVs and charts as a
//! fit, including the specimen scatter of every group; `--validate` applies the fit's
//! validation to the prediction (every group within 5 % RMS of its mean curve).

use crate::cli::fit::validate;
use crate::fit::charts;
use crate::fit::fit_set::FitSet;
use crate::fit::model::{with_values, Material};
use crate::fit::report::{table, write_files};
use crate::fit::run::run_predict;
use anyhow::{bail, Context, Result};
use materials::material::Model;
use materials::AnyModel;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Experiment-set file (its [[parameter]] entries, if any, are not varied).
    pub set: PathBuf,
    /// Parameters: a fit report (report.toml) or a material file. Default: the set's
    /// material with its [fixed] overrides.
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// Output folder for report and charts.
    #[arg(long, default_value = "out/predict")]
    pub out: PathBuf,
    /// Fail unless every group is predicted within 5 % RMS of its mean measured curve.
    #[arg(long)]
    pub validate: bool,
}

/// The material of `file`: a fit report's `final_parameters` on `base`, or a material file.
fn material_from(base: &Material, file: &Path) -> Result<Material> {
    let text = std::fs::read_to_string(file)
        .with_context(|| format!("{}: cannot read", file.display()))?;
    let value: toml::Value =
        toml::from_str(&text).map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))?;
    let Some(list) = value.get("final_parameters") else {
        return match materials::load_material(file)?.model {
            AnyModel::ElastoPlastic(m) => Ok(m),
            _ => bail!(
                "{}: the material must be elasto-plastic (Johnson-Cook)",
                file.display()
            ),
        };
    };
    let field = || format!("{}: field `final_parameters`", file.display());
    let pairs = list
        .as_array()
        .with_context(|| format!("{}: expected an array of [name, value]", field()))?;
    let mut names = Vec::new();
    let mut values = Vec::new();
    for pair in pairs {
        let (Some(name), Some(v)) = (
            pair.get(0).and_then(|n| n.as_str()),
            pair.get(1).and_then(|v| v.as_float()),
        ) else {
            bail!("{}: expected [name, value], found {pair}", field());
        };
        if base.param(name).is_none() {
            bail!(
                "{}: unknown parameter `{name}`; known: {:?}",
                field(),
                base.param_names()
            );
        }
        names.push(name);
        values.push(v);
    }
    Ok(with_values(base, &names, &values))
}

pub fn run(args: Args) -> Result<()> {
    let set = FitSet::load(&args.set)?;
    let material = match &args.params {
        Some(file) => material_from(&set.base, file)?,
        None => set.base,
    };
    let from = args.params.as_ref().map_or_else(
        || "the set's material".to_string(),
        |f| f.display().to_string(),
    );
    eprintln!(
        "predicting {} ({} experiments) with the parameters of {from}",
        args.set.display(),
        set.blocks.len()
    );
    let result = run_predict(&set, material)?;
    print!("{}", table(&set, &result));
    write_files(&args.out, &set, &result)?;
    charts::fit_charts(&args.out, &set, &result)?;
    println!("report, CSVs and charts in {}", args.out.display());
    if args.validate {
        validate(&args.set, &set, &result, false)?;
    }
    Ok(())
}
