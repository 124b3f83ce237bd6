//! The verification catalogue of `mpw verify`: every case the project checks against an
//! analytic solution, a published value, an independent implementation or a
//! finite-difference check, one `Row` each, asserted (pass or fail) or reported (info).
//! Each part of the catalogue is one function from the same `Inputs` to its rows,
//! registered once in `CATALOGUE`; `table` runs them in that order.

pub mod cutting;
pub mod cutting_derivatives;
pub mod cutting_orthogonal;
pub mod data;
pub mod fit;
pub mod materials;
pub mod mpm;
pub mod row;
pub mod shpb;
pub mod shpb_derivatives;
pub mod shpb_model;

use data::VerifyData;
use row::Row;
use std::time::Instant;

/// What every part of the catalogue is given.
pub struct Inputs<'a> {
    /// The reference data folder (`--data`).
    pub data: &'a VerifyData,
    /// The thesis sizes where a part has smaller default ones (`--full`).
    pub full: bool,
}

/// One part of the catalogue: its rows from the inputs.
pub type Part = fn(&Inputs) -> anyhow::Result<Vec<Row>>;

/// The catalogue, part by part, in table order.
pub const CATALOGUE: [(&str, Part); 11] = [
    ("materials", materials::rows),
    ("shpb", shpb::rows),
    ("fit", fit::rows),
    ("fit-mpm", fit::mpm_rows),
    ("fit-real", fit::real_rows),
    ("mpm", mpm::rows),
    ("shpb-model", shpb_model::rows),
    ("shpb-derivatives", shpb_derivatives::rows),
    ("cutting", cutting::rows),
    ("cutting-orthogonal", cutting_orthogonal::rows),
    ("cutting-derivatives", cutting_derivatives::rows),
];

/// The rows of the parts `names` of the catalogue (`selected`); a part that cannot run,
/// or two rows of one name (two builds' tables are compared by name), is an error. Each
/// part, when done, says on stderr how many rows it gave and how long it took (the whole
/// table takes minutes).
pub fn table(inputs: &Inputs, names: &[&str]) -> anyhow::Result<Vec<Row>> {
    let mut rows: Vec<Row> = vec![];
    for (k, name) in names.iter().enumerate() {
        let start = Instant::now();
        let part_rows = part(inputs, name)?;
        eprintln!(
            "verify: part {}/{} `{name}`: {} rows in {:.1} s",
            k + 1,
            names.len(),
            part_rows.len(),
            start.elapsed().as_secs_f64()
        );
        rows.extend(part_rows);
    }
    unique(rows)
}

/// The parts named in `wanted`, in catalogue order; every part when `wanted` is empty. A
/// name that is no part is an error listing the parts.
pub fn selected(wanted: &[String]) -> anyhow::Result<Vec<&'static str>> {
    if let Some(unknown) = wanted
        .iter()
        .find(|w| !CATALOGUE.iter().any(|(n, _)| n == w))
    {
        anyhow::bail!(
            "no verification part `{unknown}`; the parts are {}",
            part_names()
        );
    }
    Ok((CATALOGUE.iter())
        .map(|(n, _)| *n)
        .filter(|n| wanted.is_empty() || wanted.iter().any(|w| w == n))
        .collect())
}

/// The catalogue's part names, comma separated.
fn part_names() -> String {
    CATALOGUE.map(|(n, _)| n).join(", ")
}

/// The rows of the part `name` of the catalogue.
pub fn part(inputs: &Inputs, name: &str) -> anyhow::Result<Vec<Row>> {
    let Some((_, rows)) = CATALOGUE.iter().find(|(n, _)| *n == name) else {
        anyhow::bail!(
            "no verification part `{name}`; the parts are {}",
            part_names()
        );
    };
    rows(inputs).map_err(|e| e.context(format!("verification part {name}")))
}

/// `rows`, unless two of them have one name.
pub fn unique(rows: Vec<Row>) -> anyhow::Result<Vec<Row>> {
    let mut names: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
    names.sort_unstable();
    if let Some(twice) = names.windows(2).find(|w| w[0] == w[1]) {
        anyhow::bail!("two verification rows are named `{}`", twice[0]);
    }
    Ok(rows)
}
