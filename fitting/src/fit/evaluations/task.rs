//! The run kind `prediction`: one experiment of a fit set predicted at one material, as a
//! task of a `runs` executor. Its description names the set file as `input`, and in
//! `[set]` the experiment (`experiment = "name"`) and every material parameter
//! (`"material.A" = 7.92e8`, ...); its outcome holds the prediction as the series
//! `prediction` and the run's warnings. The set is loaded as `mpw fit` loads it, so the
//! experiment's model is the one the fit holds, and the material is the set's base with
//! every parameter replaced: the prediction is the one the fit would make in process.

use super::{predict_here, Request};
use crate::fit::levels::model::{with_values, Material};
use crate::fit::sets::fit_set::FitSet;
use anyhow::{bail, Context, Result};
use materials::material::Model;
use runs::{Outcome, OutcomeSeries, RunDescription};
use std::path::Path;

/// The run kind of a prediction.
pub const KIND: &str = "prediction";

/// The name of the predicted series in the outcome.
pub const SERIES: &str = "prediction";

/// The description of `request`, an experiment of the set in `set_file`.
pub fn description(set_file: &Path, request: &Request) -> RunDescription {
    let mut d = RunDescription::new(KIND, set_file);
    let set = &mut d.set;
    set.insert(
        "experiment".into(),
        toml::Value::String(request.block.name.clone()),
    );
    for name in request.material.param_names() {
        let value = request.material.param(name).expect("a named parameter");
        set.insert(format!("material.{name}"), toml::Value::Float(value));
    }
    d
}

/// Run a `prediction` description (`mpw run-one`); `_dir` is unused (the prediction
/// writes no files of its own).
pub fn execute_prediction(description: &RunDescription, _dir: &Path) -> Result<Outcome> {
    let file = &description.input;
    let set = FitSet::load(file)?;
    let mut experiment = None;
    let (mut names, mut values) = (Vec::new(), Vec::new());
    for (key, value) in &description.set {
        match (key.as_str(), key.strip_prefix("material.")) {
            ("experiment", _) => experiment = value.as_str(),
            (_, Some(name)) => {
                if set.base.param(name).is_none() {
                    bail!(
                        "`{key}`: the set's material has no parameter `{name}`; it has {:?}",
                        set.base.param_names()
                    );
                }
                names.push(name);
                values.push(
                    value
                        .as_float()
                        .with_context(|| format!("`{key}` must be a number"))?,
                );
            }
            _ => bail!("`{key}`: a prediction takes `experiment` and `material.<parameter>`"),
        }
    }
    let Some(experiment) = experiment else {
        bail!(
            "a prediction needs `experiment` (the name of one of {}'s experiments)",
            file.display()
        );
    };
    let Some(block) = set.blocks.iter().find(|b| b.name == experiment) else {
        let known: Vec<&str> = set.blocks.iter().map(|b| b.name.as_str()).collect();
        bail!(
            "{} has no experiment `{experiment}`; it has {}",
            file.display(),
            known.join(", ")
        );
    };
    let material: Material = with_values(&set.base, &names, &values);
    let (prediction, warnings) = predict_here(&Request { block, material })?;
    Ok(Outcome {
        warnings,
        series: vec![OutcomeSeries {
            name: SERIES.into(),
            unit: String::new(),
            values: prediction,
        }],
        ..Outcome::default()
    })
}
