//! Single-point model level: one homogeneous material point driven along the measured
//! history by `materials::driver`, with the observed channel computed from the records.
//!
//! The exact Jacobian comes from running the same driver with parameters seeded as dual
//! numbers: the driver and the return mapping differentiate their converged Newton solves
//! by the implicit function theorem, so d(prediction)/d(parameter) is exact to round-off.
//! `Dual<P>` (`materials::dual`) carries all P free parameters in one pass (P ≤ 8);
//! `PerParameter` runs one `num-dual` `Dual64` pass per parameter (kept for the cost
//! comparison in `mpw fit --compare`).

use crate::fit::levels::model::{ExperimentModel, Material};
use anyhow::{anyhow, bail, Context, Result};
use materials::ad::seed_named;
use materials::driver::{run, LoadPath, Record};
use materials::material::Model;
use materials::preheated::{Preheated, STRETCH_PARAMETERS};
use materials::scalar::Scalar;
use nalgebra::DMatrix;
use num_dual::Dual64;

/// What a single-point experiment measures, computed from the driver records.
pub trait Observable: Send + Sync {
    fn level(&self) -> &'static str;
    /// The load path the material point follows.
    fn path(&self) -> &LoadPath;
    /// Temperature at the start of the test [K].
    fn theta_start(&self) -> f64;
    /// Number of observed values.
    fn len(&self) -> usize;
    /// Observed values from the records (any scalar, so derivatives come along).
    fn observe<D: Scalar>(&self, records: &[Record<D>]) -> Vec<D>;
}

/// How the AD Jacobian is formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdMode {
    /// One driver pass with a `Dual<P>` carrying all free parameters.
    Vector,
    /// One `Dual64` driver pass per free parameter.
    PerParameter,
}

/// A single-point experiment model.
#[derive(Debug, Clone)]
pub struct SinglePoint<O> {
    pub observable: O,
    pub ad_mode: AdMode,
}

impl<O: Observable> SinglePoint<O> {
    pub fn new(observable: O) -> Self {
        SinglePoint {
            observable,
            ad_mode: AdMode::Vector,
        }
    }

    fn evaluate<D: Scalar>(&self, material: &materials::ElastoPlastic<D>) -> Result<Vec<D>> {
        let model = Preheated {
            inner: *material,
            theta_start: self.observable.theta_start(),
        };
        let records = run(&model, self.observable.path())
            .with_context(|| format!("{} model", self.observable.level()))?;
        Ok(self.observable.observe(&records))
    }

    fn check_free(&self, material: &Material, free: &[&str]) -> Result<()> {
        for name in free {
            if material.param(name).is_none() {
                bail!("the material has no parameter `{name}`");
            }
            let preheated = self.observable.theta_start() != material.thermal.theta0;
            if preheated && STRETCH_PARAMETERS.contains(name) {
                bail!("parameter `{name}` cannot be free for a test that starts away from θ0 (its thermal stretch is fixed)");
            }
        }
        Ok(())
    }

    fn vector_pass<const P: usize>(
        &self,
        material: &Material,
        free: &[&str],
    ) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let seeded = material.map_params(|name, v| seed_named::<P>(free, name, v));
        let out = self.evaluate(&seeded)?;
        let jac = DMatrix::from_fn(out.len(), P, |i, k| out[i].eps[k]);
        Ok((out.iter().map(|x| x.re).collect(), jac))
    }

    fn per_parameter(
        &self,
        material: &Material,
        free: &[&str],
    ) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let mut values = Vec::new();
        let mut jac = DMatrix::zeros(self.observable.len(), free.len());
        for (k, target) in free.iter().enumerate() {
            let seeded = material.map_params(|name, v| {
                if name == *target {
                    Dual64::new(v, 1.0)
                } else {
                    Dual64::from(v)
                }
            });
            let out = self.evaluate(&seeded)?;
            for (i, x) in out.iter().enumerate() {
                jac[(i, k)] = x.eps;
            }
            values = out.iter().map(|x| x.re).collect();
        }
        Ok((values, jac))
    }
}

impl<O: Observable> ExperimentModel for SinglePoint<O> {
    fn level(&self) -> &'static str {
        self.observable.level()
    }

    fn len(&self) -> usize {
        self.observable.len()
    }

    fn predict(&self, material: &Material) -> Result<Vec<f64>> {
        self.evaluate(material)
    }

    fn jacobian_is_cheap(&self) -> bool {
        true
    }

    fn predict_with_jacobian(
        &self,
        material: &Material,
        free: &[&str],
    ) -> Result<(Vec<f64>, DMatrix<f64>)> {
        self.check_free(material, free)?;
        if self.ad_mode == AdMode::PerParameter {
            return self.per_parameter(material, free);
        }
        match free.len() {
            1 => self.vector_pass::<1>(material, free),
            2 => self.vector_pass::<2>(material, free),
            3 => self.vector_pass::<3>(material, free),
            4 => self.vector_pass::<4>(material, free),
            5 => self.vector_pass::<5>(material, free),
            6 => self.vector_pass::<6>(material, free),
            7 => self.vector_pass::<7>(material, free),
            8 => self.vector_pass::<8>(material, free),
            n if n > 8 => self.per_parameter(material, free),
            _ => Err(anyhow!("no free parameters")),
        }
    }
}
