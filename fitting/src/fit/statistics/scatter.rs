//! Specimen scatter: the records of one group (tensile: one nominal rate and temperature)
//! as a population of specimens, so that a fit is judged against the scatter of the
//! material rather than against one specimen.
//!
//! On a common strain grid s_j (`GRID` points over the strain range all records of the
//! group cover) each record's measured stress y_i(s_j) and the model's prediction for that
//! record ŷ_i(s_j) (it follows the record's own strain history) are interpolated linearly.
//! Then, with n records,
//!
//! ȳ(s) = Σ y_i / n,  sd(s)² = Σ (y_i − ȳ)² / (n − 1),  CV(s) = sd/ȳ  [-],
//!
//! and the fit's error against the mean curve is
//! RMS_mean = √(Σ_j (ŷ̄(s_j) − ȳ(s_j))² / J) / (Σ_j ȳ(s_j) / J)  [-],
//! beside the mean over records of each record's own RMS [% of its mean stress]. A group of
//! one record (and every SHPB record) compares on its own samples.

use crate::fit::objective::Block;

/// Points of the common strain grid.
pub const GRID: usize = 50;

/// Strains [-] at which the coefficient of variation is reported (those inside the grid).
pub const CV_STRAINS: [f64; 4] = [0.02, 0.05, 0.10, 0.20];

/// Records of one group: indices into the blocks.
#[derive(Debug, Clone)]
pub struct Group {
    pub label: String,
    pub members: Vec<usize>,
}

/// The groups of `blocks` in order of first appearance; a block without a group key is a
/// group of its own.
pub fn groups(blocks: &[&Block]) -> Vec<Group> {
    let mut out: Vec<Group> = Vec::new();
    for (i, b) in blocks.iter().enumerate() {
        let label = b.group.clone().unwrap_or_else(|| b.name.clone());
        match out
            .iter_mut()
            .find(|g| b.group.is_some() && g.label == label)
        {
            Some(g) => g.members.push(i),
            None => out.push(Group {
                label,
                members: vec![i],
            }),
        }
    }
    out
}

/// One group's scatter and the fit's error against it.
#[derive(Debug, Clone)]
pub struct Scatter {
    pub group: Group,
    /// Common strain grid [-] (empty for a group compared on its own samples).
    pub strain: Vec<f64>,
    /// Mean measured curve ȳ and its standard deviation over the records [SI].
    pub mean: Vec<f64>,
    pub sd: Vec<f64>,
    /// Mean of the model's predictions for the records [SI].
    pub model_mean: Vec<f64>,
    /// (strain, CV) at the `CV_STRAINS` inside the grid.
    pub cv_at: Vec<(f64, f64)>,
    /// Mean CV over the grid [-] (NaN for one record).
    pub cv_mean: f64,
    /// RMS_mean [-].
    pub rms_vs_mean: f64,
    /// Mean of the records' own RMS, each relative to its mean measured value [-].
    pub rms_vs_records: f64,
}

impl Scatter {
    /// One line: the fit against the mean curve and against the scatter.
    pub fn verdict(&self) -> String {
        let n = self.group.members.len();
        if n < 2 {
            return format!(
                "{}: one record, RMS {:.2} % (no scatter to judge against)",
                self.group.label,
                100.0 * self.rms_vs_mean
            );
        }
        let judged = if self.rms_vs_mean <= self.cv_mean {
            "within the specimen scatter"
        } else {
            "beyond the specimen scatter: model error"
        };
        format!(
            "{}: {n} records, fit RMS {:.2} % against their mean curve, {judged} (mean CV {:.2} %); {:.2} % against single records",
            self.group.label,
            100.0 * self.rms_vs_mean,
            100.0 * self.cv_mean,
            100.0 * self.rms_vs_records
        )
    }
}

/// Linear interpolation of the curve (x, y) at `s`; x may be non-monotonic in places
/// (the first segment that brackets `s` is used). NaN outside the curve.
fn at(x: &[f64], y: &[f64], s: f64) -> f64 {
    for k in 1..x.len() {
        let (a, b) = (x[k - 1], x[k]);
        if (a <= s && s <= b) || (b <= s && s <= a) {
            if a == b {
                return y[k];
            }
            let w = (s - a) / (b - a);
            return y[k - 1] + w * (y[k] - y[k - 1]);
        }
    }
    f64::NAN
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// The common strain grid of the records `members`: `GRID` points from the largest first
/// strain to the smallest last strain; `None` if the records share no strain range.
fn common_grid(blocks: &[&Block], members: &[usize]) -> Option<Vec<f64>> {
    let span = |b: &Block| {
        let lo = b.x.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = b.x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    };
    let lo = members
        .iter()
        .map(|&i| span(blocks[i]).0)
        .fold(f64::NEG_INFINITY, f64::max);
    let hi = members
        .iter()
        .map(|&i| span(blocks[i]).1)
        .fold(f64::INFINITY, f64::min);
    (lo < hi).then(|| {
        (0..GRID)
            .map(|j| match j {
                _ if j == GRID - 1 => hi,
                _ => lo + (hi - lo) * j as f64 / (GRID - 1) as f64,
            })
            .collect()
    })
}

/// The model's mean curve of `group` on `strain` from `predictions` (one per block).
pub fn model_mean(
    blocks: &[&Block],
    group: &Group,
    strain: &[f64],
    predictions: &[Vec<f64>],
) -> Vec<f64> {
    strain
        .iter()
        .map(|&s| {
            let v: Vec<f64> = group
                .members
                .iter()
                .map(|&i| at(&blocks[i].x, &predictions[i], s))
                .collect();
            mean(&v)
        })
        .collect()
}

/// The scatter of every group of `blocks` and the error of `predictions` against it.
pub fn scatter(blocks: &[&Block], predictions: &[Vec<f64>]) -> Vec<Scatter> {
    groups(blocks)
        .into_iter()
        .map(|group| {
            let own: Vec<f64> = group
                .members
                .iter()
                .map(|&i| blocks[i].rms(&predictions[i]) / blocks[i].scale)
                .collect();
            let rms_vs_records = mean(&own);
            let grid = (group.members.len() > 1)
                .then(|| common_grid(blocks, &group.members))
                .flatten();
            let Some(strain) = grid else {
                return Scatter {
                    strain: Vec::new(),
                    mean: Vec::new(),
                    sd: Vec::new(),
                    model_mean: Vec::new(),
                    cv_at: Vec::new(),
                    cv_mean: f64::NAN,
                    rms_vs_mean: if group.members.len() == 1 {
                        rms_vs_records
                    } else {
                        f64::NAN
                    },
                    rms_vs_records,
                    group,
                };
            };
            let n = group.members.len() as f64;
            let (mut m, mut sd) = (Vec::new(), Vec::new());
            for &s in &strain {
                let y: Vec<f64> = group
                    .members
                    .iter()
                    .map(|&i| at(&blocks[i].x, &blocks[i].measured, s))
                    .collect();
                let ybar = mean(&y);
                let var = y.iter().map(|v| (v - ybar).powi(2)).sum::<f64>() / (n - 1.0);
                m.push(ybar);
                sd.push(var.sqrt());
            }
            let model = model_mean(blocks, &group, &strain, predictions);
            let cv: Vec<f64> = sd.iter().zip(&m).map(|(s, y)| s / y).collect();
            let (lo, hi) = (strain[0], strain[GRID - 1]);
            let cv_at = CV_STRAINS
                .iter()
                .filter(|&&s| lo <= s && s <= hi)
                .map(|&s| (s, at(&strain, &cv, s)))
                .collect();
            let err: Vec<f64> = model.iter().zip(&m).map(|(p, y)| (p - y).powi(2)).collect();
            Scatter {
                cv_at,
                cv_mean: mean(&cv),
                rms_vs_mean: mean(&err).sqrt() / mean(&m),
                rms_vs_records,
                strain,
                mean: m,
                sd,
                model_mean: model,
                group,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::levels::model::{ExperimentModel, Material};

    /// A stand-in for a model: predicts a fixed curve.
    struct Fixed(Vec<f64>);

    impl ExperimentModel for Fixed {
        fn level(&self) -> &'static str {
            "fixed"
        }
        fn len(&self) -> usize {
            self.0.len()
        }
        fn predict(&self, _: &Material) -> anyhow::Result<Vec<f64>> {
            Ok(self.0.clone())
        }
    }

    /// A record k·σ(ε) on its own strain samples, in group `group`.
    fn record(k: f64, strain: Vec<f64>, group: &str) -> Block {
        let sigma: Vec<f64> = strain.iter().map(|e| 400e6 + 900e6 * e).collect();
        let measured = sigma.iter().map(|s| k * s).collect();
        let model = Box::new(Fixed(sigma));
        let t = strain.clone();
        let mut b = Block::new("r", model, measured, t, strain, "e", "s", 1e-6, 1.0).unwrap();
        b.group = Some(group.into());
        b
    }

    #[test]
    fn scale_factor_scatter_gives_its_cv_and_the_bias_of_the_mean() {
        // Records k σ(ε) with k = 0.95, 1.0, 1.1 on different strain samples: CV(ε) is
        // sd(k)/mean(k) at every strain, and a model predicting σ misses the mean curve
        // by |mean(k) − 1|/mean(k).
        let ks = [0.95, 1.0, 1.1];
        let strains = |a: f64, b: f64, n: usize| -> Vec<f64> {
            (0..n)
                .map(|j| a + (b - a) * j as f64 / (n - 1) as f64)
                .collect()
        };
        let blocks = [
            record(ks[0], strains(0.01, 0.30, 40), "g"),
            record(ks[1], strains(0.012, 0.25, 33), "g"),
            record(ks[2], strains(0.008, 0.28, 57), "g"),
            record(1.0, strains(0.0, 0.1, 5), "other"),
        ];
        let refs: Vec<&Block> = blocks.iter().collect();
        let predictions: Vec<Vec<f64>> = refs
            .iter()
            .map(|b| b.model.predict(&material()).unwrap())
            .collect();
        let s = scatter(&refs, &predictions);
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].group.members, [0, 1, 2]);
        let kbar = ks.iter().sum::<f64>() / 3.0;
        let sd = (ks.iter().map(|k| (k - kbar).powi(2)).sum::<f64>() / 2.0).sqrt();
        assert!((s[0].cv_mean - sd / kbar).abs() < 1e-12, "{}", s[0].cv_mean);
        assert_eq!(
            s[0].cv_at.len(),
            4,
            "2, 5, 10 and 20 % inside [0.012, 0.25]"
        );
        // σ is linear in ε, so interpolation is exact: RMS_mean = (k̄ − 1)/k̄ · rms(σ)/mean(σ).
        let sigma: Vec<f64> = s[0].strain.iter().map(|e| 400e6 + 900e6 * e).collect();
        let rms = (sigma.iter().map(|v| v * v).sum::<f64>() / GRID as f64).sqrt();
        let expected = (kbar - 1.0) / kbar * rms / mean(&sigma);
        assert!(
            (s[0].rms_vs_mean - expected).abs() < 1e-12,
            "{}",
            s[0].rms_vs_mean
        );
        assert!(
            (s[0].strain[0] - 0.012).abs() < 1e-15 && (s[0].strain[GRID - 1] - 0.25).abs() < 1e-15
        );
        assert_eq!(s[1].rms_vs_mean, 0.0);
        assert!(
            s[0].verdict().contains("within the specimen scatter"),
            "{}",
            s[0].verdict()
        );
    }

    fn material() -> Material {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials");
        materials::load_elasto_plastic(dir.join("ss304l.toml")).unwrap()
    }

    #[test]
    fn interpolation_brackets_and_refuses_outside() {
        let x = [0.0, 1.0, 2.0];
        let y = [0.0, 10.0, 30.0];
        assert_eq!(at(&x, &y, 0.5), 5.0);
        assert_eq!(at(&x, &y, 1.5), 20.0);
        assert_eq!(at(&x, &y, 2.0), 30.0);
        assert!(at(&x, &y, 2.1).is_nan());
    }
}
