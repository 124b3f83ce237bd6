//! The objective: a weighted sum of normalized squared residuals over experiments,
//!
//! S(p) = Σ_e w_e / n_e Σ_k ((ŷ_ek(p) − y_ek) / s_e)²,  s_e = mean_k |y_ek|,
//!
//! on each experiment's own samples within its window (n_e of them). S is dimensionless;
//! the residual vector r_ek = √(w_e/n_e) (ŷ_ek − y_ek)/s_e gives S = rᵀr. Parameters
//! enter through the unbounded coordinates u of `ParamSpace`; the Jacobian dr/du is
//! dr/dp · diag(dp/du). Experiments are evaluated in parallel.

use crate::fit::evaluations::{Evaluations, Prediction, Request, IN_PROCESS};
use crate::fit::levels::model::{fd_matrix, fd_points, with_values, ExperimentModel, Material};
use crate::fit::params::ParamSpace;
use anyhow::{bail, Context, Result};
use nalgebra::DMatrix;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// One experiment in the objective.
pub struct Block {
    pub name: String,
    pub model: Box<dyn ExperimentModel>,
    /// Measured values at the samples, as the model predicts them.
    pub measured: Vec<f64>,
    /// Times of the measured values [s] (for charts).
    pub times: Vec<f64>,
    /// Abscissa for charts (e.g. engineering strain) and its label with unit.
    pub x: Vec<f64>,
    pub x_label: String,
    /// Label of the measured quantity with unit, e.g. `engineering stress [MPa]`.
    pub y_label: String,
    /// Factor from SI to the chart unit of `measured` (1e-6 for MPa, 1e-3 for kN).
    pub y_chart_scale: f64,
    pub weight: f64,
    /// Normalization s_e = mean |measured|.
    pub scale: f64,
    /// Names of the channels stacked in `measured` (equal lengths), e.g. `F1`, `F2`.
    pub channels: Vec<String>,
    /// Nominal (tensile) or mean measured (SHPB) strain rate [1/s], for reports.
    pub rate_per_s: f64,
    /// Test temperature [K].
    pub temperature_k: f64,
    /// Records of one group (tensile: same nominal rate and temperature) are compared as
    /// a specimen population (`fit::statistics::scatter`); `None`: a group of its own.
    pub group: Option<String>,
    /// Where rate and temperature were read (TOML key or CSV header line), for reports.
    pub metadata_source: String,
    /// SHPB: mean equilibrium ratio R = 2 |F1 − F2| / |F1 + F2| over the window [-]
    /// (NaN for other experiments).
    pub equilibrium_ratio: f64,
    /// Specimen strain over the compared samples, [smallest, largest] (tensile: engineering
    /// strain; SHPB: magnitude of the true strain) [-]; NaN until the builder sets it.
    pub strain_range: [f64; 2],
    /// SHPB: each sample's true strain and the factor from a face force to the specimen's
    /// true stress, so that a chart draws a record as stress against strain.
    pub stress_strain: Option<StressStrain>,
}

/// An SHPB record's samples as stress and strain: the measured true strain ε (magnitude)
/// and σ_true = F exp(−ε)/A0 for a face force F, the current area following from constant
/// volume (A = A0 L0/L, L = L0 exp(−ε) in compression).
#[derive(Debug, Clone)]
pub struct StressStrain {
    /// True strain at each sample, compression positive [-].
    pub strain: Vec<f64>,
    /// exp(−ε)/A0 at each sample [1/m²].
    pub stress_per_force: Vec<f64>,
}

impl StressStrain {
    pub fn new(strain: Vec<f64>, area_m2: f64) -> Self {
        let stress_per_force = strain.iter().map(|e| (-e).exp() / area_m2).collect();
        StressStrain {
            strain,
            stress_per_force,
        }
    }
}

impl Block {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        name: &str,
        model: Box<dyn ExperimentModel>,
        measured: Vec<f64>,
        times: Vec<f64>,
        x: Vec<f64>,
        x_label: &str,
        y_label: &str,
        y_chart_scale: f64,
        weight: f64,
    ) -> Result<Self> {
        if measured.len() != model.len() {
            bail!(
                "experiment `{name}`: {} measured values but the model predicts {}",
                measured.len(),
                model.len()
            );
        }
        if measured.is_empty() {
            bail!("experiment `{name}`: no samples in its window");
        }
        if !(weight > 0.0 && weight.is_finite()) {
            bail!("experiment `{name}`: weight {weight} must be positive");
        }
        let scale = measured.iter().map(|y| y.abs()).sum::<f64>() / measured.len() as f64;
        if !(scale > 0.0) {
            bail!("experiment `{name}`: measured values are all zero");
        }
        Ok(Block {
            name: name.to_string(),
            model,
            measured,
            times,
            x,
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            y_chart_scale,
            weight,
            scale,
            channels: vec!["measured".into()],
            rate_per_s: f64::NAN,
            temperature_k: f64::NAN,
            group: None,
            metadata_source: String::new(),
            equilibrium_ratio: f64::NAN,
            strain_range: [f64::NAN; 2],
            stress_strain: None,
        })
    }

    /// Residuals r_k = √(w/n) (ŷ_k − y_k)/s of `predicted` ŷ.
    pub fn residuals<'a>(&'a self, predicted: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
        let f = self.residual_factor();
        predicted
            .iter()
            .zip(&self.measured)
            .map(move |(p, y)| f * (p - y))
    }

    fn residual_factor(&self) -> f64 {
        (self.weight / self.measured.len() as f64).sqrt() / self.scale
    }

    /// RMS of ŷ − y in SI units.
    pub fn rms(&self, predicted: &[f64]) -> f64 {
        let s: f64 = predicted
            .iter()
            .zip(&self.measured)
            .map(|(p, y)| (p - y).powi(2))
            .sum();
        (s / self.measured.len() as f64).sqrt()
    }
}

/// Predictions of every experiment of `blocks` with `material`, through `evaluations`.
pub fn predict(
    evaluations: &dyn Evaluations,
    blocks: &[&Block],
    material: &Material,
) -> Result<Vec<Vec<f64>>> {
    Ok(predict_with_warnings(evaluations, blocks, material)?.0)
}

/// `predict`, with each experiment's warnings at `material` (`ExperimentModel::predict_with_warnings`).
pub fn predict_with_warnings(
    evaluations: &dyn Evaluations,
    blocks: &[&Block],
    material: &Material,
) -> Result<(Vec<Vec<f64>>, Vec<Vec<String>>)> {
    let requests: Vec<Request> = blocks
        .iter()
        .map(|&block| Request {
            block,
            material: *material,
        })
        .collect();
    Ok(evaluations.predict(&requests)?.into_iter().unzip())
}

/// How the Jacobian of the residuals is formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JacobianKind {
    /// The model's own (exact AD for single-point models).
    Exact,
    /// Forward finite differences for every model.
    FiniteDifference,
}

/// The objective over a set of experiments and a set of free parameters.
pub struct Objective<'a> {
    pub base: Material,
    pub blocks: Vec<&'a Block>,
    pub space: ParamSpace,
    /// Where the model runs go (default: this process).
    pub evaluations: &'a dyn Evaluations,
    evaluation_count: AtomicUsize,
    jacobians: AtomicUsize,
}

impl<'a> Objective<'a> {
    pub fn new(base: Material, blocks: Vec<&'a Block>, space: ParamSpace) -> Result<Self> {
        if blocks.is_empty() {
            bail!("objective without experiments");
        }
        let n: usize = blocks.iter().map(|b| b.measured.len()).sum();
        if n < space.len() {
            bail!("{n} samples cannot determine {} parameters", space.len());
        }
        Ok(Objective {
            base,
            blocks,
            space,
            evaluations: &IN_PROCESS,
            evaluation_count: AtomicUsize::new(0),
            jacobians: AtomicUsize::new(0),
        })
    }

    /// The objective with its model runs sent to `evaluations`.
    pub fn with_evaluations(self, evaluations: &'a dyn Evaluations) -> Self {
        Objective {
            evaluations,
            ..self
        }
    }

    /// Model evaluations so far: (real passes over all experiments, AD Jacobian passes).
    pub fn counts(&self) -> (usize, usize) {
        (
            self.evaluation_count.load(Ordering::Relaxed),
            self.jacobians.load(Ordering::Relaxed),
        )
    }

    /// The material at bounded parameter values `p`.
    pub fn material(&self, p: &[f64]) -> Material {
        with_values(&self.base, &self.space.names(), p)
    }

    /// Whether a Jacobian of `kind` costs about one pass: every model's own, and each of
    /// them from dual numbers.
    pub fn jacobian_is_cheap(&self, kind: JacobianKind) -> bool {
        kind == JacobianKind::Exact && self.blocks.iter().all(|b| b.model.jacobian_is_cheap())
    }

    /// Total number of residuals.
    pub fn len(&self) -> usize {
        self.blocks.iter().map(|b| b.measured.len()).sum()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Predictions of every experiment at bounded parameters `p`.
    pub fn predictions(&self, p: &[f64]) -> Result<Vec<Vec<f64>>> {
        self.evaluation_count.fetch_add(1, Ordering::Relaxed);
        predict(self.evaluations, &self.blocks, &self.material(p))
    }

    fn stack(&self, predictions: &[Vec<f64>]) -> Vec<f64> {
        let mut r = Vec::with_capacity(self.len());
        for (b, p) in self.blocks.iter().zip(predictions) {
            r.extend(b.residuals(p));
        }
        r
    }

    /// Residual vector at unbounded coordinates `u`.
    pub fn residuals(&self, u: &[f64]) -> Result<Vec<f64>> {
        let p = self.space.to_bounded(u);
        Ok(self.stack(&self.predictions(&p)?))
    }

    /// Residuals and their Jacobian dr/du at `u`.
    pub fn residuals_and_jacobian(
        &self,
        u: &[f64],
        kind: JacobianKind,
    ) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let p = self.space.to_bounded(u);
        let dpdu = self.space.derivatives(u);
        let material = self.material(&p);
        let names = self.space.names();
        let own = |b: &&Block| b.model.has_own_jacobian();
        if kind == JacobianKind::Exact && self.blocks.iter().all(own) {
            self.jacobians.fetch_add(1, Ordering::Relaxed);
        } else {
            // One base pass plus one pass per parameter.
            self.evaluation_count
                .fetch_add(1 + names.len(), Ordering::Relaxed);
        }
        let parts = self.jacobian_parts(&material, &names, kind)?;
        let predictions: Vec<Vec<f64>> = parts.iter().map(|(y, _)| y.clone()).collect();
        let r = self.stack(&predictions);
        let mut jac = DMatrix::zeros(r.len(), names.len());
        let mut row = 0;
        for (b, (_, j)) in self.blocks.iter().zip(&parts) {
            let f = b.residual_factor();
            for i in 0..j.nrows() {
                for k in 0..names.len() {
                    jac[(row + i, k)] = f * j[(i, k)] * dpdu[k];
                }
            }
            row += j.nrows();
        }
        Ok((r, jac))
    }
}

impl Objective<'_> {
    /// Each experiment's prediction and Jacobian d(prediction)/d(parameter) at `material`:
    /// a model's own when it has one and `kind` is exact (dual numbers, in this process),
    /// else forward differences, whose runs go to the evaluations as one batch.
    fn jacobian_parts(
        &self,
        material: &Material,
        names: &[&str],
        kind: JacobianKind,
    ) -> Result<Vec<(Vec<f64>, DMatrix<f64>)>> {
        let own = |b: &Block| kind == JacobianKind::Exact && b.model.has_own_jacobian();
        let mut points = Vec::with_capacity(self.blocks.len());
        let mut requests = Vec::new();
        for &block in &self.blocks {
            if own(block) {
                points.push(Vec::new());
                continue;
            }
            let p = fd_points(material, names, block.model.fd_step())?;
            requests.push(Request {
                block,
                material: *material,
            });
            requests.extend(p.iter().map(|(m, _)| Request {
                block,
                material: *m,
            }));
            points.push(p);
        }
        let mut predicted = self
            .evaluations
            .predict(&requests)?
            .into_iter()
            .map(|(y, _): Prediction| y);
        let exact: Vec<Option<(Vec<f64>, DMatrix<f64>)>> = self
            .blocks
            .par_iter()
            .map(|b| {
                own(b)
                    .then(|| b.model.predict_with_jacobian(material, names))
                    .transpose()
                    .with_context(|| format!("experiment `{}`", b.name))
            })
            .collect::<Result<_>>()?;
        Ok(exact
            .into_iter()
            .zip(&points)
            .map(|(e, p)| {
                e.unwrap_or_else(|| {
                    let y0 = predicted.next().expect("a base prediction per block");
                    let ys: Vec<Vec<f64>> = p
                        .iter()
                        .map(|_| predicted.next().expect("a prediction per point"))
                        .collect();
                    let hs: Vec<f64> = p.iter().map(|(_, h)| *h).collect();
                    let jacobian = fd_matrix(&y0, &ys, &hs);
                    (y0, jacobian)
                })
            })
            .collect())
    }
}

/// S = rᵀr.
pub fn cost(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}
