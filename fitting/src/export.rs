//! Johnson-Cook parameter sets written for the codes that consume them: an Abaqus material
//! block (`*PLASTIC, HARDENING=JOHNSON COOK` with `*RATE DEPENDENT, TYPE=JOHNSON COOK`), an
//! LS-DYNA `*MAT_JOHNSON_COOK` with its `*EOS_LINEAR_POLYNOMIAL`, and a generic JSON card
//! (every value with its unit), in a stated unit system.
//!
//! The model is the one of `materials::flow_stress` (eq. 4.52):
//! σ_y = [A + B ε_p^N] [1 + C ln(ε̇_p/ε̇0)] [1 − θ*^M], θ* = (θ − θ0)/(θm − θ0), with the rate
//! term 1 below ε̇0 and θ* clamped to [0, 1], which is Abaqus's form with the transition
//! temperature θ0. mpw's yield stress is a Kirchhoff stress, the codes' a Cauchy stress:
//! they differ by the elastic volume change J_e = 1 − p/K (0.6 % at 1 GPa of pressure in
//! steel), which the card header says. Temperatures are in K in every unit system.
//!
//! The LS-DYNA card sets every field that could erode an element or cut its pressure
//! instead of leaving it to the code's defaults (which this project could not check
//! against the keyword manual): failure strain D1 = 1e20 with D2-D5 = 0, pressure cutoff
//! PC = -1e20 with SPALL = 1. mpw identifies no failure model; the user adds theirs.

use crate::fit::levels::model::Material;
use anyhow::{bail, Result};
use materials::material::Model;
use materials::parameters::{parameter, Quantity};
use std::fmt::Write as _;

/// A consistent unit system: factors from SI to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Units {
    pub name: &'static str,
    /// Length, time, mass, force, stress, energy (for the header).
    pub description: &'static str,
    pub stress: f64,
    pub density: f64,
    pub rate: f64,
    pub specific_heat: f64,
    pub stress_unit: &'static str,
    pub density_unit: &'static str,
    pub rate_unit: &'static str,
    pub specific_heat_unit: &'static str,
}

pub const UNIT_SYSTEMS: [Units; 3] = [
    Units {
        name: "si",
        description: "m, s, kg, N, Pa, J, K",
        stress: 1.0,
        density: 1.0,
        rate: 1.0,
        specific_heat: 1.0,
        stress_unit: "Pa",
        density_unit: "kg/m^3",
        rate_unit: "1/s",
        specific_heat_unit: "J/(kg K)",
    },
    Units {
        // 1 kg/m³ = 1e-3 t / 1e9 mm³; 1 J/(kg K) = 1e3 mJ / 1e-3 t.
        name: "mm-s-tonne",
        description: "mm, s, tonne, N, MPa, mJ, K",
        stress: 1e-6,
        density: 1e-12,
        rate: 1.0,
        specific_heat: 1e6,
        stress_unit: "MPa",
        density_unit: "t/mm^3",
        rate_unit: "1/s",
        specific_heat_unit: "mJ/(t K)",
    },
    Units {
        // 1 kg/m³ = 1e-9 kg/mm³; kN·mm = J, so J/(kg K) is unchanged.
        name: "mm-ms-kg",
        description: "mm, ms, kg, kN, GPa, J, K",
        stress: 1e-9,
        density: 1e-9,
        rate: 1e-3,
        specific_heat: 1.0,
        stress_unit: "GPa",
        density_unit: "kg/mm^3",
        rate_unit: "1/ms",
        specific_heat_unit: "J/(kg K)",
    },
];

/// The unit system named `name`.
pub fn units(name: &str) -> Result<Units> {
    match UNIT_SYSTEMS.iter().find(|u| u.name == name) {
        Some(u) => Ok(*u),
        None => {
            let names: Vec<&str> = UNIT_SYSTEMS.iter().map(|u| u.name).collect();
            bail!("unit system \"{name}\": expected one of {names:?}")
        }
    }
}

/// The parameters of a Johnson-Cook card, in card order (quantities and units from
/// `materials::parameters`).
const FIELDS: [&str; 14] = [
    "E",
    "nu",
    "rho",
    "A",
    "B",
    "N",
    "C",
    "M",
    "alpha_dot0",
    "theta_m",
    "theta0",
    "c_theta",
    "alpha_sigma",
    "gamma_tq",
];

impl Units {
    fn factor(&self, quantity: Quantity) -> (f64, &'static str) {
        match quantity {
            Quantity::Stress => (self.stress, self.stress_unit),
            Quantity::Density => (self.density, self.density_unit),
            Quantity::Rate => (self.rate, self.rate_unit),
            Quantity::SpecificHeat => (self.specific_heat, self.specific_heat_unit),
            Quantity::Temperature
            | Quantity::Dimensionless
            | Quantity::ThermalExpansion
            | Quantity::InverseTemperature => (1.0, quantity.si_unit()),
        }
    }
}

/// The value of parameter `name` of `m` in `units`, and its unit.
pub fn value(m: &Material, name: &str, units: &Units) -> Result<(f64, &'static str)> {
    let Some(quantity) = (FIELDS.contains(&name))
        .then(|| parameter(name).map(|p| p.quantity))
        .flatten()
    else {
        bail!("`{name}` is not an exported parameter");
    };
    let Some(si) = m.param(name) else {
        bail!("the material has no parameter `{name}` (a Johnson-Cook model is needed)");
    };
    let (factor, unit) = units.factor(quantity);
    Ok((si * factor, unit))
}

/// The first words of a Johnson-Cook card's header.
const JOHNSON_COOK: &str = "Johnson-Cook parameters";

/// Refuse a law a Johnson-Cook card cannot carry.
fn johnson_cook_only(m: &Material) -> Result<()> {
    if m.flow.as_johnson_cook().is_none() {
        bail!(
            "the flow-stress law is {}, not Johnson-Cook: a Johnson-Cook card cannot carry it (a tabulated card can: abaqus-table, lsdyna-table)",
            m.flow.describe()
        );
    }
    Ok(())
}

/// Where a card's parameters come from: a sentence naming the files, and the caveats a
/// user of the card must read (the ranges a fit covered, what it did not identify).
#[derive(Debug, Clone, Default)]
pub struct Provenance {
    pub source: String,
    pub caveats: Vec<String>,
}

impl Provenance {
    /// Parameters from `source` alone, without caveats.
    pub fn named(source: &str) -> Provenance {
        Provenance {
            source: source.to_string(),
            caveats: Vec::new(),
        }
    }
}

/// Longest comment line of a card, the comment mark included: fixed-format readers
/// (LS-DYNA's 80 columns) and editors show no more.
pub const COMMENT_WIDTH: usize = 80;

/// `text` as comment lines of at most `COMMENT_WIDTH` characters, broken between words;
/// continuation lines are indented by two spaces.
pub(crate) fn comment(out: &mut String, mark: &str, text: &str) {
    let mut line = String::from(mark);
    for word in text.split_whitespace() {
        let fresh = line.trim_end() == mark;
        if !fresh && line.chars().count() + 1 + word.chars().count() > COMMENT_WIDTH {
            let _ = writeln!(out, "{line}");
            line = format!("{mark}  ");
        }
        if !line.ends_with(' ') {
            line.push(' ');
        }
        line.push_str(word);
    }
    let _ = writeln!(out, "{line}");
}

pub(crate) fn header(out: &mut String, mark: &str, what: &str, about: &Provenance, units: &Units) {
    let version = env!("CARGO_PKG_VERSION");
    comment(
        out,
        mark,
        &format!("{what} of {}, written by mpw {version}", about.source),
    );
    for caveat in &about.caveats {
        comment(out, mark, caveat);
    }
    comment(
        out,
        mark,
        &format!(
            "units: {} ({}); temperatures in K",
            units.description, units.name
        ),
    );
    comment(out, mark, "yield stress: mpw fits a Kirchhoff stress, the code reads it as Cauchy (they differ by the elastic volume change, 0.6 % at 1 GPa pressure in steel)");
}

/// A number as it round-trips, always with a decimal point or an exponent (`193000.0`,
/// `7.9e-9`).
pub(crate) struct Num(pub f64);

impl std::fmt::Display for Num {
    /// The shortest form of the value rounded to 15 significant digits: a unit conversion
    /// leaves a rounding residue in the 16th (7850 kg/m³ in t/mm³ is 7.849999999999999e-9),
    /// far below any material constant's precision.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let rounded: f64 = format!("{:.14e}", self.0).parse().unwrap_or(self.0);
        write!(f, "{rounded:?}")
    }
}

/// An Abaqus material block named `name`.
pub fn abaqus(m: &Material, name: &str, about: &Provenance, units: &Units) -> Result<String> {
    let v = |n: &str| value(m, n, units).map(|(x, _)| Num(x));
    johnson_cook_only(m)?;
    let mut out = String::new();
    header(&mut out, "**", JOHNSON_COOK, about, units);
    abaqus_material(&mut out, m, name, units, |out| {
        let _ = writeln!(
            out,
            "*PLASTIC, HARDENING=JOHNSON COOK\n {}, {}, {}, {}, {}, {}",
            v("A")?,
            v("B")?,
            v("N")?,
            v("M")?,
            v("theta_m")?,
            v("theta0")?
        );
        let _ = writeln!(
            out,
            "*RATE DEPENDENT, TYPE=JOHNSON COOK\n {}, {}",
            v("C")?,
            v("alpha_dot0")?
        );
        Ok(())
    })?;
    Ok(out)
}

/// The body of an Abaqus material block named `name`: the note on adiabatic heating,
/// density, elasticity and expansion, the plasticity `plastic` writes, specific heat and
/// the inelastic heat fraction.
pub(crate) fn abaqus_material(
    out: &mut String,
    m: &Material,
    name: &str,
    units: &Units,
    plastic: impl FnOnce(&mut String) -> Result<()>,
) -> Result<()> {
    let v = |n: &str| value(m, n, units).map(|(x, _)| Num(x));
    comment(out, "**", "adiabatic heating (*INELASTIC HEAT FRACTION) acts only in an adiabatic step (*DYNAMIC, EXPLICIT, ADIABATIC; *STATIC or *DYNAMIC with ADIABATIC) or a coupled temperature-displacement step; elsewhere the temperature stays at its initial value");
    let _ = writeln!(out, "*MATERIAL, NAME={name}");
    let _ = writeln!(out, "*DENSITY\n {},", v("rho")?);
    let _ = writeln!(out, "*ELASTIC\n {}, {}", v("E")?, v("nu")?);
    let _ = writeln!(
        out,
        "*EXPANSION, ZERO={}\n {},",
        v("theta0")?,
        v("alpha_sigma")?
    );
    plastic(out)?;
    let _ = writeln!(out, "*SPECIFIC HEAT\n {},", v("c_theta")?);
    let _ = writeln!(out, "*INELASTIC HEAT FRACTION\n {},", v("gamma_tq")?);
    Ok(())
}

/// `x` in a 10-character fixed-format field: right-aligned in at most 9 characters, so that
/// fields stay apart on the line, the written form with the smallest error (plain decimals
/// or a mantissa with `E` exponent; at least 4 significant digits for a positive value
/// with a two-digit exponent, more for most).
pub fn field10(x: f64) -> String {
    let plain = (0..=9).rev().map(|p| format!("{x:.p$}"));
    let scientific = (0..=8).rev().map(|p| format!("{x:.p$E}"));
    let best = plain
        .chain(scientific)
        .filter(|s| s.len() <= 9)
        .min_by(|a, b| {
            let err = |s: &String| (s.parse::<f64>().unwrap_or(f64::INFINITY) - x).abs();
            err(a).total_cmp(&err(b)).then(a.len().cmp(&b.len()))
        })
        .unwrap_or_else(|| "0".into());
    format!("{best:>10}")
}

/// One LS-DYNA card: a `$#` line of field names over the values, 10 characters each.
pub(crate) fn lsdyna_card(out: &mut String, names: &[&str], values: &[String]) {
    let names: String = names.iter().map(|n| format!("{n:>10}")).collect();
    let _ = writeln!(out, "$#{}", &names[2..]);
    let _ = writeln!(out, "{}", values.concat());
}

/// An LS-DYNA `*MAT_JOHNSON_COOK` (VP = 1: the rate term takes the plastic strain rate, as
/// mpw's does) with failure and pressure cutoff explicitly off, and the
/// `*EOS_LINEAR_POLYNOMIAL` it needs in solid elements (C1 = K = E / 3(1 − 2ν)), both with
/// identifier `id`.
pub fn lsdyna(
    m: &Material,
    name: &str,
    about: &Provenance,
    units: &Units,
    id: u32,
) -> Result<String> {
    let si = |n: &str| value(m, n, units).map(|(x, _)| x);
    let f = |x: f64| field10(x);
    let v = |n: &str| si(n).map(f);
    let (e, nu) = (si("E")?, si("nu")?);
    let (g, k) = (e / (2.0 * (1.0 + nu)), e / (3.0 * (1.0 - 2.0 * nu)));
    let id = format!("{id:>10}");
    johnson_cook_only(m)?;
    let mut out = String::new();
    header(&mut out, "$", JOHNSON_COOK, about, units);
    comment(&mut out, "$", &format!("material {name}; failure off (D1 = 1e20, D2-D5 = 0; PC = -1e20, SPALL = 1): add your own"));
    let gamma_tq = si("gamma_tq")?;
    let heating = if gamma_tq > 0.0 {
        format!(
            "a code that turns all plastic work into heat matches mpw with CP / gamma_tq = {}",
            f(si("c_theta")? / gamma_tq).trim()
        )
    } else {
        "mpw heats nothing; a code that turns plastic work into heat will".into()
    };
    comment(
        &mut out,
        "$",
        &format!("gamma_tq = {gamma_tq} has no field here: {heating}"),
    );
    comment(
        &mut out,
        "$",
        &format!(
            "below EPSO mpw's rate term is 1; the part that uses this material names EOSID {}",
            id.trim()
        ),
    );
    let _ = writeln!(out, "*MAT_JOHNSON_COOK");
    let one = f(1.0);
    let zero = f(0.0);
    lsdyna_card(
        &mut out,
        &["mid", "ro", "g", "e", "pr", "dtf", "vp", "rateop"],
        &[
            id.clone(),
            v("rho")?,
            f(g),
            f(e),
            f(nu),
            zero.clone(),
            one.clone(),
            zero.clone(),
        ],
    );
    lsdyna_card(
        &mut out,
        &["a", "b", "n", "c", "m", "tm", "tr", "epso"],
        &[
            v("A")?,
            v("B")?,
            v("N")?,
            v("C")?,
            v("M")?,
            v("theta_m")?,
            v("theta0")?,
            v("alpha_dot0")?,
        ],
    );
    lsdyna_card(
        &mut out,
        &["cp", "pc", "spall", "it", "d1", "d2", "d3", "d4"],
        &[
            v("c_theta")?,
            f(-1e20),
            one,
            zero.clone(),
            f(1e20),
            zero.clone(),
            zero.clone(),
            zero.clone(),
        ],
    );
    lsdyna_card(
        &mut out,
        &["d5", "c2/p", "erod", "efmin", "numint"],
        &[
            zero.clone(),
            zero.clone(),
            zero.clone(),
            zero.clone(),
            zero.clone(),
        ],
    );
    let _ = writeln!(out, "*EOS_LINEAR_POLYNOMIAL");
    lsdyna_card(
        &mut out,
        &["eosid", "c0", "c1", "c2", "c3", "c4", "c5", "c6"],
        &[
            id,
            zero.clone(),
            f(k),
            zero.clone(),
            zero.clone(),
            zero.clone(),
            zero.clone(),
            zero.clone(),
        ],
    );
    lsdyna_card(&mut out, &["e0", "v0"], &[zero, f(1.0)]);
    Ok(out)
}

/// A generic JSON card: `{"parameters": {"A": {"value": .., "unit": ".."}, ..}, ..}`.
pub fn json(m: &Material, name: &str, about: &Provenance, units: &Units) -> Result<String> {
    johnson_cook_only(m)?;
    let quoted = |s: &str| format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""));
    let mut fields = Vec::new();
    for n in FIELDS {
        let (x, unit) = value(m, n, units)?;
        let x = Num(x);
        fields.push(format!(
            "    {}: {{\"value\": {x}, \"unit\": {}}}",
            quoted(n),
            quoted(unit)
        ));
    }
    let caveats: Vec<String> = about.caveats.iter().map(|c| quoted(c)).collect();
    Ok(format!(
        "{{\n  \"model\": \"johnson-cook\",\n  \"form\": \"[A + B eps_p^N] [1 + C ln(rate/alpha_dot0)] [1 - T*^M], T* = (T - theta0)/(theta_m - theta0); rate term 1 below alpha_dot0, T* clamped to [0, 1]; Kirchhoff yield stress\",\n  \"name\": {},\n  \"source\": {},\n  \"caveats\": [{}],\n  \"units\": {},\n  \"parameters\": {{\n{}\n  }}\n}}\n",
        quoted(name),
        quoted(&about.source),
        caveats.join(", "),
        quoted(units.description),
        fields.join(",\n")
    ))
}
