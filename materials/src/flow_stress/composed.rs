//! A flow-stress law composed of three factors, each chosen by name in a parameter file:
//!
//!   τ_y(α, α̇, θ) = g(α) · R(α̇) · T(θ)   [Pa]
//!
//! with the hardening g (`hardening`), the rate sensitivity R (`rate`) and the thermal
//! softening T (`softening`). Johnson-Cook (eq. 4.52) is g = power, R = johnson-cook,
//! T = johnson-cook; the composed form of it equals `FlowStress::JohnsonCook` to round-off
//! (tested), which keeps its own fast path. Every factor is written once over the scalar
//! type, so AD tangents and parameter sensitivities come from the same code.
//!
//! Parameter names are unique over the three factors (a fit names them alone): the
//! factors of one law share none.

use super::hardening::Hardening;
use super::rate::RateSensitivity;
use super::softening::ThermalSoftening;
use crate::scalar::Scalar;
use num_dual::Dual64;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Composed<D = f64> {
    pub hardening: Hardening<D>,
    pub rate: RateSensitivity<D>,
    pub softening: ThermalSoftening<D>,
}

impl<D: Scalar> Composed<D> {
    /// g(α) R(α̇).
    pub fn tau_y_athermal(&self, alpha: D, alpha_dot: D) -> D {
        self.hardening.at(alpha) * self.rate.factor(alpha_dot)
    }

    /// T(θ).
    pub fn thermal_factor(&self, theta: D, theta0: D) -> D {
        self.softening.factor(theta, theta0)
    }

    pub fn map<E>(&self, mut f: impl FnMut(&'static str, D) -> E) -> Composed<E> {
        Composed {
            hardening: self.hardening.map(&mut f),
            rate: self.rate.map(&mut f),
            softening: self.softening.map(&mut f),
        }
    }

    /// The parameter names of the three factors, in order.
    pub fn names(&self) -> Vec<&'static str> {
        [
            self.hardening.names(),
            self.rate.names(),
            self.softening.names(),
        ]
        .concat()
    }

    /// "hardening × rate × softening", the keywords of the three factors.
    pub fn describe(&self) -> String {
        format!(
            "{} × {} × {}",
            self.hardening.keyword(),
            self.rate.keyword(),
            self.softening.keyword()
        )
    }
}

impl Composed<f64> {
    /// τ_y and dτ_y/du at u = ln Δα along a return from α_n over a step Δt [s], with the
    /// thermal factor `thermal` frozen at θ_n: α = α_n + e^u, α̇ = e^u/Δt. The derivative is
    /// the dual part of one evaluation seeded with d(e^u)/du = e^u.
    pub fn along_increment(&self, alpha_n: f64, u: f64, dt: f64, thermal: f64) -> (f64, f64) {
        let dalpha = Dual64::new(u.exp(), u.exp());
        let law = self.map(|_, v| Dual64::from(v));
        let tau = law.tau_y_athermal(Dual64::from(alpha_n) + dalpha, dalpha / dt) * thermal;
        (tau.re, tau.eps)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::flow_stress::hardening::{Power, PowerVoce};
    use crate::flow_stress::rate::{CowperSymonds, HuhKang, LogRate};
    use crate::flow_stress::softening::{ExponentialSoftening, JcSoftening};
    use crate::flow_stress::{FlowStress, JohnsonCookLaw};

    pub(crate) fn huh_kang_power_voce() -> Composed {
        Composed {
            hardening: Hardening::PowerVoce(PowerVoce {
                a: 250e6,
                b: 900e6,
                n: 0.7,
                q: 150e6,
                beta: 25.0,
            }),
            rate: RateSensitivity::HuhKang(HuhKang {
                c: 0.004,
                c2: 0.0008,
                alpha_dot0: 1e-4,
            }),
            softening: ThermalSoftening::JohnsonCook(JcSoftening {
                m: 1.0,
                theta_m: 1673.0,
            }),
        }
    }

    pub(crate) fn cowper_symonds_exponential() -> Composed {
        Composed {
            hardening: Hardening::Power(Power {
                a: 800e6,
                b: 500e6,
                n: 0.3,
            }),
            rate: RateSensitivity::CowperSymonds(CowperSymonds { d: 4e4, p: 5.0 }),
            softening: ThermalSoftening::Exponential(ExponentialSoftening {
                lambda: 1.2e-3,
                theta_m: 1793.0,
            }),
        }
    }

    /// Power × johnson-cook × johnson-cook is eq. 4.52: the composed law equals the JC
    /// variant to round-off over strain, rate (below and above α̇0) and temperature (below
    /// θ0, between, above θm).
    #[test]
    fn the_johnson_cook_composition_is_eq_4_52() {
        let jc = JohnsonCookLaw {
            a: 801e6,
            b: 1531e6,
            n: 0.81,
            c: 0.036,
            m: 1.48,
            alpha_dot0: 5.6e-5,
            theta_m: 1793.15,
        };
        let composed = FlowStress::Composed(Composed {
            hardening: Hardening::Power(Power {
                a: jc.a,
                b: jc.b,
                n: jc.n,
            }),
            rate: RateSensitivity::JohnsonCook(LogRate {
                c: jc.c,
                alpha_dot0: jc.alpha_dot0,
            }),
            softening: ThermalSoftening::JohnsonCook(JcSoftening {
                m: jc.m,
                theta_m: jc.theta_m,
            }),
        });
        let jc = FlowStress::JohnsonCook(jc);
        for alpha in [0.0f64, 1e-6, 0.01, 0.3, 2.0] {
            for rate in [0.0f64, 1e-5, 1e-2, 1e3, 1e6] {
                for theta in [250.0f64, 293.15, 600.0, 1500.0, 1800.0] {
                    let (a, b) = (
                        jc.tau_y(alpha, rate, theta, 293.15),
                        composed.tau_y(alpha, rate, theta, 293.15),
                    );
                    assert!(
                        (a - b).abs() <= 1e-15 * a.abs(),
                        "{alpha} {rate} {theta}: {a} {b}"
                    );
                }
            }
        }
        assert_eq!(
            composed.names(),
            jc.names()
                .iter()
                .take(3)
                .chain(&["C", "alpha_dot0", "M", "theta_m"])
                .copied()
                .collect::<Vec<_>>()
        );
    }

    /// Each factor against its formula written out at one point, and its invariants:
    /// R(0) = R(α̇0) = 1 and R rising, T(θ0) = 1 and T = 0 from θm on, g(0) = A.
    #[test]
    fn each_factor_follows_its_formula() {
        let hk = huh_kang_power_voce();
        let x = (1e3f64 / 1e-4).ln();
        assert!((hk.rate.factor(1e3) - (1.0 + 0.004 * x + 0.0008 * x * x)).abs() < 1e-15);
        let g = 250e6 + 900e6 * 0.2f64.powf(0.7) + 150e6 * (1.0 - (-25.0f64 * 0.2).exp());
        assert!((hk.hardening.at(0.2) / g - 1.0).abs() < 1e-15);
        assert_eq!(hk.hardening.at(0.0), 250e6);
        let cs = cowper_symonds_exponential();
        let r = 1.0 + (2e3f64 / 4e4).powf(0.2);
        assert!((cs.rate.factor(2e3) - r).abs() < 1e-15);
        let t = (-1.2e-3f64 * (700.0 - 293.15)).exp();
        assert!((cs.thermal_factor(700.0, 293.15) - t).abs() < 1e-15);
        assert!(cs.thermal_factor(250.0, 293.15) > 1.0, "colder is stronger");
        for law in [hk, cs] {
            assert_eq!(law.rate.factor(0.0), 1.0);
            let rates = [1e-6, 1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6];
            let r: Vec<f64> = rates.iter().map(|&e| law.rate.factor(e)).collect();
            assert!(r.windows(2).all(|w| w[1] >= w[0] && w[0] >= 1.0), "{r:?}");
            assert_eq!(law.thermal_factor(293.15, 293.15), 1.0);
            assert_eq!(law.thermal_factor(1793.0, 293.15), 0.0);
        }
    }
}
