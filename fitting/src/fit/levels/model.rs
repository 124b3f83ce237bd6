//! The model level of an experiment, as the objective sees it: a prediction of the
//! experiment's measured channels at its own samples, and the derivative of that
//! prediction with respect to named material parameters.
//!
//! Single-point models (`single_point`) give the exact derivative by AD through the
//! driver; a model without AD (the MPM SHPB model, `mpm_shpb`) keeps the default, a
//! forward finite difference with columns evaluated in parallel, at its own step. The optimizers see only this
//! trait, so a new model level plugs in without touching them.

use crate::shpb_model::ContactChange;
use anyhow::Result;
use materials::material::Model;
use materials::plasticity::ElastoPlastic;
use nalgebra::DMatrix;
use rayon::prelude::*;

/// The material a fit varies: an elasto-plastic model with named parameters.
pub type Material = ElastoPlastic<f64>;

pub trait ExperimentModel: Send + Sync {
    /// Short name of the model level, for reports (e.g. `single-point SHPB specimen`).
    fn level(&self) -> &'static str;

    /// Number of predicted values (the length of `predict`).
    fn len(&self) -> usize;

    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Predicted values at the experiment's samples, in the units of its measurement.
    fn predict(&self, material: &Material) -> Result<Vec<f64>>;

    /// `predict`, with what the model's run warns about at these parameters (an MPM level:
    /// specimen points that reached the melting temperature). Default: no warnings.
    fn predict_with_warnings(&self, material: &Material) -> Result<(Vec<f64>, Vec<String>)> {
        Ok((self.predict(material)?, Vec::new()))
    }

    /// Relative step of the forward differences (`finite_difference`): the driver's
    /// `FD_STEP` unless the model's own noise asks for a larger one.
    fn fd_step(&self) -> f64 {
        FD_STEP
    }

    /// Whether `predict_with_jacobian` costs about one `predict` (dual numbers), so that an
    /// optimizer may take the Jacobian at every trial point. Default: no (finite
    /// differences cost one run per free parameter more).
    fn jacobian_is_cheap(&self) -> bool {
        false
    }

    /// Whether `predict_with_jacobian` gives the model's own Jacobian (AD through the
    /// driver, or the derivatives carried through an MPM run) rather than the default
    /// finite differences, which the objective then batches itself. Default: when cheap.
    fn has_own_jacobian(&self) -> bool {
        self.jacobian_is_cheap()
    }

    /// This experiment's model with its contact assumptions changed (penalty stiffness κ
    /// and friction μ, `fit::statistics::assumptions`); `None` for a level without contact.
    fn with_contact(&self, _change: &ContactChange) -> Result<Option<Box<dyn ExperimentModel>>> {
        Ok(None)
    }

    /// Prediction and its Jacobian d(prediction)/d(parameter) (rows: samples, columns:
    /// `free` in order). Default: forward finite differences (`finite_difference`).
    fn predict_with_jacobian(
        &self,
        material: &Material,
        free: &[&str],
    ) -> Result<(Vec<f64>, DMatrix<f64>)> {
        finite_difference(self, material, free)
    }
}

/// Relative forward-difference step: ≈ √(ε_machine · noise of the driver (≈ 1e-10)).
pub const FD_STEP: f64 = 1e-6;

/// `material` with the named parameters set to `values`.
pub fn with_values(material: &Material, names: &[&str], values: &[f64]) -> Material {
    material.map_params(|name, v| match names.iter().position(|n| *n == name) {
        Some(k) => values[k],
        None => v,
    })
}

/// Forward finite-difference Jacobian, one column per free parameter, columns in parallel
/// (`fd_points`, `fd_matrix`).
pub fn finite_difference<M: ExperimentModel + ?Sized>(
    model: &M,
    material: &Material,
    free: &[&str],
) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let points = fd_points(material, free, model.fd_step())?;
    let y0 = model.predict(material)?;
    let ys: Vec<Vec<f64>> = points
        .par_iter()
        .map(|(m, _)| model.predict(m))
        .collect::<Result<_>>()?;
    let hs: Vec<f64> = points.iter().map(|(_, h)| *h).collect();
    let jacobian = fd_matrix(&y0, &ys, &hs);
    Ok((y0, jacobian))
}

/// The forward-difference points of `free` around `material`: per parameter the material
/// with that parameter stepped, and the step h.
pub fn fd_points(material: &Material, free: &[&str], fd_step: f64) -> Result<Vec<(Material, f64)>> {
    let base: Vec<f64> = free
        .iter()
        .map(|n| {
            material
                .param(n)
                .ok_or_else(|| anyhow::anyhow!("the material has no parameter `{n}`"))
        })
        .collect::<Result<_>>()?;
    Ok((0..free.len())
        .map(|k| {
            let h = fd_step * base[k].abs().max(1e-3);
            let mut p = base.clone();
            p[k] += h;
            (with_values(material, free, &p), h)
        })
        .collect())
}

/// The forward-difference Jacobian from the base prediction `y0` and the predictions `ys`
/// at the points of steps `hs` (rows: samples, columns: parameters).
pub fn fd_matrix(y0: &[f64], ys: &[Vec<f64>], hs: &[f64]) -> DMatrix<f64> {
    DMatrix::from_fn(y0.len(), hs.len(), |i, k| (ys[k][i] - y0[i]) / hs[k])
}
