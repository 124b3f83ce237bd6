//! Choosing a flow-stress law by prediction, not by fit. Each candidate law is fitted to
//! every record of the set, then judged by
//!
//! - the in-sample RMS against each group's mean curve (`scatter`),
//! - the leave-one-group-out RMS of each group predicted by the fit without it
//!   (`cross_validation`), and its mean over groups, the criterion,
//! - the small-sample Akaike criterion over records,
//!   AICc = R ln(S/R) + 2k + 2k(k + 1)/(R − k − 1),
//!   with S the fit's objective (a sum over the R records of each record's mean squared
//!   normalized residual, `objective`) and k free parameters. Records, not samples, are the
//!   independent units: the samples along one record's curve are strongly correlated, and
//!   counting them would reward every extra parameter,
//! - the parameter pairs the data do not identify (`identifiability`).
//!
//! More parameters always lower the in-sample RMS; only the held-out groups show whether
//! a law carries over to a rate or temperature it has not seen, so the law with the
//! lowest mean leave-one-group-out RMS is the one chosen.

use crate::fit::objective::Block;
use crate::fit::optimize::run::FitResult;
use crate::fit::sets::fit_set::FitSet;
use crate::fit::statistics::cross_validation::Fold;
use crate::fit::statistics::identifiability;
use crate::fit::statistics::scatter::scatter;

/// One candidate law, fitted and cross-validated.
#[derive(Debug, Clone)]
pub struct Score {
    /// The candidate's name (the set's own law: its material's name).
    pub name: String,
    /// The law's factors, e.g. `power × huh-kang × johnson-cook`.
    pub law: String,
    pub free: Vec<String>,
    /// Per group: (label, in-sample RMS, leave-one-group-out RMS) against its mean curve [-].
    pub groups: Vec<(String, f64, f64)>,
    pub aicc: f64,
    /// Every stage and every fold converged.
    pub converged: bool,
    pub warnings: Vec<String>,
}

impl Score {
    /// Mean in-sample RMS over groups [-].
    pub fn in_sample(&self) -> f64 {
        mean(self.groups.iter().map(|g| g.1))
    }

    /// Mean leave-one-group-out RMS over groups [-], the criterion.
    pub fn held_out(&self) -> f64 {
        mean(self.groups.iter().map(|g| g.2))
    }

    /// Largest leave-one-group-out RMS over groups [-].
    pub fn worst_held_out(&self) -> f64 {
        self.groups.iter().map(|g| g.2).fold(0.0, f64::max)
    }
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0), |(s, n), v| (s + v, n + 1));
    sum / n as f64
}

/// AICc over `records` records with objective `s` and `k` free parameters (infinite where
/// R ≤ k + 1: too few records to penalize the parameters).
pub fn aicc(s: f64, records: usize, k: usize) -> f64 {
    let (r, kf) = (records as f64, k as f64);
    if records <= k + 1 {
        return f64::INFINITY;
    }
    r * (s / r).ln() + 2.0 * kf + 2.0 * kf * (kf + 1.0) / (r - kf - 1.0)
}

/// The score of the candidate `set` from its fit on all records and its folds.
pub fn score(name: &str, set: &FitSet, fit: &FitResult, folds: &[Fold]) -> Score {
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    let in_sample = scatter(&blocks, &fit.predictions);
    let groups = in_sample
        .iter()
        .map(|g| {
            let fold = folds.iter().find(|f| f.left_out == g.group.label);
            let held_out = fold.map_or(f64::NAN, |f| f.out_of_sample.rms_vs_mean);
            (g.group.label.clone(), g.rms_vs_mean, held_out)
        })
        .collect();
    let last = fit.stages.last().expect("a fit has a stage");
    let converged =
        fit.stages.iter().all(|s| s.runs[s.best].converged) && folds.iter().all(|f| f.converged);
    Score {
        name: name.to_string(),
        law: set.base.flow.describe(),
        free: last.free.clone(),
        groups,
        aicc: aicc(last.cost, set.blocks.len(), last.free.len()),
        converged,
        warnings: identifiability::warnings(&last.free, &last.correlation),
    }
}

/// The index of the law that predicts best: the lowest mean leave-one-group-out RMS among
/// the laws whose fit and folds converged (among all when none did).
pub fn best(scores: &[Score]) -> Option<usize> {
    let lowest = |converged_only: bool| {
        (0..scores.len())
            .filter(|&i| scores[i].held_out().is_finite())
            .filter(|&i| scores[i].converged || !converged_only)
            .min_by(|&a, &b| scores[a].held_out().total_cmp(&scores[b].held_out()))
    };
    lowest(true).or_else(|| lowest(false))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// AICc against the formula written out: 50 records, S = 0.02, k = 4.
    #[test]
    fn aicc_follows_its_formula() {
        let expected = 50.0 * (0.02f64 / 50.0).ln() + 8.0 + 40.0 / 45.0;
        assert!((aicc(0.02, 50, 4) - expected).abs() < 1e-12);
        assert_eq!(aicc(0.02, 5, 4), f64::INFINITY);
    }

    /// The choice is the lowest held-out mean, not the lowest in-sample error.
    #[test]
    fn the_best_law_predicts_best() {
        let law = |name: &str, fit: f64, held: f64| Score {
            name: name.into(),
            law: String::new(),
            free: vec![],
            groups: vec![("a".into(), fit, held), ("b".into(), fit, held)],
            aicc: 0.0,
            converged: true,
            warnings: vec![],
        };
        let mut scores = vec![
            law("fits best", 0.01, 0.09),
            law("predicts best", 0.03, 0.04),
        ];
        assert_eq!(best(&scores), Some(1));
        scores.push(Score {
            converged: false,
            ..law("did not converge", 0.01, 0.01)
        });
        assert_eq!(best(&scores), Some(1));
    }
}
