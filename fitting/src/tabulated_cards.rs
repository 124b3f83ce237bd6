//! Cards for any flow-stress law: the law sampled into a table (`flow_table`) and written
//! as a code's tabulated plasticity, in a stated unit system.
//!
//! - Abaqus: `*PLASTIC, RATE=ε̇` blocks, the first at rate 0, each with lines
//!   `yield stress, plastic strain[, temperature]`, grouped by temperature where the table
//!   has several.
//! - LS-DYNA: `*MAT_PIECEWISE_LINEAR_PLASTICITY` (VP = 1: the plastic strain rate, as mpw's
//!   laws take it) whose LCSS is a `*DEFINE_TABLE` of plastic strain rates, each naming a
//!   `*DEFINE_CURVE` of yield stress over plastic strain. The material has no thermal
//!   softening, so the table is written at one temperature and the card says what is lost.
//!
//! Both codes interpolate linearly between nodes and hold the last node beyond them; the
//! table's sampling, tolerance and ranges stand in the header. mpw's yield stress is a
//! Kirchhoff stress, the codes' a Cauchy stress (`export`).

use crate::export::{abaqus_material, comment, header, lsdyna_card, value, Num, Provenance, Units};
use crate::fit::levels::model::Material;
use crate::flow_table::{FlowTable, TableRange};
use anyhow::Result;
use std::fmt::Write as _;

/// The header lines of a tabulated card: the law, the table's ranges, nodes and tolerance.
fn describe_table(
    out: &mut String,
    mark: &str,
    m: &Material,
    table: &FlowTable,
    range: &TableRange,
    units: &Units,
) {
    let rate_unit = units.rate_unit;
    let last_rate = table.rates.last().copied().unwrap_or(0.0) * units.rate;
    comment(
        out,
        mark,
        &format!(
            "flow-stress law {} sampled at {} plastic strains (0 to {}), {} rates (0 to {last_rate:e} {rate_unit}) and {} temperatures ({} to {} K); linear interpolation, in the rate or in its logarithm, stays within {} % of the law's cold flow stress; beyond the last node the code holds the table constant",
            m.flow.describe(),
            table.strains.len(),
            range.strain_max,
            table.rates.len(),
            table.temperatures.len(),
            table.temperatures[0],
            table.temperatures.last().copied().unwrap_or(0.0),
            100.0 * range.tolerance,
        ),
    );
}

/// An Abaqus material block named `name` with the law of `m` as rate- (and temperature-)
/// dependent tabulated plasticity.
pub fn abaqus_table(
    m: &Material,
    name: &str,
    about: &Provenance,
    units: &Units,
    range: &TableRange,
) -> Result<String> {
    let theta0 = value(m, "theta0", units)?.0;
    let table = FlowTable::sample(&m.flow, theta0, range)?;
    let mut out = String::new();
    header(&mut out, "**", "Tabulated flow stress", about, units);
    describe_table(&mut out, "**", m, &table, range, units);
    abaqus_material(&mut out, m, name, units, |out| {
        let with_temperature = table.temperatures.len() > 1;
        for (r, &rate) in table.rates.iter().enumerate() {
            writeln!(out, "*PLASTIC, RATE={}", Num(rate * units.rate))?;
            for (t, &theta) in table.temperatures.iter().enumerate() {
                for (s, &strain) in table.strains.iter().enumerate() {
                    let stress = Num(table.stress[t][r][s] * units.stress);
                    match with_temperature {
                        true => writeln!(out, " {stress}, {}, {}", Num(strain), Num(theta)),
                        false => writeln!(out, " {stress}, {}", Num(strain)),
                    }?;
                }
            }
        }
        Ok(())
    })?;
    Ok(out)
}

/// A 20-character field of a `*DEFINE_TABLE` or `*DEFINE_CURVE` line.
fn field20(x: f64) -> String {
    format!("{:>20}", format!("{:.12e}", x))
}

/// An LS-DYNA `*MAT_PIECEWISE_LINEAR_PLASTICITY` with identifier `id`, its table
/// (identifier 1000·id) and curves (1000·id + 1, ...), at the table's one temperature.
pub fn lsdyna_table(
    m: &Material,
    name: &str,
    about: &Provenance,
    units: &Units,
    id: u32,
    range: &TableRange,
) -> Result<String> {
    let theta0 = value(m, "theta0", units)?.0;
    let table = FlowTable::sample(&m.flow, theta0, range)?;
    let si = |n: &str| value(m, n, units).map(|(x, _)| x);
    let f = crate::export::field10;
    let mut out = String::new();
    header(&mut out, "$", "Tabulated flow stress", about, units);
    describe_table(&mut out, "$", m, &table, range, units);
    let theta = table.temperatures[0];
    let softens =
        m.flow.tau_y(0.5, 0.0, theta + 100.0, theta0) < m.flow.tau_y(0.5, 0.0, theta, theta0);
    if softens {
        comment(&mut out, "$", &format!("WARNING: *MAT_024 has no thermal softening: the table is the law at {theta} K, so adiabatic heating does not soften this material as the law does (*MAT_224 would carry it)"));
    }
    comment(&mut out, "$", &format!("material {name}; failure off (FAIL = 0); LCSS = table {} of plastic strain rates, curves {} to {}", 1000 * id, 1000 * id + 1, 1000 * id + table.rates.len() as u32));
    let zero = f(0.0);
    let _ = writeln!(out, "*MAT_PIECEWISE_LINEAR_PLASTICITY");
    let sigy = table.stress[0][0][0] * units.stress;
    lsdyna_card(
        &mut out,
        &["mid", "ro", "e", "pr", "sigy", "etan", "fail", "tdel"],
        &[
            format!("{id:>10}"),
            f(si("rho")?),
            f(si("E")?),
            f(si("nu")?),
            f(sigy),
            zero.clone(),
            zero.clone(),
            zero.clone(),
        ],
    );
    lsdyna_card(
        &mut out,
        &["c", "p", "lcss", "lcsr", "vp"],
        &[
            zero.clone(),
            zero.clone(),
            format!("{:>10}", 1000 * id),
            zero.clone(),
            f(1.0),
        ],
    );
    lsdyna_card(
        &mut out,
        &[
            "eps1", "eps2", "eps3", "eps4", "eps5", "eps6", "eps7", "eps8",
        ],
        &vec![zero.clone(); 8],
    );
    lsdyna_card(
        &mut out,
        &["es1", "es2", "es3", "es4", "es5", "es6", "es7", "es8"],
        &vec![zero.clone(); 8],
    );
    let _ = writeln!(out, "*DEFINE_TABLE");
    lsdyna_card(
        &mut out,
        &["tbid", "sfa", "offa"],
        &[format!("{:>10}", 1000 * id), f(1.0), zero.clone()],
    );
    let _ = writeln!(out, "$#{:>18}{:>20}", "value", "lcid");
    for (r, &rate) in table.rates.iter().enumerate() {
        let _ = writeln!(
            out,
            "{}{:>20}",
            field20(rate * units.rate),
            1000 * id + 1 + r as u32
        );
    }
    for (r, _) in table.rates.iter().enumerate() {
        let _ = writeln!(out, "*DEFINE_CURVE");
        lsdyna_card(
            &mut out,
            &["lcid", "sidr", "sfa", "sfo", "offa", "offo", "dattyp"],
            &[
                format!("{:>10}", 1000 * id + 1 + r as u32),
                zero.clone(),
                f(1.0),
                f(1.0),
                zero.clone(),
                zero.clone(),
                zero.clone(),
            ],
        );
        let _ = writeln!(out, "$#{:>18}{:>20}", "a1", "o1");
        for (s, &strain) in table.strains.iter().enumerate() {
            let _ = writeln!(
                out,
                "{}{}",
                field20(strain),
                field20(table.stress[0][r][s] * units.stress)
            );
        }
    }
    Ok(out)
}
