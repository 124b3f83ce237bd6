//! Leave one group out: for each group (`scatter::groups`), fit every free parameter on
//! the other groups (one Levenberg-Marquardt run from the set's stated starts, so the
//! left-out records do not even choose the start) and predict the group left out. The
//! out-of-sample RMS against that group's mean curve, beside the in-sample RMS of the fit
//! on all records, says how well the model carries over to a rate (or temperature) it
//! has not seen.

use crate::fit::levels::model::{with_values, Material};
use crate::fit::objective::{predict, Block};
use crate::fit::optimize::run::refit;
use crate::fit::sets::fit_set::FitSet;
use crate::fit::statistics::scatter::{groups, scatter, Scatter};
use anyhow::Result;
use rayon::prelude::*;

/// One fold: the group left out, the parameters fitted without it and its scatter
/// against their predictions.
#[derive(Debug, Clone)]
pub struct Fold {
    pub left_out: String,
    pub values: Vec<f64>,
    pub converged: bool,
    /// In-sample: the fit on all records against this group.
    pub in_sample: Scatter,
    /// Out-of-sample: the fit without this group against it.
    pub out_of_sample: Scatter,
}

/// Every fold of `set`; `fitted` is the material of the fit on all records. Folds run side
/// by side when the set's evaluations take several fits at once, with the same results.
pub fn leave_one_group_out(
    set: &FitSet,
    fitted: &Material,
    progress: &(dyn Fn(usize, &str) + Sync),
) -> Result<Vec<Fold>> {
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    let names: Vec<&str> = set.params.iter().map(|p| p.name.as_str()).collect();
    let all = scatter(
        &blocks,
        &predict(set.evaluations.as_ref(), &blocks, fitted)?,
    );
    let groups = groups(&blocks);
    anyhow::ensure!(
        groups.len() >= 2,
        "leave-one-group-out needs at least two groups"
    );
    let fold = |k: usize| -> Result<Fold> {
        let g = &groups[k];
        progress(k, &g.label);
        let kept: Vec<&Block> = (0..blocks.len())
            .filter(|i| !g.members.contains(i))
            .map(|i| blocks[i])
            .collect();
        let r = refit(set, set.base, kept, None)?;
        let material = with_values(&set.base, &names, &r.values);
        let out = scatter(
            &blocks,
            &predict(set.evaluations.as_ref(), &blocks, &material)?,
        );
        Ok(Fold {
            left_out: g.label.clone(),
            values: r.values,
            converged: r.converged,
            in_sample: all[k].clone(),
            out_of_sample: out[k].clone(),
        })
    };
    let folds = match set.evaluations.fits_at_once().min(groups.len()) {
        0 | 1 => (0..groups.len()).map(fold).collect::<Result<Vec<_>>>()?,
        k => rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()?
            .install(|| {
                (0..groups.len())
                    .into_par_iter()
                    .map(fold)
                    .collect::<Result<Vec<_>>>()
            })?,
    };
    Ok(folds)
}
