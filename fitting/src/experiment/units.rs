//! Units that experiment files may state, converted to SI at the edge:
//! `si = value · scale + offset` (the offset is non-zero only for °C and °F).
//!
//! Scalar metadata in an experiment TOML is a quantity string `"<number> <unit>"`,
//! e.g. `"20 mm"`, `"210 GPa"`, `"293.15 K"`; CSV columns name their unit separately.

/// Physical dimension of a column or a metadata value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    Time,
    Strain,
    Stress,
    /// An elastic modulus: the units of stress, a larger plausible magnitude.
    Modulus,
    Force,
    Length,
    Area,
    Density,
    Velocity,
    Temperature,
    StrainRate,
    Voltage,
}

/// (unit name, scale, offset) with `si = value · scale + offset`.
type UnitRow = (&'static str, f64, f64);

const TIME: &[UnitRow] = &[
    ("s", 1.0, 0.0),
    ("ms", 1e-3, 0.0),
    ("us", 1e-6, 0.0),
    ("µs", 1e-6, 0.0),
    ("ns", 1e-9, 0.0),
    ("min", 60.0, 0.0),
    ("h", 3600.0, 0.0),
];
const STRAIN: &[UnitRow] = &[
    ("1", 1.0, 0.0),
    ("%", 1e-2, 0.0),
    ("microstrain", 1e-6, 0.0),
    ("µε", 1e-6, 0.0),
];
const PSI_PA: f64 = 6_894.757_293_168_361;
const STRESS: &[UnitRow] = &[
    ("Pa", 1.0, 0.0),
    ("kPa", 1e3, 0.0),
    ("MPa", 1e6, 0.0),
    ("N/mm^2", 1e6, 0.0),
    ("GPa", 1e9, 0.0),
    ("psi", PSI_PA, 0.0),
    ("ksi", 1e3 * PSI_PA, 0.0),
];
const LBF_N: f64 = 4.448_221_615_260_5;
const FORCE: &[UnitRow] = &[
    ("N", 1.0, 0.0),
    ("kN", 1e3, 0.0),
    ("MN", 1e6, 0.0),
    ("lbf", LBF_N, 0.0),
    ("kip", 1e3 * LBF_N, 0.0),
];
const LENGTH: &[UnitRow] = &[
    ("m", 1.0, 0.0),
    ("cm", 1e-2, 0.0),
    ("mm", 1e-3, 0.0),
    ("um", 1e-6, 0.0),
    ("µm", 1e-6, 0.0),
    ("in", 0.0254, 0.0),
];
const AREA: &[UnitRow] = &[
    ("m^2", 1.0, 0.0),
    ("cm^2", 1e-4, 0.0),
    ("mm^2", 1e-6, 0.0),
    ("in^2", 0.0254 * 0.0254, 0.0),
];
const DENSITY: &[UnitRow] = &[("kg/m^3", 1.0, 0.0), ("g/cm^3", 1e3, 0.0)];
const VELOCITY: &[UnitRow] = &[("m/s", 1.0, 0.0), ("mm/s", 1e-3, 0.0), ("km/s", 1e3, 0.0)];
const TEMPERATURE: &[UnitRow] = &[
    ("K", 1.0, 0.0),
    ("degC", 1.0, 273.15),
    ("°C", 1.0, 273.15),
    ("degF", 5.0 / 9.0, 459.67 * 5.0 / 9.0),
    ("°F", 5.0 / 9.0, 459.67 * 5.0 / 9.0),
];
const STRAIN_RATE: &[UnitRow] = &[("1/s", 1.0, 0.0), ("1/min", 1.0 / 60.0, 0.0)];
const VOLTAGE: &[UnitRow] = &[("V", 1.0, 0.0), ("mV", 1e-3, 0.0)];

impl Dimension {
    fn table(self) -> &'static [UnitRow] {
        match self {
            Dimension::Time => TIME,
            Dimension::Strain => STRAIN,
            Dimension::Stress | Dimension::Modulus => STRESS,
            Dimension::Force => FORCE,
            Dimension::Length => LENGTH,
            Dimension::Area => AREA,
            Dimension::Density => DENSITY,
            Dimension::Velocity => VELOCITY,
            Dimension::Temperature => TEMPERATURE,
            Dimension::StrainRate => STRAIN_RATE,
            Dimension::Voltage => VOLTAGE,
        }
    }

    /// The accepted unit names, for error messages: `"s", "ms", ...`.
    pub fn accepted(self) -> String {
        let names: Vec<String> = self
            .table()
            .iter()
            .map(|(n, _, _)| format!("\"{n}\""))
            .collect();
        names.join(", ")
    }

    /// The largest magnitude [SI] that a measured column or a metadata quantity of this
    /// dimension can hold in a test of metals, and the likely mistake behind a larger
    /// value. Wide on purpose: it catches a mistyped cell and a wrong unit,
    /// not an unusual test.
    pub fn plausible_magnitude(self) -> (f64, &'static str) {
        match self {
            Dimension::Time => (1e8, "over three years: is a column in ms or µs declared as \"s\"?"),
            Dimension::Strain => (5.0, "a strain beyond 500 %: a mistyped value, or a column in % or microstrain declared as \"1\"?"),
            Dimension::Stress => (1e10, "beyond 10 GPa: a mistyped value, or a column in Pa declared as \"MPa\" or \"GPa\"?"),
            Dimension::Modulus => (1e12, "beyond 1000 GPa: a mistyped value, or a modulus in MPa declared as \"GPa\"?"),
            Dimension::Force => (1e8, "beyond 100 MN: a mistyped value, or a column in N declared as \"kN\"?"),
            Dimension::Length => (10.0, "beyond 10 m: a mistyped value, or a column in mm declared as \"m\"?"),
            Dimension::Voltage => (1e3, "beyond 1000 V: a mistyped value, or a column in mV declared as \"V\"?"),
            Dimension::Area => (1.0, "beyond 1 m²"),
            Dimension::Density => (1e5, "beyond 100 000 kg/m³"),
            Dimension::Velocity => (1e5, "beyond 100 km/s"),
            Dimension::Temperature => (1e4, "beyond 10 000 K"),
            Dimension::StrainRate => (1e9, "beyond 10⁹ 1/s"),
        }
    }

    /// The smallest peak magnitude [SI] that a whole measured column of this dimension
    /// reaches in a test of metals, and the likely mistake behind a smaller one; `None`
    /// where no such floor holds. A stress column that never reaches 1 MPa has not seen a
    /// metal yield.
    pub fn plausible_peak(self) -> Option<(f64, &'static str)> {
        match self {
            Dimension::Stress => Some((
                1e6,
                "below 1 MPa, where no metal yields: is a column in MPa declared as \"Pa\"?",
            )),
            _ => None,
        }
    }

    /// `(scale, offset)` of `unit`, or `None` if this dimension has no such unit.
    pub fn to_si(self, unit: &str) -> Option<UnitConversion> {
        self.table()
            .iter()
            .find(|(n, _, _)| *n == unit)
            .map(|&(_, scale, offset)| UnitConversion { scale, offset })
    }
}

/// An affine conversion to SI: `si = value · scale + offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitConversion {
    pub scale: f64,
    pub offset: f64,
}

impl UnitConversion {
    pub fn apply(self, value: f64) -> f64 {
        value * self.scale + self.offset
    }
}

/// Why a quantity string could not be read.
#[derive(Debug, Clone, PartialEq)]
pub enum QuantityProblem {
    /// Not `"<number> <unit>"`, or the number is not finite.
    Malformed,
    /// The unit is not one of the dimension's units.
    UnknownUnit(String),
}

/// Parse `"<number> <unit>"` (e.g. `"8 mm"`) into SI.
pub fn parse_quantity(text: &str, dimension: Dimension) -> Result<f64, QuantityProblem> {
    let text = text.trim();
    let (number, unit) = text
        .split_once(char::is_whitespace)
        .ok_or(QuantityProblem::Malformed)?;
    let value: f64 = number.parse().map_err(|_| QuantityProblem::Malformed)?;
    if !value.is_finite() {
        return Err(QuantityProblem::Malformed);
    }
    let unit = unit.trim();
    let conversion = dimension
        .to_si(unit)
        .ok_or_else(|| QuantityProblem::UnknownUnit(unit.to_string()))?;
    Ok(conversion.apply(value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_match_their_definitions() {
        // 1 ksi = 1000 lbf / in² = 1000 · 4.4482216152605 N / (0.0254 m)².
        let ksi = 1e3 * LBF_N / (0.0254 * 0.0254);
        let got = parse_quantity("1 ksi", Dimension::Stress).unwrap();
        assert!((got - ksi).abs() <= 1e-9 * ksi, "{got} vs {ksi}");
        assert_eq!(parse_quantity("8 mm", Dimension::Length), Ok(8e-3));
        assert_eq!(parse_quantity("2.5 %", Dimension::Strain), Ok(0.025));
        // 0 °C = 273.15 K, 212 °F = 373.15 K.
        assert_eq!(parse_quantity("0 degC", Dimension::Temperature), Ok(273.15));
        let boiling = parse_quantity("212 degF", Dimension::Temperature).unwrap();
        assert!((boiling - 373.15).abs() < 1e-9, "{boiling}");
    }

    #[test]
    fn malformed_and_unknown_units_are_reported() {
        assert_eq!(
            parse_quantity("8mm", Dimension::Length),
            Err(QuantityProblem::Malformed)
        );
        assert_eq!(
            parse_quantity("nan mm", Dimension::Length),
            Err(QuantityProblem::Malformed)
        );
        assert_eq!(
            parse_quantity("8 furlong", Dimension::Length),
            Err(QuantityProblem::UnknownUnit("furlong".into()))
        );
        // A unit of another dimension is unknown here.
        assert_eq!(
            parse_quantity("8 MPa", Dimension::Length),
            Err(QuantityProblem::UnknownUnit("MPa".into()))
        );
    }
}
