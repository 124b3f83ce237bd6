//! Metadata in a CSV's `#` header: lines `# key: value` (or `# key = value`) above the
//! column names, as the shared 304L records write them:
//!
//! ```text
//! # nominal_engineering_strain_rate_per_s: 1800
//! # temperature_K: 297.04
//! ```
//!
//! A key either carries its unit in its name (`temperature_K`, `..._per_s`) and a plain
//! number as value, or has a quantity string as value (`# temperature: 20 °C`). The TOML
//! overrides the header; each value records where it came from.

use super::table::CsvTable;
use super::units::{parse_quantity, Dimension};
use std::fmt;

/// (header key, unit of its plain-number value; "" when the value is a quantity string).
pub type HeaderKey<'a> = (&'a str, &'a str);

/// Header keys of a test temperature, in the order they are looked for.
pub const TEMPERATURE_KEYS: &[HeaderKey<'static>] = &[
    ("temperature_K", "K"),
    ("temperature_C", "°C"),
    ("temperature_degC", "°C"),
    ("temperature", ""),
];

/// Header keys of a nominal strain rate, in the order they are looked for.
pub const STRAIN_RATE_KEYS: &[HeaderKey<'static>] = &[
    ("nominal_engineering_strain_rate_per_s", "1/s"),
    ("nominal_strain_rate_per_s", "1/s"),
    ("strain_rate_per_s", "1/s"),
    ("nominal_strain_rate", ""),
];

/// Where a metadata value was read.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// The experiment TOML's key.
    Toml { key: String },
    /// A `#` header line of the CSV.
    Header { key: String, line: usize },
}

impl fmt::Display for Source {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Source::Toml { key } => write!(f, "TOML `{key}`"),
            Source::Header { key, line } => write!(f, "CSV header `{key}` (line {line})"),
        }
    }
}

/// A header value that is present but cannot be read.
#[derive(Debug, Clone, PartialEq)]
pub struct BadHeaderValue {
    pub line: usize,
    pub key: String,
    pub problem: String,
}

/// The `key: value` pairs of the header comments, with their line numbers.
fn pairs(table: &CsvTable) -> impl Iterator<Item = (usize, &str, &str)> {
    table.comments.iter().filter_map(|(line, text)| {
        let cut = text.find([':', '='])?;
        Some((*line, text[..cut].trim(), text[cut + 1..].trim()))
    })
}

/// The first of `keys` present in the header of `table`, in SI units of `dimension`, with
/// its source; `Ok(None)` if none is present.
pub(crate) fn lookup(
    table: &CsvTable,
    keys: &[HeaderKey],
    dimension: Dimension,
) -> Result<Option<(f64, Source)>, BadHeaderValue> {
    for &(key, unit) in keys {
        let Some((line, _, value)) = pairs(table).find(|(_, k, _)| *k == key) else {
            continue;
        };
        let text = if unit.is_empty() {
            value.to_string()
        } else {
            format!("{value} {unit}")
        };
        let si = parse_quantity(&text, dimension).map_err(|_| BadHeaderValue {
            line,
            key: key.into(),
            problem: format!(
                "\"{value}\" is not {}",
                if unit.is_empty() {
                    format!("\"<number> <unit>\" with one of {}", dimension.accepted())
                } else {
                    "a finite number".into()
                }
            ),
        })?;
        let (limit, likely) = dimension.plausible_magnitude();
        if !(si > 0.0 && si <= limit) {
            return Err(BadHeaderValue {
                line,
                key: key.into(),
                problem: format!(
                    "\"{value}\" must be positive and at most {limit:e} in SI units ({likely})"
                ),
            });
        }
        let source = Source::Header {
            key: key.into(),
            line,
        };
        return Ok(Some((si, source)));
    }
    Ok(None)
}

/// The keys of `keys` as a list for messages: `` `temperature_K`, `temperature_C` ``.
pub(crate) fn names(keys: &[HeaderKey]) -> String {
    let names: Vec<String> = keys.iter().map(|(k, _)| format!("`{k}`")).collect();
    names.join(", ")
}
