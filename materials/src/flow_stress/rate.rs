//! Strain-rate sensitivity R(α̇) [-] of a composed flow-stress law (`composed`), α̇ the
//! plastic strain rate [1/s]:
//!
//! - `None`: rate independent, R = 1.
//! - `JohnsonCook`: R = 1 + C ln(α̇/α̇0) (Johnson & Cook 1983; eq. 4.52's second factor).
//! - `HuhKang`: R = 1 + C ln(α̇/α̇0) + C2 ln²(α̇/α̇0), the quadratic-logarithmic form
//!   (Huh & Kang, Int. J. Vehicle Design 30, 2002, 1), which lets the sensitivity grow
//!   with the rate: small over the quasi-static decades, steep at impact rates.
//! - `CowperSymonds`: R = 1 + (α̇/D)^(1/p) (Cowper & Symonds, Brown Univ. report 28,
//!   1957), a power of the rate with no reference rate.
//!
//! The logarithmic forms count a rate below α̇0 as α̇0 (R = 1), as eq. 4.52 does in common
//! explicit codes. Invariant: R(0) = 1 and R ≥ 1 is non-decreasing in α̇ for every
//! parameter set a file may give (C, C2 ≥ 0; D, p > 0).

use crate::parameter_set;
use crate::scalar::{c, Scalar};

parameter_set! {
    /// 1 + C ln(α̇/α̇0).
    LogRate {
        /// rate sensitivity C [-]
        c => "C",
        /// reference plastic rate α̇0 [1/s]
        alpha_dot0 => "alpha_dot0",
    }
}

parameter_set! {
    /// 1 + C ln(α̇/α̇0) + C2 ln²(α̇/α̇0).
    HuhKang {
        /// linear rate sensitivity C [-]
        c => "C",
        /// quadratic rate sensitivity C2 [-]
        c2 => "C2",
        /// reference plastic rate α̇0 [1/s]
        alpha_dot0 => "alpha_dot0",
    }
}

parameter_set! {
    /// 1 + (α̇/D)^(1/p).
    CowperSymonds {
        /// rate constant D [1/s]
        d => "D_cs",
        /// rate exponent p [-]
        p => "p_cs",
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RateSensitivity<D = f64> {
    None,
    JohnsonCook(LogRate<D>),
    HuhKang(HuhKang<D>),
    CowperSymonds(CowperSymonds<D>),
}

impl<D: Scalar> RateSensitivity<D> {
    /// The law's name in a parameter file.
    pub fn keyword(&self) -> &'static str {
        match self {
            RateSensitivity::None => "none",
            RateSensitivity::JohnsonCook(_) => "johnson-cook",
            RateSensitivity::HuhKang(_) => "huh-kang",
            RateSensitivity::CowperSymonds(_) => "cowper-symonds",
        }
    }

    /// R(α̇) [-].
    pub fn factor(&self, alpha_dot: D) -> D {
        let one = c::<D>(1.0);
        match self {
            RateSensitivity::None => one,
            RateSensitivity::JohnsonCook(p) if alpha_dot.re() > p.alpha_dot0.re() => {
                one + p.c * (alpha_dot / p.alpha_dot0).ln()
            }
            RateSensitivity::HuhKang(p) if alpha_dot.re() > p.alpha_dot0.re() => {
                let x = (alpha_dot / p.alpha_dot0).ln();
                one + (p.c + p.c2 * x) * x
            }
            RateSensitivity::CowperSymonds(p) if alpha_dot.re() > 0.0 => {
                one + (alpha_dot / p.d).powd(p.p.recip())
            }
            _ => one,
        }
    }

    pub fn map<E>(&self, f: impl FnMut(&'static str, D) -> E) -> RateSensitivity<E> {
        match self {
            RateSensitivity::None => RateSensitivity::None,
            RateSensitivity::JohnsonCook(p) => RateSensitivity::JohnsonCook(p.map(f)),
            RateSensitivity::HuhKang(p) => RateSensitivity::HuhKang(p.map(f)),
            RateSensitivity::CowperSymonds(p) => RateSensitivity::CowperSymonds(p.map(f)),
        }
    }

    pub fn names(&self) -> &'static [&'static str] {
        match self {
            RateSensitivity::None => &[],
            RateSensitivity::JohnsonCook(_) => LogRate::<D>::NAMES,
            RateSensitivity::HuhKang(_) => HuhKang::<D>::NAMES,
            RateSensitivity::CowperSymonds(_) => CowperSymonds::<D>::NAMES,
        }
    }
}

impl RateSensitivity<f64> {
    /// The law named `keyword` with parameters `value(name)`, `None` for an unknown name.
    pub fn from_keyword(keyword: &str, value: impl Fn(&str) -> f64) -> Option<Self> {
        Some(match keyword {
            "none" => RateSensitivity::None,
            "johnson-cook" => RateSensitivity::JohnsonCook(LogRate::from_names(value)),
            "huh-kang" => RateSensitivity::HuhKang(HuhKang::from_names(value)),
            "cowper-symonds" => RateSensitivity::CowperSymonds(CowperSymonds::from_names(value)),
            _ => return None,
        })
    }

    /// The parameter names of the law named `keyword`.
    pub fn names_of(keyword: &str) -> Option<&'static [&'static str]> {
        Self::from_keyword(keyword, |_| 0.0).map(|r| r.names())
    }
}

/// The laws a file may name.
pub const KEYWORDS: [&str; 4] = ["none", "johnson-cook", "huh-kang", "cowper-symonds"];
