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

/// The flow stress at one plastic increment of a local solve (see `along_log_increment`).
#[derive(Debug, Clone, Copy)]
pub struct AtIncrement {
    /// Δα = e^u [-]
    pub dalpha: f64,
    /// τ_y [Pa]
    pub tau_y: f64,
    /// dτ_y/du [Pa]
    pub dtau_y_du: f64,
}

impl FlowStress<f64> {
    /// The u = ln Δα at which the JC rate term alone takes up the overstress ratio
    /// q/τ_y0 > 1 of a trial state (τ_y0 = τ_y(α_n, 0, θ_n)): 1 + C (u − ln(Δt α̇0)) = q/τ_y0.
    /// Hardening and the elastic relaxation q − 3G̃ Δα only lower the root of the return,
    /// so this bounds its ln Δα from above. `None` for a law without a rate term.
    pub fn log_increment_bound(&self, overstress: f64, dt: f64) -> Option<f64> {
        match self {
            FlowStress::JohnsonCook(p) if p.c > 0.0 => {
                Some((dt * p.alpha_dot0).ln() + (overstress - 1.0) / p.c)
            }
            _ => None,
        }
    }

    /// The law along a local solve in u = ln Δα (`return_principal`'s hot path):
    /// α = α_n + e^u, α̇ = e^u/Δt and θ = θ_n frozen, so the thermal factor is computed once and
    /// the JC rate term 1 + C (u − ln(Δt α̇0)) needs no logarithm. The returned closure
    /// gives Δα, τ_y and dτ_y/du; it equals `tau_y` to round-off (tested).
    pub fn along_log_increment(
        &self,
        alpha_n: f64,
        dt: f64,
        theta: f64,
        theta0: f64,
    ) -> impl Fn(f64) -> AtIncrement + '_ {
        let thermal = self.thermal_factor(theta, theta0);
        let ln_dalpha0 = match self {
            FlowStress::JohnsonCook(p) => (dt * p.alpha_dot0).ln(),
            FlowStress::Voce(_) => 0.0,
        };
        move |u: f64| {
            let dalpha = u.exp();
            let alpha = alpha_n + dalpha;
            let (tau_y, dtau_y_du) = match self {
                FlowStress::Voce(p) => {
                    let decay = (p.tau0 - p.tau_inf) * (-p.eta * alpha).exp();
                    (
                        p.tau_inf + decay + p.h * alpha,
                        dalpha * (p.h - p.eta * decay),
                    )
                }
                FlowStress::JohnsonCook(p) => {
                    let power = alpha.powf(p.n);
                    let hardening = p.a + p.b * power;
                    let d_hardening = p.b * p.n * power / alpha * dalpha;
                    let excess = u - ln_dalpha0;
                    let (rate, d_rate) = if excess > 0.0 {
                        (1.0 + p.c * excess, p.c)
                    } else {
                        (1.0, 0.0)
                    };
                    (
                        hardening * rate * thermal,
                        (d_hardening * rate + hardening * d_rate) * thermal,
                    )
                }
            };
            AtIncrement {
                dalpha,
                tau_y,
                dtau_y_du,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::Dual64;

    #[test]
    fn along_log_increment_matches_tau_y_and_its_derivative() {
        let laws = [
            FlowStress::JohnsonCook(JohnsonCookLaw {
                a: 800e6,
                b: 1500e6,
                n: 0.3,
                c: 0.03,
                m: 1.2,
                alpha_dot0: 1e-3,
                theta_m: 1800.0,
            }),
            FlowStress::Voce(Voce {
                tau0: 300e6,
                tau_inf: 450e6,
                eta: 12.0,
                h: 1e8,
            }),
        ];
        let (alpha_n, dt, theta, theta0) = (0.05, 1e-5, 400.0, 293.15);
        for law in &laws {
            let along = law.along_log_increment(alpha_n, dt, theta, theta0);
            let dual = law.map(|_, v| Dual64::from(v));
            // Below and above the rate kink Δα = Δt α̇0 = 1e-8.
            for dalpha in [1e-10, 3e-9, 2e-8, 1e-4, 0.05] {
                let u = f64::ln(dalpha);
                let at = along(u);
                assert_eq!(at.dalpha, u.exp());
                let (tau, dtau_du) = (at.tau_y, at.dtau_y_du);
                let d = Dual64::new(dalpha, dalpha); // d/du of e^u
                let expected = dual.tau_y(
                    Dual64::from(alpha_n) + d,
                    d / dt,
                    Dual64::from(theta),
                    Dual64::from(theta0),
                );
                assert!(
                    (tau / expected.re - 1.0).abs() < 1e-13,
                    "τ_y {tau} vs {}",
                    expected.re
                );
                assert!(
                    (dtau_du - expected.eps).abs() <= 1e-9 * expected.eps.abs() + 1e-6,
                    "dτ_y/du {dtau_du} vs {}",
                    expected.eps
                );
            }
        }
    }

    /// The rate-only increment bounds the root of the scalar return q − 3G e^u = τ_y(u)
    /// (found by bisection) from above, for small and large overstress.
    #[test]
    fn log_increment_bound_lies_above_the_scalar_return() {
        let law = FlowStress::JohnsonCook(JohnsonCookLaw {
            a: 90e6,
            b: 292e6,
            n: 0.31,
            c: 0.025,
            m: 1.09,
            alpha_dot0: 1.0,
            theta_m: 1356.0,
        });
        let (alpha_n, dt, theta, theta0, three_g) = (0.05, 3e-8, 400.0, 293.15, 3.0 * 46e9);
        let along = law.along_log_increment(alpha_n, dt, theta, theta0);
        let tau_y0 = law.tau_y(alpha_n, 0.0, theta, theta0);
        for overstress in [1.001, 1.05, 1.3, 3.0] {
            let q = overstress * tau_y0;
            let f = |u: f64| q - three_g * u.exp() - along(u).tau_y;
            let (mut below, mut above) = (-60.0, (q / three_g).ln());
            assert!(f(below) > 0.0 && f(above) < 0.0);
            for _ in 0..200 {
                let mid = 0.5 * (below + above);
                if f(mid) > 0.0 {
                    below = mid;
                } else {
                    above = mid;
                }
            }
            let bound = law
                .log_increment_bound(overstress, dt)
                .expect("JC has a rate term");
            assert!(
                below <= bound,
                "q/τ_y0 = {overstress}: root {below} above bound {bound}"
            );
        }
        let voce = FlowStress::Voce(Voce {
            tau0: 300e6,
            tau_inf: 450e6,
            eta: 12.0,
            h: 1e8,
        });
        assert_eq!(voce.log_increment_bound(1.1, dt), None);
    }
}
