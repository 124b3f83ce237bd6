//! Parameter uncertainty that includes specimen scatter: a bootstrap over records.
//!
//! Sample b draws, within each group (`scatter::groups`), as many records as the group
//! has, with replacement, and refits every free parameter from the optimum (`run::refit`).
//! Over the B samples: per parameter the mean, standard deviation and the 2.5 / 97.5 %
//! percentiles (linear interpolation between order statistics), the correlation matrix,
//! and per group of several records the 2.5 / 97.5 % band of the model's mean curve.
//!
//! The JᵀJ standard errors (`run::statistics`) treat every sample of every curve as an
//! independent measurement; records scatter as whole curves, so within a curve the
//! residuals are correlated and the JᵀJ errors understate the uncertainty of parameters
//! that describe the material rather than one specimen. Sample b uses the random stream
//! `seed`, b: the same numbers whatever the thread count.

use crate::fit::levels::model::{with_values, Material};
use crate::fit::objective::{predict, Block, Objective};
use crate::fit::optimize::run::{refit, statistics};
use crate::fit::params::ParamSpace;
use crate::fit::sets::fit_set::FitSet;
use crate::fit::statistics::scatter::{groups, model_mean, scatter};
use anyhow::{Context, Result};
use materials::material::Model;
use rand::Rng;
use rand_pcg::Pcg64;
use rayon::prelude::*;

/// One parameter's bootstrap distribution beside its JᵀJ standard error.
#[derive(Debug, Clone)]
pub struct ParamInterval {
    pub name: String,
    pub optimum: f64,
    pub mean: f64,
    pub sd: f64,
    pub lo95: f64,
    pub hi95: f64,
    pub jtj_std_error: f64,
}

/// The 95 % band of one group's model mean curve.
#[derive(Debug, Clone)]
pub struct Band {
    pub group: String,
    pub strain: Vec<f64>,
    pub lo95: Vec<f64>,
    pub hi95: Vec<f64>,
}

#[derive(Debug, Clone)]
pub struct Bootstrap {
    pub samples: usize,
    /// Samples whose refit stopped without converging (kept) and that failed (dropped).
    pub not_converged: usize,
    pub failed: usize,
    pub params: Vec<ParamInterval>,
    pub correlation: Vec<Vec<f64>>,
    pub bands: Vec<Band>,
    pub wall_s: f64,
}

/// One resample's refit: its values, its model's mean curve of each group, and whether it
/// converged.
struct Refitted {
    values: Vec<f64>,
    curves: Vec<Vec<f64>>,
    converged: bool,
}

/// Percentile q ∈ [0, 1] of sorted values (linear between order statistics).
pub fn percentile(sorted: &[f64], q: f64) -> f64 {
    let h = q * (sorted.len() - 1) as f64;
    let (k, w) = (h.floor() as usize, h - h.floor());
    match sorted.get(k + 1) {
        Some(next) => sorted[k] + w * (next - sorted[k]),
        None => sorted[k],
    }
}

/// Records of `blocks` drawn with replacement within each group, from `rng`.
fn resample<'a>(blocks: &[&'a Block], rng: &mut Pcg64) -> Vec<&'a Block> {
    let mut out = Vec::with_capacity(blocks.len());
    for g in groups(blocks) {
        for _ in 0..g.members.len() {
            out.push(blocks[g.members[rng.gen_range(0..g.members.len())]]);
        }
    }
    out
}

/// `samples` bootstrap refits of `set` from the optimum `material`; `progress(b)` after
/// each sample. The set's evaluations say how many refits run at once
/// (`Evaluations::fits_at_once`: one in this process, more when their runs go to a
/// cluster); the samples are the same either way.
pub fn bootstrap(
    set: &FitSet,
    material: &Material,
    samples: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Bootstrap> {
    let t0 = std::time::Instant::now();
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    let names: Vec<&str> = set.params.iter().map(|p| p.name.as_str()).collect();
    let optimum: Vec<f64> = names.iter().map(|n| material.param(n).unwrap()).collect();
    let grids = scatter(
        &blocks,
        &predict(set.evaluations.as_ref(), &blocks, material)?,
    );
    // one resample's refit; `None` when the refit failed
    let sample = |b: usize| -> Result<Option<Refitted>> {
        let mut rng = Pcg64::new(set.seed as u128, b as u128);
        let drawn = resample(&blocks, &mut rng);
        let refitted = match refit(set, *material, drawn, Some(&optimum)) {
            Ok(r) => {
                let m = with_values(material, &names, &r.values);
                let p = predict(set.evaluations.as_ref(), &blocks, &m)
                    .with_context(|| format!("bootstrap sample {b}"))?;
                let mean_curves: Vec<Vec<f64>> = grids
                    .iter()
                    .map(|g| model_mean(&blocks, &g.group, &g.strain, &p))
                    .collect();
                Some(Refitted {
                    values: r.values,
                    curves: mean_curves,
                    converged: r.converged,
                })
            }
            Err(e) => {
                eprintln!("bootstrap sample {b}: refit failed: {e:#}");
                None
            }
        };
        progress(b);
        Ok(refitted)
    };
    let refits: Vec<Option<Refitted>> = match set.evaluations.fits_at_once() {
        1 => (0..samples).map(sample).collect::<Result<_>>()?,
        k => rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()?
            .install(|| {
                (0..samples)
                    .into_par_iter()
                    .map(sample)
                    .collect::<Result<_>>()
            })?,
    };
    let (mut values, mut curves) = (Vec::new(), Vec::new());
    let (mut not_converged, mut failed) = (0, 0);
    for refitted in refits {
        match refitted {
            Some(r) => {
                not_converged += usize::from(!r.converged);
                values.push(r.values);
                curves.push(r.curves);
            }
            None => failed += 1,
        }
    }
    anyhow::ensure!(
        values.len() >= 2,
        "bootstrap: fewer than two refits succeeded"
    );
    let jtj = jtj_std_errors(set, material, &blocks, &optimum)?;
    let (params, correlation) = intervals(&names, &optimum, &jtj, &values);
    let bands = grids
        .iter()
        .enumerate()
        .filter(|(_, g)| !g.strain.is_empty())
        .map(|(k, g)| band(&g.group.label, &g.strain, curves.iter().map(|c| &c[k][..])))
        .collect();
    Ok(Bootstrap {
        samples: values.len(),
        not_converged,
        failed,
        params,
        correlation,
        bands,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}

/// The JᵀJ standard errors of `set.params` at `optimum` on all of `blocks`.
fn jtj_std_errors(
    set: &FitSet,
    material: &Material,
    blocks: &[&Block],
    optimum: &[f64],
) -> Result<Vec<f64>> {
    let params = set
        .params
        .iter()
        .zip(optimum)
        .map(|(p, &x)| p.starting_at(x));
    let space = ParamSpace::new(params.collect())?;
    let u = space.to_unbounded(&space.starts());
    let objective = Objective::new(*material, blocks.to_vec(), space)?
        .with_evaluations(set.evaluations.as_ref());
    Ok(statistics(&objective, &u)?.0)
}

/// Per parameter the bootstrap distribution of `values` (one row per sample) beside its
/// JᵀJ error, and the correlation matrix of the samples.
fn intervals(
    names: &[&str],
    optimum: &[f64],
    jtj: &[f64],
    values: &[Vec<f64>],
) -> (Vec<ParamInterval>, Vec<Vec<f64>>) {
    let n = values.len() as f64;
    let column = |k: usize| -> Vec<f64> { values.iter().map(|v| v[k]).collect() };
    let mean: Vec<f64> = (0..names.len())
        .map(|k| column(k).iter().sum::<f64>() / n)
        .collect();
    let cov = |i: usize, j: usize| {
        values
            .iter()
            .map(|v| (v[i] - mean[i]) * (v[j] - mean[j]))
            .sum::<f64>()
            / (n - 1.0)
    };
    let params = (0..names.len())
        .map(|k| {
            let mut sorted = column(k);
            sorted.sort_by(f64::total_cmp);
            ParamInterval {
                name: names[k].to_string(),
                optimum: optimum[k],
                mean: mean[k],
                sd: cov(k, k).sqrt(),
                lo95: percentile(&sorted, 0.025),
                hi95: percentile(&sorted, 0.975),
                jtj_std_error: jtj[k],
            }
        })
        .collect();
    let correlation = (0..names.len())
        .map(|i| {
            (0..names.len())
                .map(|j| cov(i, j) / (cov(i, i) * cov(j, j)).sqrt())
                .collect()
        })
        .collect();
    (params, correlation)
}

/// The 2.5 / 97.5 % band of a group's model mean curves (one per sample) on `strain`.
fn band<'a>(group: &str, strain: &[f64], curves: impl Iterator<Item = &'a [f64]> + Clone) -> Band {
    let at = |j: usize, q: f64| {
        let mut v: Vec<f64> = curves.clone().map(|c| c[j]).collect();
        v.sort_by(f64::total_cmp);
        percentile(&v, q)
    };
    Band {
        group: group.to_string(),
        strain: strain.to_vec(),
        lo95: (0..strain.len()).map(|j| at(j, 0.025)).collect(),
        hi95: (0..strain.len()).map(|j| at(j, 0.975)).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_interpolate_between_order_statistics() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0];
        assert_eq!(percentile(&v, 0.0), 1.0);
        assert_eq!(percentile(&v, 0.5), 3.0);
        assert_eq!(percentile(&v, 1.0), 5.0);
        assert!((percentile(&v, 0.025) - 1.1).abs() < 1e-12);
        assert!((percentile(&v, 0.975) - 4.9).abs() < 1e-12);
    }
}
