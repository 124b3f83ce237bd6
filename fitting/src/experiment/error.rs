//! Errors of reading an experiment: each names the file, the line, and the column (CSV
//! column name, or TOML key and character column) and says what was expected.

use std::path::PathBuf;
use thiserror::Error;

pub use materials::toml_place::Location;

#[derive(Debug, Error)]
pub enum ExperimentError {
    #[error("{}: cannot read: {reason}", file.display())]
    Io {
        file: PathBuf,
        reason: std::io::Error,
    },
    /// TOML syntax, a missing or unknown key, or a value of the wrong type; `key` when the
    /// error's line names one (`materials::toml_place::key_at`).
    #[error("{at}: {}{message}", key.as_ref().map(|k| format!("`{k}`: ")).unwrap_or_default())]
    Toml {
        at: Location,
        key: Option<String>,
        message: String,
    },
    #[error("{at}: `{key}`: kind \"{found}\", expected \"{expected}\"")]
    WrongKind {
        at: Location,
        key: String,
        found: String,
        expected: String,
    },
    #[error("{at}: `{key}`: unknown unit \"{unit}\", expected one of {expected}")]
    UnknownUnit {
        at: Location,
        key: String,
        unit: String,
        expected: String,
    },
    #[error("{at}: `{key}`: {problem}")]
    InvalidValue {
        at: Location,
        key: String,
        problem: String,
    },
    #[error("{at}: `{key}` = {value} lies outside the data, which spans {data_min} .. {data_max}")]
    WindowOutsideData {
        at: Location,
        key: String,
        value: f64,
        data_min: f64,
        data_max: f64,
    },
    #[error("{}:{line}: no column \"{name}\" (named by {named_by}); the header has: {available}", file.display())]
    MissingColumn {
        file: PathBuf,
        line: usize,
        name: String,
        named_by: Location,
        available: String,
    },
    #[error("{}:{line}: column {column} \"{name}\" appears twice in the header", file.display())]
    DuplicateColumn {
        file: PathBuf,
        line: usize,
        column: usize,
        name: String,
    },
    #[error("{}:{line}: {found} fields, expected {expected} as in the header", file.display())]
    FieldCount {
        file: PathBuf,
        line: usize,
        found: usize,
        expected: usize,
    },
    #[error("{}:{line}: column {column} \"{name}\": expected a number, found \"{text}\"", file.display())]
    BadNumber {
        file: PathBuf,
        line: usize,
        column: usize,
        name: String,
        text: String,
    },
    #[error("{}:{line}: column {column} \"{name}\": {value} is not a finite number", file.display())]
    NotFinite {
        file: PathBuf,
        line: usize,
        column: usize,
        name: String,
        value: f64,
    },
    #[error(
        "{}:{line}: column {column} \"{name}\": time {value} s is not after the previous row's {previous} s (values in seconds); time must increase strictly",
        file.display()
    )]
    NonMonotonicTime {
        file: PathBuf,
        line: usize,
        column: usize,
        name: String,
        previous: f64,
        value: f64,
    },
    #[error("{}:{line}: column {column} \"{name}\": {problem}", file.display())]
    Implausible {
        file: PathBuf,
        line: usize,
        column: usize,
        name: String,
        /// The value as written with its unit, what it is in SI, and the likely mistake.
        problem: String,
    },
    #[error("{}: {source}", file.display())]
    TooLarge {
        file: PathBuf,
        source: Box<materials::limits::TooLarge>,
    },
    #[error(
        "{}: no `{key}`: the experiment TOML {} does not state it and the CSV header has none of {header_keys}",
        csv.display(), toml.display()
    )]
    MissingMetadata {
        toml: PathBuf,
        csv: PathBuf,
        key: String,
        header_keys: String,
    },
    #[error("{}:{line}: header `{key}`: {problem}", file.display())]
    BadHeader {
        file: PathBuf,
        line: usize,
        key: String,
        problem: String,
    },
    #[error("{}: {found} data rows, at least {needed} needed", file.display())]
    TooFewRows {
        file: PathBuf,
        found: usize,
        needed: usize,
    },
}
