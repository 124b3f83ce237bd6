//! A material that starts at a temperature θ_start other than its reference θ0 (a
//! preheated SHPB specimen, a tensile test in a furnace), and the stress-free thermal
//! stretch it has there.
//!
//! The elastic law (eq. 4.22) carries the thermal term −3 α_σ κ (θ − θ0) I, so a specimen
//! whose length L0 is the reference (cold) length has the free thermal stretch λ_θ at
//! θ_start with τ(λ_θ I) = 0:
//! 3 Λ ln λ + G (λ² − 1) − 3 α_σ κ (θ_start − θ0) = 0, solved by Newton (≈ α_σ Δθ).

use crate::material::{Deliver, Keep, Model, RealUpdate, State};
use crate::plasticity::ElastoPlastic;
use crate::scalar::{c, Scalar};
use crate::tensor::M3;
use crate::MaterialError;

/// `inner` with its initial state at temperature `theta_start` [K].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Preheated<M> {
    pub inner: M,
    pub theta_start: f64,
}

impl<D: Scalar, M: Model<D>> Model<D> for Preheated<M> {
    type With<E: Scalar> = Preheated<M::With<E>>;

    fn map_params<E: Scalar>(&self, f: impl FnMut(&'static str, D) -> E) -> Self::With<E> {
        Preheated {
            inner: self.inner.map_params(f),
            theta_start: self.theta_start,
        }
    }
    fn param_names(&self) -> Vec<&'static str> {
        self.inner.param_names()
    }
    fn param(&self, name: &str) -> Option<D> {
        self.inner.param(name)
    }
    fn density(&self) -> D {
        self.inner.density()
    }
    fn p_wave_modulus(&self) -> D {
        self.inner.p_wave_modulus()
    }
    fn initial_state(&self) -> State<D> {
        State::virgin(c(self.theta_start))
    }
    fn update(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        self.inner.update(f, dt, old)
    }
    fn update_from_real(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
        real: RealUpdate<'_>,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        self.inner.update_from_real(f, dt, old, real)
    }
    fn update_batch(&self, f: &[M3<D>], dt: f64, old: &[State<D>], deliver: &mut Deliver<D>) {
        self.inner.update_batch(f, dt, old, deliver)
    }
    fn update_batch_keeping(
        &self,
        f: &[M3<D>],
        dt: f64,
        old: &[State<D>],
        deliver: &mut Deliver<D>,
        keep: &mut Keep,
    ) {
        self.inner.update_batch_keeping(f, dt, old, deliver, keep)
    }
}

/// Free thermal stretch λ_θ of `material` at `theta` [K] (1 at θ0).
pub fn thermal_stretch(material: &ElastoPlastic<f64>, theta: f64) -> f64 {
    let el = &material.elastic;
    let (lambda, g, kappa) = (el.lambda(), el.shear_modulus(), el.bulk_modulus());
    let rhs = 3.0 * material.thermal.alpha_sigma * kappa * (theta - material.thermal.theta0);
    let mut x: f64 = 1.0;
    for _ in 0..50 {
        let r = 3.0 * lambda * x.ln() + g * (x * x - 1.0) - rhs;
        let dr = 3.0 * lambda / x + 2.0 * g * x;
        let dx = r / dr;
        x -= dx;
        if dx.abs() < 1e-15 {
            break;
        }
    }
    x
}

/// Material parameters the thermal stretch depends on; they cannot be free in a fit of a
/// preheated experiment because the load path is real-valued.
pub const STRETCH_PARAMETERS: [&str; 4] = ["E", "nu", "alpha_sigma", "theta0"];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::driver::{run, LoadPath, Temperature};

    #[test]
    fn free_thermal_stretch_is_stress_free() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/materials");
        let m = crate::load_elasto_plastic(std::path::Path::new(dir).join("42crmo4_qt660.toml"))
            .unwrap();
        let theta = 573.15;
        let l = thermal_stretch(&m, theta);
        // ≈ α_σ Δθ to first order: 1.27e-5 · 280 = 3.556e-3, within 1 % (second order).
        assert!(((l - 1.0) / 3.556e-3 - 1.0).abs() < 1e-2, "{l}");
        // Holding F_xx = λ_θ at θ_start gives σ_xx = 0 to 1e-3 Pa.
        let pre = Preheated {
            inner: m,
            theta_start: theta,
        };
        let path = LoadPath::uniaxial_stretch(vec![0.0, 1e-6], vec![l, l], Temperature::Adiabatic)
            .unwrap();
        let rec = run(&pre, &path).unwrap();
        assert!(
            rec[1].sigma[(0, 0)].abs() < 1e-3,
            "{}",
            rec[1].sigma[(0, 0)]
        );
        assert!((rec[1].f[(1, 1)] - l).abs() < 1e-12, "{}", rec[1].f[(1, 1)]);
    }
}
