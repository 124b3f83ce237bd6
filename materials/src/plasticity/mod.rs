//! Finite-strain J2 thermo-visco-plasticity on a Neo-Hooke elastic law (thesis 4.3,
//! algorithms 3 and 4).
//!
//! - Multiplicative split F = Fe Fp; history `fp_inv` = Fp⁻¹, `alpha`, `theta`.
//! - Trial Fe = F Fp_n⁻¹; von Mises yield φ = τ_VM − τ_y(α, α̇, θ_n), α̇ = Δα/Δt.
//! - Plastic flow by the implicit exponential map, eq. 4.48:
//!   Fe = exp(−Δα √(3/2) N) F Fp_n⁻¹, N = dev τ / ‖dev τ‖.
//! - Adiabatic heating after the return, eq. 4.50 with Kirchhoff flow stress:
//!   θ = θ_n + γ_TQ/(ρ0 c_θ) Δα τ_y, with τ_y = τ_VM of the returned stress.
//!
//! With a `Voce` flow stress this is the rate-independent J2 model (eq. 4.51); with a
//! `JohnsonCook` flow stress the Johnson-Cook model (eq. 4.52).
//!
//! The local problem is solved in `f64` (reference 10-unknown Newton or the fast
//! principal-stretch return). For dual scalars one more Newton step is taken in dual
//! arithmetic with the converged real Jacobian: x = x* − K⁻¹ r(x*), which is the implicit
//! function theorem dx/dp = −K⁻¹ ∂r/∂p, so derivatives never pass through the iterations.
//! Each return takes that step in its own unknowns: the reference return in its ten, the
//! principal return in its four (`return_principal_dual`, with the rotation of the
//! eigenbasis carried by the derivative of an isotropic tensor function).

pub mod return_principal;
mod return_principal_dual;
pub mod return_reference;

use crate::elastic::Elastic;
use crate::error::MaterialError;
use crate::flow_stress::{FlowStress, Onset, MOLTEN_THERMAL_FACTOR};
use crate::lanes::{pack, F64x4, MAX_LANES};
use crate::material::{one_by_one, Converged, Deliver, Keep, Model, RealUpdate, State};
use crate::parameter_set;
use crate::scalar::{c, Scalar};
use crate::tensor::{all_finite, det, det_in, lift, mul, mul_in, re, von_mises, M3};
use return_principal::Yielding;

parameter_set! {
    /// Thermal constants (eq. 4.22-4.23, 4.50).
    Thermal {
        /// reference (stress-free) temperature θ0 [K]
        theta0 => "theta0",
        /// specific heat capacity c_θ [J/(kg K)]
        c_theta => "c_theta",
        /// thermal expansion coefficient α_σ [1/K]
        alpha_sigma => "alpha_sigma",
        /// Taylor-Quinney coefficient γ_TQ [-]
        gamma_tq => "gamma_tq",
    }
}

/// Which algorithm solves the local return mapping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReturnMap {
    /// Thesis algorithm 3: Newton on the 9 entries of Fp⁻¹ and α (10 unknowns).
    Reference,
    /// Equivalent return in the principal logarithmic stretches of the trial be
    /// (4 unknowns), valid because the model is isotropic.
    Principal,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElastoPlastic<D = f64> {
    pub elastic: Elastic<D>,
    pub flow: FlowStress<D>,
    pub thermal: Thermal<D>,
    pub return_map: ReturnMap,
}

impl<D: Scalar> ElastoPlastic<D> {
    /// Kirchhoff stress of the elastic part at temperature `theta`.
    pub fn tau(&self, fe: &M3<D>, theta: D) -> M3<D> {
        self.tau_in::<false>(fe, theta)
    }

    /// `tau` of an `fe` with the structure `IN_PLANE` (`tensor::sum_coupled`).
    fn tau_in<const IN_PLANE: bool>(&self, fe: &M3<D>, theta: D) -> M3<D> {
        let (theta0, alpha_sigma) = (self.thermal.theta0, self.thermal.alpha_sigma);
        self.elastic
            .tau_in::<IN_PLANE>(fe, theta - theta0, alpha_sigma)
    }

    /// Flow stress after a plastic increment `dalpha` over `dt` at temperature `theta`.
    pub fn tau_y(&self, alpha: D, dalpha: D, dt: f64, theta: D) -> D {
        self.flow
            .tau_y(alpha, dalpha / c::<D>(dt), theta, self.thermal.theta0)
    }

    /// The same model with real parameters.
    pub fn re(&self) -> ElastoPlastic<f64> {
        self.map_params(|_, v| v.re())
    }

    /// The same model with constant parameters of scalar type `E`.
    pub fn lift<E: Scalar>(&self) -> ElastoPlastic<E> {
        self.map_params(|_, v| c::<E>(v.re()))
    }
}

impl<D: Scalar> Model<D> for ElastoPlastic<D> {
    type With<E: Scalar> = ElastoPlastic<E>;

    fn map_params<E: Scalar>(&self, mut f: impl FnMut(&'static str, D) -> E) -> ElastoPlastic<E> {
        ElastoPlastic {
            elastic: self.elastic.map(&mut f),
            flow: self.flow.map(&mut f),
            thermal: self.thermal.map(&mut f),
            return_map: self.return_map,
        }
    }

    fn param_names(&self) -> Vec<&'static str> {
        let mut names = Elastic::<D>::NAMES.to_vec();
        names.extend(self.flow.names());
        names.extend_from_slice(Thermal::<D>::NAMES);
        names
    }

    fn param(&self, name: &str) -> Option<D> {
        let mut found = None;
        self.map_params(|n, v| {
            if n == name {
                found = Some(v);
            }
            v
        });
        found
    }

    fn density(&self) -> D {
        self.elastic.rho
    }

    fn p_wave_modulus(&self) -> D {
        self.elastic.p_wave_modulus()
    }

    fn initial_state(&self) -> State<D> {
        State::virgin(self.thermal.theta0)
    }

    fn update(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        let (onset, phi_trial) = match self.trial(f, old) {
            Trial::Done(result) => return result,
            Trial::Yields { onset, phi_trial } => (onset, phi_trial),
        };
        let (model, old_re, f_re) = (self.re(), old.re(), re(f));
        if onset.is_molten() {
            let real = RealReturn {
                molten: true,
                ..return_principal::molten(&model, &f_re, &old_re)?.into()
            };
            return self.after_return(f, dt, old, real);
        }
        // (Fp⁻¹, α) in real arithmetic, and τ where the return gives it.
        let real = match self.return_map {
            ReturnMap::Reference => {
                // Perfectly plastic estimate of Δα (radial return with 3G) as the first guess.
                let dalpha0 = phi_trial / (3.0 * model.elastic.shear_modulus());
                let (fp_inv, dalpha) =
                    return_reference::solve(&model, &f_re, &old_re, dt, dalpha0)?;
                RealReturn {
                    fp_inv,
                    alpha: old_re.alpha + dalpha,
                    dalpha,
                    tau: None,
                    molten: false,
                    converged: None,
                    in_plane: false,
                }
            }
            ReturnMap::Principal => {
                return_principal::solve(&model, &f_re, &old_re, dt, &onset)?.into()
            }
        };
        self.after_return(f, dt, old, real)
    }

    /// The run's real return in place of solving it again: the point yielded where the
    /// run's Δα is positive (an elastic point, or a molten one that did not flow, takes
    /// `update`), and the implicit step starts from its Fp⁻¹ and Δα.
    fn update_from_real(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
        RealUpdate {
            state: real,
            converged,
            in_plane,
        }: RealUpdate<'_>,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        let theta = old.theta.re();
        let flow = self.flow.map(|_, v| v.re());
        let molten = flow.thermal_factor(theta, self.thermal.theta0.re()) < MOLTEN_THERMAL_FACTOR;
        if real.dalpha <= 0.0 {
            // The run kept the point elastic; a molten point that did not flow (a trial
            // strain without deviator) takes the whole update and its molten derivative.
            return match molten {
                false if in_plane => {
                    (self.trial_stress::<true>(f, old)).map(|s| self.stay_elastic::<true>(s, old))
                }
                false => {
                    (self.trial_stress::<false>(f, old)).map(|s| self.stay_elastic::<false>(s, old))
                }
                true => self.update(f, dt, old),
            };
        }
        let real = RealReturn {
            fp_inv: real.fp_inv,
            alpha: real.alpha,
            dalpha: real.dalpha,
            tau: None,
            molten,
            converged: converged.copied(),
            in_plane,
        };
        self.after_return(f, dt, old, real)
    }

    /// The onsets of flow and the principal returns four points at a time
    /// (`FlowStress::onset` in lanes, `return_principal::solve_batch`); one at a time for
    /// dual scalars and the reference return.
    fn update_batch(&self, f: &[M3<D>], dt: f64, old: &[State<D>], deliver: &mut Deliver<D>) {
        self.batch(f, dt, old, deliver, None)
    }

    /// `update_batch`, keeping each principal return's y* and K⁻¹ (`solve_batch`).
    fn update_batch_keeping(
        &self,
        f: &[M3<D>],
        dt: f64,
        old: &[State<D>],
        deliver: &mut Deliver<D>,
        keep: &mut Keep,
    ) {
        self.batch(f, dt, old, deliver, Some(keep))
    }
}

impl<D: Scalar> ElastoPlastic<D> {
    /// `update_batch`, with `keep` as in `update_batch_keeping`.
    #[inline(always)]
    fn batch(
        &self,
        f: &[M3<D>],
        dt: f64,
        old: &[State<D>],
        deliver: &mut Deliver<D>,
        mut keep: Option<&mut Keep>,
    ) {
        if D::NDERIV > 0 || self.return_map == ReturnMap::Reference {
            return one_by_one(|f, old| self.update(f, dt, old), f, old, deliver);
        }
        let model = self.re();
        let mut group = YieldingGroup::default();
        // Four points at a time: their onsets of flow in lanes, then their trial states.
        for (first, (f_c, old_c)) in f.chunks(MAX_LANES).zip(old.chunks(MAX_LANES)).enumerate() {
            let last = f_c.len() - 1;
            let onsets = model.flow.onset::<F64x4>(
                pack(|k| old_c[k.min(last)].alpha.re()),
                pack(|k| old_c[k.min(last)].theta.re()),
                model.thermal.theta0,
            );
            for (k, (f_i, old_i)) in f_c.iter().zip(old_c).enumerate() {
                let i = first * MAX_LANES + k;
                let trial = match self.trial_stress::<false>(f_i, old_i) {
                    Ok(stress) => self.decide(stress, old_i, onsets.lane(k)),
                    Err(e) => Trial::Done(Err(e)),
                };
                match trial {
                    Trial::Done(result) => deliver(i, result),
                    Trial::Yields { onset, .. } if onset.is_molten() => {
                        deliver(i, self.update(f_i, dt, old_i))
                    }
                    Trial::Yields { onset, .. } => {
                        group.push(i, re(f_i), old_i.re(), onset);
                        if group.len == MAX_LANES {
                            let keep = keep.as_deref_mut();
                            self.return_group(&model, &mut group, (f, dt, old), deliver, keep);
                        }
                    }
                }
            }
        }
        if group.len > 0 {
            let keep = keep.as_deref_mut();
            self.return_group(&model, &mut group, (f, dt, old), deliver, keep);
        }
    }
}

/// What the trial state decides.
enum Trial<D> {
    /// Elastic (or failed): the update's result.
    Done(Result<(M3<D>, State<D>), MaterialError>),
    /// Yields: its onset of flow and φ^tr = τ_VM^tr − τ_y0 > 0 [Pa].
    Yields { onset: Onset, phi_trial: f64 },
}

/// The elastic trial state of a point.
struct TrialStress<D> {
    /// J = det F
    j: D,
    /// Fe^tr = F Fp_n⁻¹
    fe: M3<D>,
    /// τ^tr, in real arithmetic only (dual scalars compute it where it is the result).
    tau: Option<M3<D>>,
}

/// A return in real arithmetic: Fp⁻¹, α, and τ where the return gives it.
struct RealReturn {
    fp_inv: M3<f64>,
    alpha: f64,
    /// Δα as solved (α − α_n loses it below the last digit of α_n, and the implicit
    /// step needs ln Δα).
    dalpha: f64,
    tau: Option<M3<f64>>,
    /// At or above melting: no flow stress, the closed-form return.
    molten: bool,
    /// y* and K⁻¹ of the return as the run solved it, where it kept them.
    converged: Option<Converged>,
    /// Whether F, the old Fp⁻¹ and their derivatives keep the z axis (`RealUpdate`).
    in_plane: bool,
}

impl From<return_principal::Returned> for RealReturn {
    fn from(r: return_principal::Returned) -> Self {
        RealReturn {
            fp_inv: r.fp_inv,
            alpha: r.alpha,
            dalpha: r.dalpha,
            tau: Some(r.tau),
            molten: false,
            converged: None,
            in_plane: false,
        }
    }
}

/// A return with the derivatives of its result: Fp⁻¹, τ and α.
struct Flowed<D> {
    fp_inv: M3<D>,
    tau: M3<D>,
    alpha: D,
}

/// Up to `MAX_LANES` yielding points of a batch, in real arithmetic, and their indices.
#[derive(Default)]
struct YieldingGroup {
    len: usize,
    index: [usize; MAX_LANES],
    points: [Yielding; MAX_LANES],
}

impl YieldingGroup {
    fn push(&mut self, index: usize, f: M3<f64>, old: State<f64>, onset: Onset) {
        self.index[self.len] = index;
        self.points[self.len] = Yielding { f, old, onset };
        self.len += 1;
    }
}

impl<D: Scalar> ElastoPlastic<D> {
    /// The elastic trial state: its result if it does not yield.
    #[inline(always)]
    fn trial(&self, f: &M3<D>, old: &State<D>) -> Trial<D> {
        match self.trial_stress::<false>(f, old) {
            Ok(stress) => {
                let old_re = old.re();
                let flow = self.flow.map(|_, v| v.re());
                let onset = flow.onset(old_re.alpha, old_re.theta, self.thermal.theta0.re());
                self.decide(stress, old, onset)
            }
            Err(e) => Trial::Done(Err(e)),
        }
    }

    /// J, Fe^tr = F Fp_n⁻¹, and τ^tr where it may be the result (real scalars), of
    /// tensors with the structure `IN_PLANE`.
    #[inline(always)]
    fn trial_stress<const IN_PLANE: bool>(
        &self,
        f: &M3<D>,
        old: &State<D>,
    ) -> Result<TrialStress<D>, MaterialError> {
        let j = det_in::<IN_PLANE, D>(f);
        if j.re() <= 0.0 || !j.re().is_finite() {
            return Err(MaterialError::InvertedDeformation { det_f: j.re() });
        }
        let fe = mul_in::<IN_PLANE, D>(f, &old.fp_inv);
        // Dual scalars carry τ^tr only where it is the result.
        let tau = (D::NDERIV == 0).then(|| self.tau_in::<IN_PLANE>(&fe, old.theta));
        Ok(TrialStress { j, fe, tau })
    }

    /// τ_VM^tr of a trial state, in real arithmetic: yielding is decided there (φ^tr is
    /// not carried further).
    #[inline(always)]
    fn trial_von_mises(&self, stress: &TrialStress<D>, old: &State<D>) -> f64 {
        match &stress.tau {
            Some(tau) => von_mises(tau).re(),
            None => von_mises(&self.re().tau(&re(&stress.fe), old.theta.re())),
        }
    }

    /// The elastic update from the trial state: σ = τ^tr / J, the history kept (Δα = 0).
    #[inline(always)]
    fn stay_elastic<const IN_PLANE: bool>(
        &self,
        stress: TrialStress<D>,
        old: &State<D>,
    ) -> (M3<D>, State<D>) {
        let new = State {
            dalpha: c::<D>(0.0),
            ..*old
        };
        let tau = stress
            .tau
            .unwrap_or_else(|| self.tau_in::<IN_PLANE>(&stress.fe, old.theta));
        (tau * stress.j.recip(), new)
    }

    /// Whether the trial state `stress` yields at the `onset` of flow, and its result if
    /// it does not.
    #[inline(always)]
    fn decide(&self, stress: TrialStress<D>, old: &State<D>, onset: Onset) -> Trial<D> {
        let phi_trial = self.trial_von_mises(&stress, old) - onset.tau_y0;
        if phi_trial <= 0.0 {
            return Trial::Done(Ok(self.stay_elastic::<false>(stress, old)));
        }
        Trial::Yields { onset, phi_trial }
    }

    /// The update from a return solved in real arithmetic: derivatives of dual scalars by
    /// one implicit step, adiabatic heating, Cauchy stress.
    fn after_return(
        &self,
        f: &M3<D>,
        dt: f64,
        old: &State<D>,
        real: RealReturn,
    ) -> Result<(M3<D>, State<D>), MaterialError> {
        let (fp_inv, alpha, tau) = if D::NDERIV == 0 {
            let fp_inv = lift(&real.fp_inv);
            let tau = match real.tau {
                Some(tau) => lift(&tau),
                None => self.tau(&mul(f, &fp_inv), old.theta),
            };
            (fp_inv, c::<D>(real.alpha), tau)
        } else {
            let (fp_inv, dalpha) = (&real.fp_inv, real.dalpha);
            let Flowed { fp_inv, tau, alpha } = match (real.molten, self.return_map) {
                (true, _) => return_principal_dual::molten_step(self, f, old, real.in_plane)?,
                (false, ReturnMap::Principal) => {
                    let real = (fp_inv, dalpha, real.converged.as_ref(), real.in_plane);
                    return_principal_dual::implicit_step(self, f, old, dt, real)?
                }
                (false, ReturnMap::Reference) => {
                    let (fp_inv, alpha) =
                        return_reference::implicit_step(self, f, old, dt, fp_inv, dalpha)?;
                    let tau = self.tau(&mul(f, &fp_inv), old.theta);
                    Flowed { fp_inv, tau, alpha }
                }
            };
            (fp_inv, alpha, tau)
        };
        // Δα as solved where it is real: α − α_n loses it below the last digit of α_n,
        // and the next return (and a derivative pass, `update_from_real`) starts from it.
        let dalpha = match D::NDERIV {
            0 => c::<D>(real.dalpha),
            _ => alpha - old.alpha,
        };
        // τ_VM = τ_y at the converged return (φ = 0 holds identically in the parameters,
        // so their derivatives agree too) and costs no transcendental functions.
        let heating = self.thermal.gamma_tq / (self.elastic.rho * self.thermal.c_theta)
            * dalpha
            * von_mises(&tau);
        let new = State {
            fp_inv,
            alpha,
            theta: old.theta + heating,
            dalpha,
        };
        // (real scalars: never in plane, the branch compiled away)
        let j = match D::NDERIV > 0 && real.in_plane {
            true => det_in::<true, _>(f),
            false => det(f),
        };
        let sigma = tau * j.recip();
        if !all_finite(&sigma) {
            return Err(MaterialError::NonFinite {
                what: "Cauchy stress",
            });
        }
        Ok((sigma, new))
    }

    /// The returns of a group of yielding points in lockstep, delivered as updates.
    fn return_group(
        &self,
        model: &ElastoPlastic<f64>,
        group: &mut YieldingGroup,
        (f, dt, old): (&[M3<D>], f64, &[State<D>]),
        deliver: &mut Deliver<D>,
        keep: Option<&mut Keep>,
    ) {
        let points = &group.points[..group.len];
        let index = group.index;
        let mut keep = keep.map(|keep| move |k: usize, c: &Converged| keep(index[k], c));
        let keep = keep.as_mut().map(|k| k as &mut Keep);
        return_principal::solve_batch(
            model,
            points,
            dt,
            &mut |k, returned| {
                let i = index[k];
                let result = returned.and_then(|r| self.after_return(&f[i], dt, &old[i], r.into()));
                deliver(i, result);
            },
            keep,
        );
        group.len = 0;
    }
}
