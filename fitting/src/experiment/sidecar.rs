//! The experiment TOML ("sidecar" of a CSV file): parsing with serde, locations of keys
//! for error messages, quantity strings and column specifications.

use super::error::{ExperimentError, Location};
use super::header::{self, HeaderKey, Source};
use super::table::CsvTable;
use super::units::{parse_quantity, Dimension, QuantityProblem};
use serde::de::DeserializeOwned;
use serde::Deserialize;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A CSV column and the unit its values are in: `{ name = "time_s", unit = "s" }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ColumnSpec {
    pub name: Spanned<String>,
    pub unit: Spanned<String>,
}

/// The text of an experiment TOML file.
pub(crate) struct Sidecar {
    pub file: PathBuf,
    text: String,
}

impl Sidecar {
    pub fn read(file: &Path) -> Result<Sidecar, ExperimentError> {
        let text = std::fs::read_to_string(file).map_err(|reason| ExperimentError::Io {
            file: file.to_path_buf(),
            reason,
        })?;
        Ok(Sidecar {
            file: file.to_path_buf(),
            text,
        })
    }

    /// 1-based line and column of byte offset `span.start`.
    pub fn at(&self, span: Range<usize>) -> Location {
        Location::in_text(&self.file, &self.text, span.start)
    }

    /// The line that opens table `name` (`[name]`, `[name.x]` or `name = {`), for an error
    /// about the table as a whole (0..0 when it is not found). Tables are not parsed as
    /// `Spanned`: toml cannot span a table written as `[name.x]` headers.
    pub fn table_span(&self, name: &str) -> Range<usize> {
        let mut start = 0;
        for line in self.text.split_inclusive('\n') {
            let t = line.trim_start();
            let opens = t.strip_prefix('[').is_some_and(|r| {
                r.strip_prefix(name)
                    .is_some_and(|r| r.starts_with(']') || r.starts_with('.'))
            }) || t
                .strip_prefix(name)
                .is_some_and(|r| r.trim_start().starts_with('='));
            if opens {
                return start..start + line.trim_end().len();
            }
            start += line.len();
        }
        0..0
    }

    pub fn parse<T: DeserializeOwned>(&self) -> Result<T, ExperimentError> {
        toml::from_str(&self.text).map_err(|e| {
            let span = e.span().unwrap_or(0..0);
            ExperimentError::Toml {
                message: self.type_hint(span.clone(), e.message().trim()),
                key: materials::toml_place::key_at(&self.text, span.start),
                at: self.at(span),
            }
        })
    }

    /// The file parsed as `T` after checking that its `kind` is `expected` (so that a file
    /// of another kind is reported as such, not as an unknown key).
    pub fn parse_kind<T: DeserializeOwned>(&self, expected: &str) -> Result<T, ExperimentError> {
        let kind: KindOnly = self.parse()?;
        self.expect_kind(&kind.kind, expected)?;
        self.parse()
    }

    /// The file's `kind` key must be `expected` ("tensile", "shpb").
    pub fn expect_kind(
        &self,
        kind: &Spanned<String>,
        expected: &str,
    ) -> Result<(), ExperimentError> {
        if kind.get_ref() == expected {
            return Ok(());
        }
        Err(ExperimentError::WrongKind {
            at: self.at(kind.span()),
            key: "kind".into(),
            found: kind.get_ref().clone(),
            expected: expected.into(),
        })
    }

    /// A path written in the TOML, relative to the TOML's folder.
    pub fn relative_path(&self, path: &str) -> PathBuf {
        self.file.parent().unwrap_or(Path::new(".")).join(path)
    }

    /// The file the `data` key names, relative to the TOML's folder; a single file that
    /// does not exist is an error at the key (a pattern or folder is expanded later).
    pub fn data_path(&self, data: &Spanned<String>) -> Result<PathBuf, ExperimentError> {
        let path = self.relative_path(data.get_ref());
        if path.exists() || super::pattern::is_many(&path) {
            return Ok(path);
        }
        Err(self.invalid(
            "data",
            data.span(),
            format!(
                "no file {}: the path is relative to the folder of this TOML ({}); was the TOML copied or moved without its data?",
                path.display(),
                self.file.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new(".")).display()
            ),
        ))
    }

    /// The TOML's type error, with the unit a bare number probably lacked
    /// (`diameter = 20`: write `"20 mm"`).
    fn type_hint(&self, span: Range<usize>, message: &str) -> String {
        let Some(number) = message
            .strip_prefix("invalid type: integer `")
            .or_else(|| message.strip_prefix("invalid type: floating point `"))
            .and_then(|m| m.split_once("`, expected a string"))
            .map(|(n, _)| n)
        else {
            return message.to_string();
        };
        let line = self.text[..span.start.min(self.text.len())]
            .rsplit('\n')
            .next()
            .unwrap_or("");
        let key = line
            .split('=')
            .next()
            .unwrap_or("")
            .trim()
            .trim_start_matches('{')
            .trim();
        let key = key.rsplit([',', '{', ' ']).next().unwrap_or(key);
        match unit_for(key) {
            Some(unit) => format!("{message}: a quantity is a string with its unit, e.g. `{key} = \"{number} {unit}\"`"),
            None => format!("{message}: a quantity is a string with its unit, e.g. \"{number} <unit>\""),
        }
    }

    pub fn invalid(
        &self,
        key: &str,
        span: Range<usize>,
        problem: impl Into<String>,
    ) -> ExperimentError {
        ExperimentError::InvalidValue {
            at: self.at(span),
            key: key.to_string(),
            problem: problem.into(),
        }
    }

    /// A quantity string `"<number> <unit>"` in SI, within the dimension's plausible
    /// magnitude.
    pub fn quantity(
        &self,
        key: &str,
        value: &Spanned<String>,
        dimension: Dimension,
    ) -> Result<f64, ExperimentError> {
        let x = self.parsed_quantity(key, value, dimension)?;
        let (limit, likely) = dimension.plausible_magnitude();
        if x.abs() > limit {
            return Err(self.invalid(
                key,
                value.span(),
                format!(
                    "\"{}\" is implausible ({x:e} in SI units, {likely})",
                    value.get_ref()
                ),
            ));
        }
        Ok(x)
    }

    fn parsed_quantity(
        &self,
        key: &str,
        value: &Spanned<String>,
        dimension: Dimension,
    ) -> Result<f64, ExperimentError> {
        parse_quantity(value.get_ref(), dimension).map_err(|problem| match problem {
            QuantityProblem::Malformed => self.invalid(
                key,
                value.span(),
                format!(
                    "expected \"<number> <unit>\" with a finite number and one of {}, found \"{}\"",
                    dimension.accepted(),
                    value.get_ref()
                ),
            ),
            QuantityProblem::UnknownUnit(unit) => {
                self.unknown_unit(key, value.span(), &unit, dimension)
            }
        })
    }

    /// A quantity that must be > 0.
    pub fn positive(
        &self,
        key: &str,
        value: &Spanned<String>,
        dimension: Dimension,
    ) -> Result<f64, ExperimentError> {
        let x = self.quantity(key, value, dimension)?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(
                key,
                value.span(),
                format!("must be positive, found \"{}\"", value.get_ref()),
            ))
        }
    }

    fn unknown_unit(
        &self,
        key: &str,
        span: Range<usize>,
        unit: &str,
        dimension: Dimension,
    ) -> ExperimentError {
        ExperimentError::UnknownUnit {
            at: self.at(span),
            key: key.to_string(),
            unit: unit.to_string(),
            expected: dimension.accepted(),
        }
    }

    /// Column `spec` of `table`, converted to SI.
    pub fn column(
        &self,
        table: &CsvTable,
        key: &str,
        spec: &ColumnSpec,
        dimension: Dimension,
    ) -> Result<Vec<f64>, ExperimentError> {
        let unit_key = format!("{key}.unit");
        let conversion = dimension.to_si(spec.unit.get_ref()).ok_or_else(|| {
            self.unknown_unit(&unit_key, spec.unit.span(), spec.unit.get_ref(), dimension)
        })?;
        let values = table.column(spec.name.get_ref(), &self.at(spec.name.span()))?;
        let si: Vec<f64> = values.iter().map(|&v| conversion.apply(v)).collect();
        let unit = spec.unit.get_ref();
        let (limit, likely) = dimension.plausible_magnitude();
        let how = format!("in SI units, {likely}");
        self.check_plausible(table, spec, (&values, unit), &si, limit, &how)?;
        if let Some((floor, likely)) = dimension.plausible_peak() {
            self.check_peak(table, spec, (&values, unit), &si, floor, likely)?;
        }
        Ok(si)
    }

    /// Check that column `spec` (its values as written in `unit`, and `si`) reaches the
    /// peak magnitude `floor` [SI] somewhere (`Dimension::plausible_peak`).
    fn check_peak(
        &self,
        table: &CsvTable,
        spec: &ColumnSpec,
        (written, unit): (&[f64], &str),
        si: &[f64],
        floor: f64,
        likely: &str,
    ) -> Result<(), ExperimentError> {
        let peak = (0..si.len()).max_by(|&a, &b| si[a].abs().total_cmp(&si[b].abs()));
        match peak {
            Some(i) if si[i].abs() < floor => Err(implausible(table, spec, i, {
                let (value, in_si) = (written[i], si[i]);
                format!("the column's largest value, {value} {unit} ({in_si:e} in SI units), is {likely}")
            })),
            _ => Ok(()),
        }
    }

    /// Check `derived` [SI], computed row by row from column `spec` (its values and their
    /// unit in `source`), against the plausible magnitude `limit`
    /// (`Dimension::plausible_magnitude`); `how` says how a value was derived and what the
    /// likely mistake is.
    pub fn check_plausible(
        &self,
        table: &CsvTable,
        spec: &ColumnSpec,
        (written, unit): (&[f64], &str),
        derived: &[f64],
        limit: f64,
        how: &str,
    ) -> Result<(), ExperimentError> {
        match derived.iter().position(|v| v.abs() > limit) {
            None => Ok(()),
            Some(i) => Err(implausible(table, spec, i, {
                format!(
                    "{} {unit} is implausible ({:e} {how})",
                    written[i], derived[i]
                )
            })),
        }
    }

    /// A metadata value: the TOML's `key` where it is given, otherwise the first of
    /// `header_keys` in the CSV header of `table`; `Ok(None)` if neither has it.
    pub fn optional_metadata(
        &self,
        table: &CsvTable,
        (key, value): (&str, Option<&Spanned<String>>),
        header_keys: &[HeaderKey],
        dimension: Dimension,
    ) -> Result<Option<(f64, Source)>, ExperimentError> {
        if let Some(v) = value {
            let si = self.positive(key, v, dimension)?;
            return Ok(Some((si, Source::Toml { key: key.into() })));
        }
        header::lookup(table, header_keys, dimension).map_err(|bad| ExperimentError::BadHeader {
            file: table.file.clone(),
            line: bad.line,
            key: bad.key,
            problem: bad.problem,
        })
    }

    /// `optional_metadata` that must be found in the TOML or the header.
    pub fn metadata(
        &self,
        table: &CsvTable,
        (key, value): (&str, Option<&Spanned<String>>),
        header_keys: &[HeaderKey],
        dimension: Dimension,
    ) -> Result<(f64, Source), ExperimentError> {
        self.optional_metadata(table, (key, value), header_keys, dimension)?
            .ok_or_else(|| ExperimentError::MissingMetadata {
                toml: self.file.clone(),
                csv: table.file.clone(),
                key: key.into(),
                header_keys: header::names(header_keys),
            })
    }

    /// Check that `time` (from column `spec` of `table`) increases strictly.
    pub fn check_time_increases(
        &self,
        table: &CsvTable,
        spec: &ColumnSpec,
        time: &[f64],
    ) -> Result<(), ExperimentError> {
        for i in 1..time.len() {
            if time[i] <= time[i - 1] {
                let name = spec.name.get_ref().clone();
                return Err(ExperimentError::NonMonotonicTime {
                    file: table.file.clone(),
                    line: table.line_of(i),
                    column: table.position(&name).unwrap_or(0),
                    name,
                    previous: time[i - 1],
                    value: time[i],
                });
            }
        }
        Ok(())
    }
}

/// First pass over any experiment TOML: only its `kind`.
#[derive(Deserialize)]
pub(crate) struct KindOnly {
    pub kind: Spanned<String>,
}

/// Row `row` of column `spec` of `table` is implausible: `problem` says why.
fn implausible(
    table: &CsvTable,
    spec: &ColumnSpec,
    row: usize,
    problem: String,
) -> ExperimentError {
    let name = spec.name.get_ref().clone();
    ExperimentError::Implausible {
        file: table.file.clone(),
        line: table.line_of(row),
        column: table.position(&name).unwrap_or(0),
        name,
        problem,
    }
}

/// The unit a quantity key is usually written in, for the hint on a bare number.
fn unit_for(key: &str) -> Option<&'static str> {
    Some(match key {
        "temperature" => "K",
        "nominal_strain_rate" => "1/s",
        "elastic_modulus" => "GPa",
        "density" => "kg/m^3",
        "wave_speed" => "m/s",
        "excitation" => "V",
        "area" => "mm^2",
        "time_min" | "time_max" => "s",
        "incident_gauge_delay" | "transmitted_gauge_delay" => "us",
        k if k == "diameter"
            || k == "length"
            || k.ends_with("_length")
            || k.ends_with("_to_specimen") =>
        {
            "mm"
        }
        _ => return None,
    })
}
