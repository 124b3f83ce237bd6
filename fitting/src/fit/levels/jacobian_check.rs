//! A model's own Jacobian (`ExperimentModel::predict_with_jacobian`: AD through the
//! driver, or the derivatives carried through an MPM run) against central differences of
//! its predictions, (y(p + h) − y(p − h)) / 2h, at several relative steps h/p: per free
//! parameter, the worst difference over the samples relative to the column's largest
//! entry. Over the steps this is the difference quotient's error curve: truncation at
//! large steps, round-off at small ones, and between them, where the model's events are
//! sparse, a plateau on which the exact column sits.

use crate::fit::levels::model::{with_values, ExperimentModel, Material};
use anyhow::{Context, Result};
use materials::material::Model;

/// One parameter's column against central differences.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnCheck {
    pub parameter: String,
    /// The column's largest entry times the parameter's value [unit of the prediction].
    pub scale: f64,
    /// Worst |central − exact| over the samples over the column's largest entry, one per
    /// step of the check.
    pub errors: Vec<f64>,
}

impl ColumnCheck {
    /// The smallest error over the steps.
    pub fn best(&self) -> f64 {
        self.errors.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// `model`'s Jacobian at `material` along `free` against central differences at the
/// relative steps `steps`.
pub fn against_central_differences(
    model: &dyn ExperimentModel,
    material: &Material,
    free: &[&str],
    steps: &[f64],
) -> Result<Vec<ColumnCheck>> {
    let (y, jacobian) = model.predict_with_jacobian(material, free)?;
    free.iter()
        .enumerate()
        .map(|(k, name)| {
            let p = material
                .param(name)
                .with_context(|| format!("the material has no parameter `{name}`"))?;
            let largest = (0..y.len())
                .map(|i| jacobian[(i, k)].abs())
                .fold(0.0, f64::max);
            let errors = steps
                .iter()
                .map(|rel| {
                    let h = rel * p;
                    let at = |v: f64| model.predict(&with_values(material, &[name], &[v]));
                    let (up, down) = (at(p + h)?, at(p - h)?);
                    Ok((0..y.len())
                        .map(|i| ((up[i] - down[i]) / (2.0 * h) - jacobian[(i, k)]).abs())
                        .fold(0.0, f64::max)
                        / largest)
                })
                .collect::<Result<_>>()?;
            Ok(ColumnCheck {
                parameter: name.to_string(),
                scale: largest * p,
                errors,
            })
        })
        .collect()
}
