//! Flow stress laws τ_y(α, α̇, θ) in Kirchhoff stress [Pa].
//!
//! - `Voce`: rate-independent saturation plus linear hardening, eq. 4.51:
//!   τ_y = τ∞ + (τ0 − τ∞) exp(−η α) + h α.
//! - `JohnsonCook`: eq. 4.52, τ_y = [A + B α^N] [1 + C ln(α̇/α̇0)] [1 − θ*^M] with the rate
//!   term clamped to ≥ 1 (α̇ < α̇0 counts as α̇0) and θ* = (θ − θ0)/(θm − θ0) clamped to
//!   [0, 1], as common explicit codes do.

use crate::parameter_set;
use crate::scalar::{c, Scalar};

parameter_set! {
    /// Eq. 4.51 parameters.
    Voce {
        /// initial yield strength τ0 [Pa]
        tau0 => "tau0",
        /// saturated yield strength τ∞ [Pa]
        tau_inf => "tau_inf",
        /// exponential hardening rate η [-]
        eta => "eta",
        /// linear hardening modulus h [Pa]
        h => "h",
    }
}

parameter_set! {
    /// Eq. 4.52 parameters (θ0 lives with the thermal parameters).
    JohnsonCookLaw {
        /// initial yield strength A [Pa]
        a => "A",
        /// hardening modulus B [Pa]
        b => "B",
        /// hardening exponent N [-]
        n => "N",
        /// rate sensitivity C [-]
        c => "C",
        /// thermal softening exponent M [-]
        m => "M",
        /// reference plastic rate α̇0 [1/s]
        alpha_dot0 => "alpha_dot0",
        /// melting temperature θm [K]
        theta_m => "theta_m",
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FlowStress<D = f64> {
    Voce(Voce<D>),
    JohnsonCook(JohnsonCookLaw<D>),
}

impl<D: Scalar> FlowStress<D> {
    /// τ_y at accumulated plastic strain `alpha`, plastic rate `alpha_dot` [1/s] and
    /// temperature `theta` [K] (reference temperature `theta0`).
    pub fn tau_y(&self, alpha: D, alpha_dot: D, theta: D, theta0: D) -> D {
        match self {
            FlowStress::Voce(p) => {
                p.tau_inf + (p.tau0 - p.tau_inf) * (-p.eta * alpha).exp() + p.h * alpha
            }
            FlowStress::JohnsonCook(p) => {
                let hardening = if alpha.re() > 0.0 {
                    p.a + p.b * alpha.powd(p.n)
                } else {
                    p.a
                };
                let rate = if alpha_dot.re() > p.alpha_dot0.re() {
                    c::<D>(1.0) + p.c * (alpha_dot / p.alpha_dot0).ln()
                } else {
                    c::<D>(1.0)
                };
                hardening * rate * self.thermal_factor(theta, theta0)
            }
        }
    }

    /// The JC thermal factor 1 − θ*^M with θ* clamped to [0, 1]; 1 for Voce.
    pub fn thermal_factor(&self, theta: D, theta0: D) -> D {
        match self {
            FlowStress::Voce(_) => c::<D>(1.0),
            FlowStress::JohnsonCook(p) => {
                let theta_star = (theta - theta0) / (p.theta_m - theta0);
                if theta_star.re() <= 0.0 {
                    c::<D>(1.0)
                } else if theta_star.re() >= 1.0 {
                    c::<D>(0.0)
                } else {
                    c::<D>(1.0) - theta_star.powd(p.m)
                }
            }
        }
    }

    /// Initial yield strength (for scaling and elastic-limit estimates).
    pub fn initial_yield(&self) -> D {
        match self {
            FlowStress::Voce(p) => p.tau0,
            FlowStress::JohnsonCook(p) => p.a,
        }
    }

    pub fn map<E>(&self, f: impl FnMut(&'static str, D) -> E) -> FlowStress<E> {
        match self {
            FlowStress::Voce(p) => FlowStress::Voce(p.map(f)),
            FlowStress::JohnsonCook(p) => FlowStress::JohnsonCook(p.map(f)),
        }
    }

    pub fn names(&self) -> &'static [&'static str] {
        match self {
            FlowStress::Voce(_) => Voce::<D>::NAMES,
            FlowStress::JohnsonCook(_) => JohnsonCookLaw::<D>::NAMES,
        }
    }
}
