//! The "LANL standard" raw SHPB record (the format lanl/HopPyBar reads): tab-separated
//! text, CRLF or LF line ends, ° and µ in key names. Files arrive in Latin-1 (as
//! published), in UTF-8 with or without a byte-order mark, and with the unit characters
//! replaced by U+FFFD after a wrong conversion: `Time(\u{FFFD}s)` can only be µs and
//! `Temperature(\u{FFFD}C)` only °C, so these are read as such, each with a note.
//!
//! Columns 1-2 of the leading lines are key/value metadata: the test (`Test Loading`,
//! `Initial Sample Diameter(mm)`, `Initial Sample Length(mm)`, `Test Temperature(°C)`,
//! `Incident/Reflected Bar Gain`, `Transmitted Bar Gain`, ...), then an `Incident Bar
//! Properties` and a `Transmitted Bar Properties` block whose keys start with `Incident
//! Bar ` and `Transmitted Bar ` (`Calibrated Gage Factor`, `Young's Modulus(GPa)`, `Rod
//! Sound Speed(m/s)`, `Density(kg/m^3)`, `Diameter(mm)`, `Strain Gage Location(mm)`,
//! `Excitation Voltage(V)`, `Calibrated Gain`; the incident block also `Calibrated
//! Reflected Time(µs)`, the gauge-to-face-and-back travel time). Columns 3-4 hold the
//! waveforms: line 1 their names, line 2 the start time t0 [s], line 3 the sampling
//! interval dt [s], then one sample per line in volts at the amplifier output.
//!
//! This module reads the file into keys and samples and turns the metadata into the bar
//! and the gauge strains, with checks on what they say; `shpb::ShpbExperiment` takes the
//! bridge and polarity from the record's TOML.

use super::error::{ExperimentError, Location};
use super::shpb::Bar;
use super::units::Dimension;
use std::path::{Path, PathBuf};

/// A metadata value and the line it is on.
#[derive(Debug, Clone)]
pub struct Entry {
    /// The key as written, without its unit in parentheses.
    pub name: String,
    /// The unit in the key's last parentheses ("mm", "°C"), or "".
    pub unit: String,
    pub value: String,
    pub line: usize,
}

/// A raw record: metadata in file order and both waveforms in volts.
#[derive(Debug, Clone)]
pub struct RawRecord {
    pub file: PathBuf,
    pub metadata: Vec<Entry>,
    /// Start time t0 and sampling interval dt of the waveforms [s].
    pub t0_s: f64,
    pub dt_s: f64,
    /// Amplifier output of the incident and transmitted gauges [V].
    pub incident_v: Vec<f64>,
    pub transmitted_v: Vec<f64>,
    /// What the reader decided about the text: its encoding, repaired unit characters.
    pub notes: Vec<String>,
}

/// The file's text: UTF-8 (a byte-order mark dropped) when the bytes are valid UTF-8,
/// else Latin-1, in which every byte is the code point of its value.
fn decode(bytes: &[u8], notes: &mut Vec<String>) -> String {
    let (bytes, bom) = match bytes.strip_prefix(b"\xEF\xBB\xBF") {
        Some(rest) => (rest, true),
        None => (bytes, false),
    };
    match std::str::from_utf8(bytes) {
        Ok(text) => {
            if bom || !text.is_ascii() {
                let mark = if bom { " with a byte-order mark" } else { "" };
                notes.push(format!("read as UTF-8{mark}"));
            }
            text.to_string()
        }
        Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
    }
}

/// A key's unit with a replaced unit character (U+FFFD) restored where only one reading
/// is possible: before `s` the prefix µ, before `C` or `F` the degree sign.
fn repair_unit(key: &str, unit: String, line: usize, notes: &mut Vec<String>) -> String {
    if !unit.contains('\u{FFFD}') {
        return unit;
    }
    let repaired = match unit.as_str() {
        "\u{FFFD}s" => "µs",
        "\u{FFFD}C" => "°C",
        "\u{FFFD}F" => "°F",
        _ => return unit,
    };
    notes.push(format!(
        "line {line}: `{}` has a replaced character (U+FFFD) in its unit, read as \"{repaired}\"",
        key.trim()
    ));
    repaired.to_string()
}

/// First line of the samples (1-based): after the names, t0 and dt.
const FIRST_SAMPLE_LINE: usize = 4;

impl RawRecord {
    pub fn read(file: &Path) -> Result<RawRecord, ExperimentError> {
        let io = |reason| ExperimentError::Io {
            file: file.to_path_buf(),
            reason,
        };
        let size = std::fs::metadata(file).map_err(io)?.len();
        crate::experiment::limits::TEXT_FILE_BYTES
            .check(size as f64, || file.display().to_string())
            .map_err(|e| invalid(file, 1, 1, "file", e.to_string()))?;
        let bytes = std::fs::read(file).map_err(io)?;
        let mut notes = Vec::new();
        let text = decode(&bytes, &mut notes);
        let mut record = parse(&text, file, &mut notes)?;
        record.notes = notes;
        Ok(record)
    }

    /// The entry named `name` (without unit), or an error naming the key that is missing.
    pub fn entry(&self, name: &str) -> Result<&Entry, ExperimentError> {
        self.metadata
            .iter()
            .find(|e| e.name == name)
            .ok_or_else(|| {
                invalid(
                    &self.file,
                    1,
                    1,
                    name,
                    "missing from the metadata (columns 1-2) of this LANL raw record".into(),
                )
            })
    }

    /// The number under `name`, converted from the key's unit to SI as `dimension`
    /// (`None`: a plain number).
    pub fn number(&self, name: &str, dimension: Option<Dimension>) -> Result<f64, ExperimentError> {
        let e = self.entry(name)?;
        let bad = |problem: String| invalid(&self.file, e.line, 2, &e.name, problem);
        let v: f64 = e
            .value
            .trim()
            .parse()
            .map_err(|_| bad(format!("expected a number, found \"{}\"", e.value)))?;
        if !v.is_finite() {
            return Err(bad(format!("{v} is not a finite number")));
        }
        let Some(dimension) = dimension else {
            return Ok(v);
        };
        let unit = e.unit.replace('°', "deg");
        match dimension.to_si(&unit) {
            Some(conversion) => Ok(conversion.apply(v)),
            None => Err(bad(format!(
                "unit \"{}\" in the key, expected one of {}",
                e.unit,
                dimension.accepted()
            ))),
        }
    }

    /// Sample times [s].
    pub fn time_s(&self) -> Vec<f64> {
        (0..self.incident_v.len())
            .map(|k| self.t0_s + k as f64 * self.dt_s)
            .collect()
    }
}

/// Relative difference above which two statements of one quantity disagree.
const AGREE: f64 = 0.02;

impl RawRecord {
    /// The record must be a compression test.
    pub fn check_compression(&self) -> Result<(), ExperimentError> {
        let loading = self.entry("Test Loading")?;
        match loading.value.as_str() {
            "Compression" => Ok(()),
            other => Err(self.invalid_at(
                loading.line,
                "Test Loading",
                format!("\"{other}\": only compression records are processed"),
            )),
        }
    }

    /// The bars, which must be of one material and diameter. c0 is the rod sound speed
    /// and ρ = E/c0² (the stated density is checked against it: one record writes g/cm³
    /// under a kg/m³ label). The incident delay is half the calibrated reflected time; the
    /// transmitted one is its gauge distance over the same calibrated timing speed (one
    /// bar material, one calibration).
    pub fn bar(&self, notes: &mut Vec<String>) -> Result<Bar, ExperimentError> {
        let e = self.both_bars("Young's Modulus", Some(Dimension::Modulus))?;
        let c0 = self.both_bars("Rod Sound Speed", Some(Dimension::Velocity))?;
        let density = e / (c0 * c0);
        let stated = self.number("Incident Bar Density", Some(Dimension::Density))?;
        if ((1e3 * stated) / density - 1.0).abs() < AGREE {
            notes.push(format!("Incident Bar Density(kg/m^3) = {stated} looks like g/cm^3: E/c0^2 = {density:.0} kg/m^3 is used"));
        } else if (stated / density - 1.0).abs() > AGREE {
            notes.push(format!("Incident Bar Density(kg/m^3) = {stated} disagrees with E/c0^2 = {density:.0} kg/m^3, which is used"));
        }
        let length = Some(Dimension::Length);
        let round_trip = self.number(
            "Incident Bar Calibrated Reflected Time",
            Some(Dimension::Time),
        )?;
        let timing = self.number(
            "Incident Bar Reflected Time Sound Speed",
            Some(Dimension::Velocity),
        )?;
        let transmitted_distance = self.number("Transmitted Bar Strain Gage Location", length)?;
        notes.push(format!(
            "timing at the calibrated {timing:.1} m/s, impedance at c0 = {c0:.1} m/s"
        ));
        let nu = self.both_bars("Poisson Ratio", None)?;
        if let Err(problem) = Bar::check_poisson_ratio(nu) {
            let line = self.entry("Incident Bar Poisson Ratio")?.line;
            return Err(self.invalid_at(line, "Poisson Ratio", problem));
        }
        let bar = Bar {
            elastic_modulus_pa: e,
            density_kg_m3: density,
            diameter_m: self.both_bars("Diameter", Some(Dimension::Length))?,
            incident_gauge_to_specimen_m: self
                .number("Incident Bar Strain Gage Location", length)?,
            transmitted_gauge_to_specimen_m: transmitted_distance,
            incident_delay_calibrated_s: Some(0.5 * round_trip),
            transmitted_delay_calibrated_s: Some(transmitted_distance / timing),
            poisson_ratio: Some(nu),
        };
        if let Err(problem) = bar.check_wave_speed(false) {
            let line = self.entry("Incident Bar Rod Sound Speed")?.line;
            return Err(self.invalid_at(line, "Rod Sound Speed", problem));
        }
        Ok(bar)
    }

    /// The value of `Incident Bar {key}`, which `Transmitted Bar {key}` must repeat.
    fn both_bars(&self, key: &str, dimension: Option<Dimension>) -> Result<f64, ExperimentError> {
        let incident = self.number(&format!("Incident Bar {key}"), dimension)?;
        let transmitted = self.number(&format!("Transmitted Bar {key}"), dimension)?;
        if (incident - transmitted).abs() > 1e-9 * incident.abs() {
            let line = self.entry(&format!("Transmitted Bar {key}"))?.line;
            return Err(self.invalid_at(line, key, format!("{transmitted} on the transmitted bar against {incident} on the incident bar: mpw processes two bars of one material and diameter")));
        }
        Ok(incident)
    }

    /// Strain of the `bar_name` ("Incident", "Transmitted") gauge [-]:
    /// ε = scale · U / (k · U_ex · gain), `scale` = ±4/n_active (the bridge and the
    /// polarity), with the test's gain under `gain_key`; a bar block's `Calibrated Gain`
    /// that differs from it is noted.
    pub fn gauge_strain(
        &self,
        bar_name: &str,
        gain_key: &str,
        scale: f64,
        notes: &mut Vec<String>,
    ) -> Result<Vec<f64>, ExperimentError> {
        let key = |k: &str| format!("{bar_name} Bar {k}");
        let gain = self.positive(gain_key, None)?;
        let calibrated = self.number(&key("Calibrated Gain"), None)?;
        if (calibrated / gain - 1.0).abs() > 1e-9 {
            notes.push(format!(
                "{} = {calibrated} differs from {gain_key} = {gain}; the test's {gain} is used",
                key("Calibrated Gain")
            ));
        }
        let gauge_factor = self.positive(&key("Calibrated Gage Factor"), None)?;
        let excitation = self.positive(&key("Excitation Voltage"), Some(Dimension::Voltage))?;
        let volts = match bar_name {
            "Incident" => &self.incident_v,
            _ => &self.transmitted_v,
        };
        let per_volt = scale / (gauge_factor * excitation * gain);
        Ok(volts.iter().map(|u| u * per_volt).collect())
    }

    /// `number`, which must be positive.
    fn positive(&self, name: &str, dimension: Option<Dimension>) -> Result<f64, ExperimentError> {
        let v = self.number(name, dimension)?;
        match v > 0.0 {
            true => Ok(v),
            false => Err(self.invalid_at(
                self.entry(name)?.line,
                name,
                format!("{v}: must be positive"),
            )),
        }
    }

    /// An invalid value in column 2 of `line`.
    fn invalid_at(&self, line: usize, key: &str, problem: String) -> ExperimentError {
        invalid(&self.file, line, 2, key, problem)
    }
}

/// An invalid value at `file:line:column`.
fn invalid(file: &Path, line: usize, column: usize, key: &str, problem: String) -> ExperimentError {
    ExperimentError::InvalidValue {
        at: Location {
            file: file.to_path_buf(),
            line,
            column,
        },
        key: key.to_string(),
        problem,
    }
}

/// `Diameter(mm)` → ("Diameter", "mm").
fn split_unit(key: &str) -> (String, String) {
    match (key.rfind('('), key.ends_with(')')) {
        (Some(open), true) => (
            key[..open].trim().to_string(),
            key[open + 1..key.len() - 1].to_string(),
        ),
        _ => (key.trim().to_string(), String::new()),
    }
}

fn parse(text: &str, file: &Path, notes: &mut Vec<String>) -> Result<RawRecord, ExperimentError> {
    let mut metadata = Vec::new();
    let mut columns: [Vec<(usize, &str)>; 2] = [Vec::new(), Vec::new()];
    for (k, raw_line) in text.lines().enumerate() {
        let line = k + 1;
        let fields: Vec<&str> = raw_line.trim_end_matches('\r').split('\t').collect();
        if let (Some(key), Some(value)) = (fields.first(), fields.get(1)) {
            if !key.trim().is_empty() {
                let (name, unit) = split_unit(key);
                let unit = repair_unit(key, unit, line, notes);
                metadata.push(Entry {
                    name,
                    unit,
                    value: value.trim().to_string(),
                    line,
                });
            }
        }
        for (c, column) in columns.iter_mut().enumerate() {
            match fields.get(2 + c).map(|f| f.trim()) {
                Some(f) if !f.is_empty() => column.push((line, f)),
                _ => {}
            }
        }
    }
    let number = |(line, f): (usize, &str), c: usize| {
        f.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                invalid(
                    file,
                    line,
                    3 + c,
                    "waveform",
                    format!("expected a number in column {}, found \"{f}\"", 3 + c),
                )
            })
    };
    let mut waves = Vec::with_capacity(2);
    for (c, column) in columns.iter().enumerate() {
        // names, t0, dt on lines 1-3; samples on consecutive lines from line 4
        let header: Vec<usize> = column.iter().take(3).map(|(line, _)| *line).collect();
        if header != [1, 2, 3] || column.len() <= 3 {
            return Err(invalid(
                file,
                1,
                3 + c,
                "waveform",
                format!("column {}: expected the waveform's name on line 1, t0 [s] on line 2, dt [s] on line 3 and samples from line {FIRST_SAMPLE_LINE}: is this a LANL standard raw record?", 3 + c),
            ));
        }
        let samples = &column[3..];
        if let Some(gap) = samples
            .iter()
            .enumerate()
            .find(|(k, (line, _))| *line != FIRST_SAMPLE_LINE + k)
        {
            return Err(invalid(
                file,
                gap.1 .0,
                3 + c,
                "waveform",
                format!("a sample is missing in column {} before this line", 3 + c),
            ));
        }
        let t0 = number(column[1], c)?;
        let dt = number(column[2], c)?;
        let values = samples
            .iter()
            .map(|s| number(*s, c))
            .collect::<Result<Vec<f64>, _>>()?;
        waves.push((t0, dt, values));
    }
    let (transmitted, incident) = (waves.pop().unwrap(), waves.pop().unwrap());
    if incident.0 != transmitted.0 || incident.1 != transmitted.1 || incident.1 <= 0.0 {
        return Err(invalid(
            file,
            2,
            3,
            "waveform",
            format!(
                "both waveforms need one time base with dt > 0: t0 {} / {} s, dt {} / {} s",
                incident.0, transmitted.0, incident.1, transmitted.1
            ),
        ));
    }
    if incident.2.len() != transmitted.2.len() {
        return Err(invalid(
            file,
            FIRST_SAMPLE_LINE,
            3,
            "waveform",
            format!(
                "{} incident and {} transmitted samples: the columns must be equally long",
                incident.2.len(),
                transmitted.2.len()
            ),
        ));
    }
    Ok(RawRecord {
        file: file.to_path_buf(),
        metadata,
        t0_s: incident.0,
        dt_s: incident.1,
        incident_v: incident.2,
        transmitted_v: transmitted.2,
        notes: Vec::new(),
    })
}
