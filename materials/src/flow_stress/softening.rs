//! Thermal softening T(θ) [-] of a composed flow-stress law (`composed`), θ the
//! temperature and θ0 the reference temperature [K]:
//!
//! - `None`: T = 1.
//! - `JohnsonCook`: T = 1 − θ*^M, θ* = (θ − θ0)/(θm − θ0) clamped to [0, 1] (Johnson &
//!   Cook 1983; eq. 4.52's third factor).
//! - `Exponential`: T = exp(−λ (θ − θ0)) below θm and 0 from θm on: the thermal factor of
//!   the Zerilli-Armstrong laws at a fixed rate (Zerilli & Armstrong, J. Appl. Phys. 61,
//!   1987, 1816). Unlike JC's it keeps softening without a kink at θ0 and rises above 1
//!   below θ0 (colder is stronger); it drops to zero at melting.
//!
//! Invariant: T(θ0) = 1, T ≥ 0, T = 0 at and above θm (where the law has one).

use crate::parameter_set;
use crate::scalar::{c, Scalar};

parameter_set! {
    /// 1 − θ*^M.
    JcSoftening {
        /// thermal softening exponent M [-]
        m => "M",
        /// melting temperature θm [K]
        theta_m => "theta_m",
    }
}

parameter_set! {
    /// exp(−λ (θ − θ0)) below θm.
    ExponentialSoftening {
        /// softening coefficient λ [1/K]
        lambda => "lambda_theta",
        /// melting temperature θm [K]
        theta_m => "theta_m",
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ThermalSoftening<D = f64> {
    None,
    JohnsonCook(JcSoftening<D>),
    Exponential(ExponentialSoftening<D>),
}

/// 1 − θ*^M with θ* = (θ − θ0)/(θm − θ0) clamped to [0, 1].
pub fn johnson_cook<D: Scalar>(m: D, theta_m: D, theta: D, theta0: D) -> D {
    let theta_star = (theta - theta0) / (theta_m - theta0);
    if theta_star.re() <= 0.0 {
        c::<D>(1.0)
    } else if theta_star.re() >= 1.0 {
        c::<D>(0.0)
    } else {
        c::<D>(1.0) - theta_star.powd(m)
    }
}

impl<D: Scalar> ThermalSoftening<D> {
    /// The law's name in a parameter file.
    pub fn keyword(&self) -> &'static str {
        match self {
            ThermalSoftening::None => "none",
            ThermalSoftening::JohnsonCook(_) => "johnson-cook",
            ThermalSoftening::Exponential(_) => "exponential",
        }
    }

    /// T(θ) [-] with reference temperature `theta0`.
    pub fn factor(&self, theta: D, theta0: D) -> D {
        match self {
            ThermalSoftening::None => c::<D>(1.0),
            ThermalSoftening::JohnsonCook(p) => johnson_cook(p.m, p.theta_m, theta, theta0),
            ThermalSoftening::Exponential(p) if theta.re() < p.theta_m.re() => {
                (-p.lambda * (theta - theta0)).exp()
            }
            ThermalSoftening::Exponential(_) => c::<D>(0.0),
        }
    }

    pub fn map<E>(&self, f: impl FnMut(&'static str, D) -> E) -> ThermalSoftening<E> {
        match self {
            ThermalSoftening::None => ThermalSoftening::None,
            ThermalSoftening::JohnsonCook(p) => ThermalSoftening::JohnsonCook(p.map(f)),
            ThermalSoftening::Exponential(p) => ThermalSoftening::Exponential(p.map(f)),
        }
    }

    pub fn names(&self) -> &'static [&'static str] {
        match self {
            ThermalSoftening::None => &[],
            ThermalSoftening::JohnsonCook(_) => JcSoftening::<D>::NAMES,
            ThermalSoftening::Exponential(_) => ExponentialSoftening::<D>::NAMES,
        }
    }
}

impl ThermalSoftening<f64> {
    /// The law named `keyword` with parameters `value(name)`, `None` for an unknown name.
    pub fn from_keyword(keyword: &str, value: impl Fn(&str) -> f64) -> Option<Self> {
        Some(match keyword {
            "none" => ThermalSoftening::None,
            "johnson-cook" => ThermalSoftening::JohnsonCook(JcSoftening::from_names(value)),
            "exponential" => ThermalSoftening::Exponential(ExponentialSoftening::from_names(value)),
            _ => return None,
        })
    }

    /// The parameter names of the law named `keyword`.
    pub fn names_of(keyword: &str) -> Option<&'static [&'static str]> {
        Self::from_keyword(keyword, |_| 0.0).map(|s| s.names())
    }
}

/// The laws a file may name.
pub const KEYWORDS: [&str; 3] = ["none", "johnson-cook", "exponential"];
