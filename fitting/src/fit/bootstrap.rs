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

use super::fit_set::FitSet;
use super::model::{with_values, Material};
use super::objective::{predict, Block, Objective};
use super::params::ParamSpace;
use super::run::{refit, statistics};
use super::scatter::{groups, model_mean, scatter};
use anyhow::{Context, Result};
use materials::material::Model;
use rand::Rng;
use rand_pcg::Pcg64;

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
/// each sample.
pub fn bootstrap(
    set: &FitSet,
    material: &Material,
    samples: usize,
    progress: &dyn Fn(usize),
) -> Result<Bootstrap> {
    let t0 = std::time::Instant::now();
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    let names: Vec<&str> = set.params.iter().map(|p| p.name.as_str()).collect();
    let optimum: Vec<f64> = names.iter().map(|n| material.param(n).unwrap()).collect();
    let grids = scatter(&blocks, &predict(&blocks, material)?);
    let (mut values, mut curves) = (Vec::new(), Vec::new());
    let (mut not_converged, mut failed) = (0, 0);
    for b in 0..samples {
        let mut rng = Pcg64::new(set.seed as u128, b as u128);
        let drawn = resample(&blocks, &mut rng);
        match refit(set, *material, drawn, Some(&optimum)) {
            Ok(r) => {
                not_converged += usize::from(!r.converged);
                let m = with_values(material, &names, &r.values);
                let p = predict(&blocks, &m).with_context(|| format!("bootstrap sample {b}"))?;
                let mean_curves: Vec<Vec<f64>> = grids
                    .iter()
                    .map(|g| model_mean(&blocks, &g.group, &g.strain, &p))
                    .collect();
                curves.push(mean_curves);
                values.push(r.values);
            }
            Err(e) => {
                eprintln!("bootstrap sample {b}: refit failed: {e:#}");
                failed += 1;
            }
        }
        progress(b);
    }
    anyhow::ensure!(
        values.len() >= 2,
        "bootstrap: fewer than two refits succeeded"
    );
    let objective = Objective::new(
        *material,
        blocks.clone(),
        ParamSpace::new(
            set.params
                .iter()
                .zip(&optimum)
                .map(|(p, &x)| p.starting_at(x))
                .collect(),
        )?,
    )?;
    let u = objective.space.to_unbounded(&optimum);
    let (jtj, _) = statistics(&objective, &u)?;
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
    let bands = grids
        .iter()
        .enumerate()
        .filter(|(_, g)| !g.strain.is_empty())
        .map(|(k, g)| {
            let at = |j: usize, q: f64| {
                let mut v: Vec<f64> = curves.iter().map(|c| c[k][j]).collect();
                v.sort_by(f64::total_cmp);
                percentile(&v, q)
            };
            Band {
                group: g.group.label.clone(),
                strain: g.strain.clone(),
                lo95: (0..g.strain.len()).map(|j| at(j, 0.025)).collect(),
                hi95: (0..g.strain.len()).map(|j| at(j, 0.975)).collect(),
            }
        })
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
