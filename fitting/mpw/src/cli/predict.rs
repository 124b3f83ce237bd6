//! `mpw predict SET [--params FILE]`: evaluate an experiment set with given parameters,
//! no optimizer. The parameters are the set's material with its `[fixed]` overrides, or
//! those of `--params`: a fit report (`report.toml`, its `final_parameters` applied to the
//! set's material) or a material file (used as it is). Same report, CSVs and charts as a
//! fit, including the specimen scatter of every group; `--validate` applies the fit's
//! validation to the prediction (every group within 5 % RMS of its mean curve).

use crate::charts::fit as fit_charts;
use crate::cli::fit::validate;
use anyhow::Result;
use fitting::fit::optimize::run::run_predict;
use fitting::fit::reports::report::{read_parameters, table, write_files};
use fitting::fit::sets::fit_set::FitSet;
use std::path::PathBuf;

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

pub fn run(args: Args) -> Result<()> {
    let set = FitSet::load(&args.set)?;
    let material = match &args.params {
        Some(file) => read_parameters(&set.base, file)?,
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
    fit_charts::fit_charts(&args.out, &set, &result)?;
    crate::cli::fit::warn_about_models(&set, &result);
    println!("report, CSVs and charts in {}", args.out.display());
    if args.validate {
        validate(&args.set, &set, &result)?;
    }
    Ok(())
}
