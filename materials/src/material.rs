//! The material interface shared by the single-point driver and the MPM solver.
//!
//! A pure update in the style of Ferrite.jl: `(σ, new_state) = f(F, Δt, old_state)`.
//! The old state is never mutated, so a failed update leaves the history untouched.

use crate::error::MaterialError;
use crate::local_newton::Converged as Root;
use crate::scalar::{c, Scalar};
use crate::tensor::{identity, M3};
use nalgebra::Matrix3;

/// History of one material point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State<D = f64> {
    /// Inverse plastic deformation gradient F^p⁻¹ (identity for elastic models).
    pub fp_inv: M3<D>,
    /// Accumulated plastic arc length α (equivalent plastic strain) [-].
    pub alpha: D,
    /// Temperature θ [K].
    pub theta: D,
    /// Plastic increment Δα of the step that led here (0 after an elastic step) [-]: where
    /// the next return starts its local solve (a point in flow changes it little per step).
    pub dalpha: D,
}

impl<D: Scalar> State<D> {
    /// Virgin state at temperature `theta`.
    pub fn virgin(theta: D) -> Self {
        State {
            fp_inv: identity(),
            alpha: c(0.0),
            theta,
            dalpha: c(0.0),
        }
    }

    pub fn map<E: Scalar>(&self, f: impl Fn(D) -> E) -> State<E> {
        State {
            fp_inv: self.fp_inv.map(&f),
            alpha: f(self.alpha),
            theta: f(self.theta),
            dalpha: f(self.dalpha),
        }
    }

    pub fn re(&self) -> State<f64> {
        self.map(|x| x.re())
    }
}

/// Receives the update of point i of a batch: (σ, new state) or its failure.
pub type Deliver<'a, D = f64> = dyn FnMut(usize, Result<(M3<D>, State<D>), MaterialError>) + 'a;

/// Takes `(i, converged)` for point i of a batch whose update solved a local problem: what
/// `Model::update_from_real` differentiates without forming it again (a derivative pass).
pub type Keep<'a> = dyn FnMut(usize, &Converged) + 'a;

/// A converged local problem of a model's update (the principal return's four unknowns).
pub type Converged = Root<4>;

/// What the run's own update of a point gave, for `Model::update_from_real`.
#[derive(Clone, Copy)]
pub struct RealUpdate<'a> {
    /// The new state.
    pub state: &'a State<f64>,
    /// The local problem it converged to, where the run kept it (`update_batch_keeping`).
    pub converged: Option<&'a Converged>,
    /// Whether F, the old Fp⁻¹ and their derivatives keep the z axis (xz, yz, zx and zy
    /// zero, as in plane strain and axisymmetric models): the update may then skip the
    /// terms that structure makes zero (`tensor::mul_in`).
    pub in_plane: bool,
}

/// A batch update point by point with `update`.
pub fn one_by_one<D: Scalar>(
    update: impl Fn(&M3<D>, &State<D>) -> Result<(M3<D>, State<D>), MaterialError>,
    f: &[M3<D>],
    old: &[State<D>],
    deliver: &mut Deliver<D>,
) {
    for (i, (f, old)) in f.iter().zip(old).enumerate() {
        deliver(i, update(f, old));
    }
}

/// A material model written once for any scalar `D` (real or dual).
pub trait Model<D: Scalar>: Clone + Send + Sync {
    /// The same model with parameters of another scalar type.
    type With<E: Scalar>: Model<E>;

    /// Convert (or seed with dual parts) every parameter by name.
    fn map_params<E: Scalar>(&self, f: impl FnMut(&'static str, D) -> E) -> Self::With<E>;

    /// Names of all parameters, in a fixed order.
    fn param_names(&self) -> Vec<&'static str>;

    /// Value of the named parameter.
    fn param(&self, name: &str) -> Option<D>;

    /// Reference density ρ0 [kg/m³].
    fn density(&self) -> D;

    /// P-wave modulus Λ + 2G [Pa] (dilatational wave speed √(M/ρ) for the CFL limit).
    fn p_wave_modulus(&self) -> D;

    /// Initial state (reference temperature for thermal models).
    fn initial_state(&self) -> State<D>;

    /// Cauchy stress and new state from the total deformation gradient `f`, the time step
    /// `dt` [s] and the previous state.
    fn update(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
    ) -> Result<(M3<D>, State<D>), MaterialError>;

    /// `update` given what the same update gave in real arithmetic for the real parts of
    /// `f` and `old` (the run's own update, in a derivative pass): a model that solves a
    /// local problem takes the solution from there and only differentiates it. The same
    /// result as `update` to round-off; the default is `update`. A model that wraps
    /// another forwards it.
    fn update_from_real(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
        real: RealUpdate<'_>,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        let _ = real;
        self.update(f, dt, old)
    }

    /// `update` of many points at once: `deliver(i, result)` for point i of `f` and `old`
    /// (same length), in any order. Models that can solve several points in lockstep
    /// override it; each result equals `update`'s. A model that wraps another forwards it
    /// (the default, one point at a time, would give the same numbers more slowly: the
    /// preheated SHPB specimen ran 9 % slower before it did).
    fn update_batch(&self, f: &[M3<D>], dt: f64, old: &[State<D>], deliver: &mut Deliver<D>) {
        one_by_one(|f, old| self.update(f, dt, old), f, old, deliver);
    }

    /// `update_batch`, handing `keep` the converged local problem of each point whose
    /// update solved one. The default keeps none; a model that wraps another forwards it.
    fn update_batch_keeping(
        &self,
        f: &[M3<D>],
        dt: f64,
        old: &[State<D>],
        deliver: &mut Deliver<D>,
        keep: &mut Keep,
    ) {
        let _ = keep;
        self.update_batch(f, dt, old, deliver)
    }
}

/// Object-safe, real-valued view of a model, as the MPM solver uses it.
pub trait Material: Send + Sync {
    fn density(&self) -> f64;
    fn p_wave_modulus(&self) -> f64;
    fn initial_state(&self) -> State<f64>;
    /// Reference and melting temperatures [θ0, θm] [K] of a model whose flow stress vanishes
    /// at θm (Johnson-Cook's `theta0`, `theta_m`); `None` for a model without one.
    fn melting_range(&self) -> Option<[f64; 2]>;
    fn update(
        &self,
        f: &Matrix3<f64>,
        dt: f64,
        old: &State<f64>,
    ) -> Result<(Matrix3<f64>, State<f64>), MaterialError>;
    /// Many points at once (`Model::update_batch`; one by one unless overridden).
    fn update_batch(
        &self,
        f: &[Matrix3<f64>],
        dt: f64,
        old: &[State<f64>],
        deliver: &mut Deliver<'_>,
    ) {
        one_by_one(|f, old| self.update(f, dt, old), f, old, deliver);
    }
    /// `Model::update_batch_keeping`.
    fn update_batch_keeping(
        &self,
        f: &[Matrix3<f64>],
        dt: f64,
        old: &[State<f64>],
        deliver: &mut Deliver<'_>,
        keep: &mut Keep,
    ) {
        let _ = keep;
        self.update_batch(f, dt, old, deliver)
    }
}

impl<T: Model<f64>> Material for T {
    fn density(&self) -> f64 {
        Model::density(self)
    }
    fn p_wave_modulus(&self) -> f64 {
        Model::p_wave_modulus(self)
    }
    fn initial_state(&self) -> State<f64> {
        Model::initial_state(self)
    }
    fn melting_range(&self) -> Option<[f64; 2]> {
        Some([
            Model::param(self, "theta0")?,
            Model::param(self, "theta_m")?,
        ])
    }
    fn update(
        &self,
        f: &Matrix3<f64>,
        dt: f64,
        old: &State<f64>,
    ) -> Result<(Matrix3<f64>, State<f64>), MaterialError> {
        Model::update(self, f, dt, old)
    }
    fn update_batch(
        &self,
        f: &[Matrix3<f64>],
        dt: f64,
        old: &[State<f64>],
        deliver: &mut Deliver<'_>,
    ) {
        Model::update_batch(self, f, dt, old, deliver)
    }
    fn update_batch_keeping(
        &self,
        f: &[Matrix3<f64>],
        dt: f64,
        old: &[State<f64>],
        deliver: &mut Deliver<'_>,
        keep: &mut Keep,
    ) {
        Model::update_batch_keeping(self, f, dt, old, deliver, keep)
    }
}
