//! Every material parameter by name, in one table: the parameter-file section it is
//! written in, its quantity (so its SI unit, and how a solver card or a report shows it),
//! and the values a parameter file may give it (for E and ρ: a metal's, the bounds of a
//! Johnson-Cook file; θm must also lie above θ0, which the reader checks). The reader
//! (`param_file`), the solver cards and the fit reports all read it.

/// What a parameter measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    Stress,
    Dimensionless,
    Density,
    Rate,
    SpecificHeat,
    Temperature,
    ThermalExpansion,
    InverseTemperature,
}

impl Quantity {
    /// The SI unit the code works in.
    pub fn si_unit(self) -> &'static str {
        match self {
            Quantity::Stress => "Pa",
            Quantity::Dimensionless => "1",
            Quantity::Density => "kg/m^3",
            Quantity::Rate => "1/s",
            Quantity::SpecificHeat => "J/(kg K)",
            Quantity::Temperature => "K",
            Quantity::ThermalExpansion | Quantity::InverseTemperature => "1/K",
        }
    }
}

/// One parameter of the table.
#[derive(Debug, Clone, Copy)]
pub struct Parameter {
    pub name: &'static str,
    /// Its section in a parameter file.
    pub section: &'static str,
    pub quantity: Quantity,
    /// What a parameter file may give it.
    pub accepted: Range,
}

const fn entry(
    name: &'static str,
    section: &'static str,
    quantity: Quantity,
    accepted: Range,
) -> Parameter {
    Parameter {
        name,
        section,
        quantity,
        accepted,
    }
}

use Quantity::*;

/// Every parameter of every model (Neo-Hooke: elastic; J2: elastic, voce; Johnson-Cook:
/// elastic, johnson_cook, thermal). A composed law (`flow_stress::composed`) takes its
/// factors' parameters from the same entries (the JC and Voce names among them) but reads
/// each in the section of its factor (`hardening`, `rate`, `softening`); the entries only
/// composed laws have stand in that section here.
pub const TABLE: [Parameter; 24] = [
    entry(
        "E",
        "elastic",
        Stress,
        Range::plausible(
            1e9,
            1e12,
            "a metal's E in Pa, e.g. 210e9 for steel (GPa or MPa given?)",
        ),
    ),
    entry("nu", "elastic", Dimensionless, Range::open(-1.0, 0.5)),
    entry(
        "rho",
        "elastic",
        Density,
        Range::plausible(
            500.0,
            25e3,
            "a metal's density in kg/m^3, e.g. 7850 for steel (g/cm^3 given?)",
        ),
    ),
    entry("tau0", "voce", Stress, Range::positive()),
    entry("tau_inf", "voce", Stress, Range::positive()),
    entry("eta", "voce", Dimensionless, Range::non_negative()),
    entry("h", "voce", Stress, Range::non_negative()),
    entry(
        "A",
        "johnson_cook",
        Stress,
        Range::plausible(
            1e6,
            1e10,
            "a yield stress in Pa, e.g. 8e8 for 800 MPa (MPa given?)",
        ),
    ),
    entry(
        "B",
        "johnson_cook",
        Stress,
        Range::plausible(
            0.0,
            1e10,
            "a hardening modulus in Pa, e.g. 5e8 for 500 MPa (MPa given?)",
        ),
    ),
    entry("N", "johnson_cook", Dimensionless, Range::open(0.0, 5.0)),
    entry("C", "johnson_cook", Dimensionless, Range::non_negative()),
    entry("M", "johnson_cook", Dimensionless, Range::positive()),
    entry("alpha_dot0", "johnson_cook", Rate, Range::positive()),
    entry("theta_m", "johnson_cook", Temperature, Range::positive()),
    entry(
        "Q",
        "hardening",
        Stress,
        Range::plausible(
            0.0,
            1e10,
            "a saturating hardening in Pa, e.g. 2e8 for 200 MPa (MPa given?)",
        ),
    ),
    entry("beta", "hardening", Dimensionless, Range::non_negative()),
    entry("C2", "rate", Dimensionless, Range::non_negative()),
    entry("D_cs", "rate", Rate, Range::positive()),
    entry("p_cs", "rate", Dimensionless, Range::positive()),
    entry(
        "lambda_theta",
        "softening",
        InverseTemperature,
        Range::plausible(
            0.0,
            0.1,
            "a softening coefficient in 1/K, e.g. 1e-3 (%/K or per 100 K given?)",
        ),
    ),
    entry("theta0", "thermal", Temperature, Range::positive()),
    entry("c_theta", "thermal", SpecificHeat, Range::positive()),
    entry(
        "alpha_sigma",
        "thermal",
        ThermalExpansion,
        Range::non_negative(),
    ),
    entry(
        "gamma_tq",
        "thermal",
        Dimensionless,
        Range::closed(0.0, 1.0),
    ),
];

/// The table's entry for `name`.
pub fn parameter(name: &str) -> Option<&'static Parameter> {
    TABLE.iter().find(|p| p.name == name)
}

/// What a parameter file may give `name` (a name of the table).
pub(crate) fn accepted(name: &str) -> Range {
    parameter(name)
        .map(|p| p.accepted)
        .expect("a parameter of the table")
}

/// Allowed open/closed interval of a field.
#[derive(Debug, Clone, Copy)]
pub struct Range {
    pub(crate) lo: f64,
    pub(crate) lo_open: bool,
    pub(crate) hi: f64,
    pub(crate) hi_open: bool,
    /// The likely mistake behind a value outside, for the message ("" for none).
    pub(crate) hint: &'static str,
}

impl Range {
    pub(crate) const fn positive() -> Self {
        Range {
            lo: 0.0,
            lo_open: true,
            hi: f64::INFINITY,
            hi_open: true,
            hint: "",
        }
    }
    pub(crate) const fn non_negative() -> Self {
        Range {
            lo: 0.0,
            lo_open: false,
            hi: f64::INFINITY,
            hi_open: true,
            hint: "",
        }
    }
    pub(crate) const fn closed(lo: f64, hi: f64) -> Self {
        Range {
            lo,
            lo_open: false,
            hi,
            hi_open: false,
            hint: "",
        }
    }
    pub(crate) const fn open(lo: f64, hi: f64) -> Self {
        Range {
            lo,
            lo_open: true,
            hi,
            hi_open: true,
            hint: "",
        }
    }
    /// A closed range with the likely mistake behind a value outside it: the metal bounds
    /// of a Johnson-Cook file (E = 224.2 "Pa" ran and gave σ = 0).
    pub(crate) const fn plausible(lo: f64, hi: f64, hint: &'static str) -> Self {
        Range {
            hint,
            ..Range::closed(lo, hi)
        }
    }
    pub fn contains(&self, v: f64) -> bool {
        let above = if self.lo_open {
            v > self.lo
        } else {
            v >= self.lo
        };
        let below = if self.hi_open {
            v < self.hi
        } else {
            v <= self.hi
        };
        v.is_finite() && above && below
    }
    pub fn describe(&self) -> String {
        format!(
            "{}{}, {}{}",
            if self.lo_open { "(" } else { "[" },
            self.lo,
            if self.hi.is_infinite() {
                "inf".to_string()
            } else {
                self.hi.to_string()
            },
            if self.hi_open { ")" } else { "]" }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every parameter of every model is in the table once, and only those.
    #[test]
    fn the_table_holds_every_model_parameter_once() {
        use crate::elastic::Elastic;
        use crate::flow_stress::hardening::{Power, PowerVoce};
        use crate::flow_stress::rate::{CowperSymonds, HuhKang, LogRate};
        use crate::flow_stress::softening::{ExponentialSoftening, JcSoftening};
        use crate::flow_stress::{JohnsonCookLaw, Voce};
        use crate::plasticity::Thermal;
        let mut names: Vec<&str> = [
            Elastic::<f64>::NAMES,
            Voce::<f64>::NAMES,
            JohnsonCookLaw::<f64>::NAMES,
            Thermal::<f64>::NAMES,
            Power::<f64>::NAMES,
            PowerVoce::<f64>::NAMES,
            LogRate::<f64>::NAMES,
            HuhKang::<f64>::NAMES,
            CowperSymonds::<f64>::NAMES,
            JcSoftening::<f64>::NAMES,
            ExponentialSoftening::<f64>::NAMES,
        ]
        .concat();
        names.sort_unstable();
        names.dedup();
        let mut table: Vec<&str> = TABLE.iter().map(|p| p.name).collect();
        names.sort_unstable();
        table.sort_unstable();
        assert_eq!(names, table);
    }
}
