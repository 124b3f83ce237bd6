//! Strain hardening g(α) [Pa] of a composed flow-stress law (`composed`), α the
//! accumulated plastic strain [-]:
//!
//! - `Power`: the Johnson-Cook hardening, g = A + B α^N (Johnson & Cook 1983; eq. 4.52's
//!   first factor), unbounded.
//! - `Voce`: saturation plus linear hardening, g = τ∞ + (τ0 − τ∞) e^(−ηα) + h α (Voce,
//!   J. Inst. Metals 74, 1948, 537; eq. 4.51).
//! - `PowerVoce`: the additive mixed form g = A + B α^N + Q (1 − e^(−βα)): a saturating
//!   term for the early, fast hardening beside the power law of large strains (cf. the
//!   weighted Swift-Voce law of Sung, Kim & Wagoner, Int. J. Plast. 26, 2010, 1746).
//!
//! Invariant: g(0) is the initial yield strength and g > 0 for every parameter set a file
//! may give (all moduli non-negative, A, τ0 positive).

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
    /// The Johnson-Cook hardening A + B α^N.
    Power {
        /// initial yield strength A [Pa]
        a => "A",
        /// hardening modulus B [Pa]
        b => "B",
        /// hardening exponent N [-]
        n => "N",
    }
}

parameter_set! {
    /// A + B α^N + Q (1 − e^(−βα)).
    PowerVoce {
        /// initial yield strength A [Pa]
        a => "A",
        /// hardening modulus B [Pa]
        b => "B",
        /// hardening exponent N [-]
        n => "N",
        /// saturating hardening Q [Pa]
        q => "Q",
        /// saturation rate β [-]
        beta => "beta",
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Hardening<D = f64> {
    Power(Power<D>),
    Voce(Voce<D>),
    PowerVoce(PowerVoce<D>),
}

/// A + B α^N, with α^N = 0 at α = 0 (its derivative there is infinite for N < 1).
pub(crate) fn power_law<D: Scalar>(a: D, b: D, n: D, alpha: D) -> D {
    if alpha.re() > 0.0 {
        a + b * alpha.powd(n)
    } else {
        a
    }
}

impl<D: Scalar> Hardening<D> {
    /// The law's name in a parameter file.
    pub fn keyword(&self) -> &'static str {
        match self {
            Hardening::Power(_) => "power",
            Hardening::Voce(_) => "voce",
            Hardening::PowerVoce(_) => "power-voce",
        }
    }

    /// g(α) [Pa].
    pub fn at(&self, alpha: D) -> D {
        match self {
            Hardening::Power(p) => power_law(p.a, p.b, p.n, alpha),
            Hardening::Voce(p) => {
                p.tau_inf + (p.tau0 - p.tau_inf) * (-p.eta * alpha).exp() + p.h * alpha
            }
            Hardening::PowerVoce(p) => {
                power_law(p.a, p.b, p.n, alpha) + p.q * (c::<D>(1.0) - (-p.beta * alpha).exp())
            }
        }
    }

    pub fn map<E>(&self, f: impl FnMut(&'static str, D) -> E) -> Hardening<E> {
        match self {
            Hardening::Power(p) => Hardening::Power(p.map(f)),
            Hardening::Voce(p) => Hardening::Voce(p.map(f)),
            Hardening::PowerVoce(p) => Hardening::PowerVoce(p.map(f)),
        }
    }

    pub fn names(&self) -> &'static [&'static str] {
        match self {
            Hardening::Power(_) => Power::<D>::NAMES,
            Hardening::Voce(_) => Voce::<D>::NAMES,
            Hardening::PowerVoce(_) => PowerVoce::<D>::NAMES,
        }
    }
}

impl Hardening<f64> {
    /// The law named `keyword` with parameters `value(name)`, `None` for an unknown name.
    pub fn from_keyword(keyword: &str, value: impl Fn(&str) -> f64) -> Option<Self> {
        Some(match keyword {
            "power" => Hardening::Power(Power::from_names(value)),
            "voce" => Hardening::Voce(Voce::from_names(value)),
            "power-voce" => Hardening::PowerVoce(PowerVoce::from_names(value)),
            _ => return None,
        })
    }

    /// The parameter names of the law named `keyword`.
    pub fn names_of(keyword: &str) -> Option<&'static [&'static str]> {
        Self::from_keyword(keyword, |_| 0.0).map(|h| h.names())
    }
}

/// The laws a file may name.
pub const KEYWORDS: [&str; 3] = ["power", "voce", "power-voce"];
