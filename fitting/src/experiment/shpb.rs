//! Split-Hopkinson-Pressure-Bar experiments: raw bar strains (incident gauge with the
//! incident and reflected pulses, transmitted gauge) plus bar and specimen metadata.
//!
//! ```toml
//! kind = "shpb"
//! name = "945 steel, test 01"          # optional, default: the TOML's file stem
//! data = "path/relative/to/this.csv"
//! temperature = "293.15 K"
//! polarity = "compression-negative"   # default; "compression-positive" flips both gauges
//! alignment = "geometric"              # default; "arrival" or "force-balance" (shpb::alignment)
//! dispersion = false                   # default; true corrects for Pochhammer-Chree dispersion (needs bar.poisson_ratio)
//! # savitzky_golay = { window = 31, order = 3 }   # filter both gauges (window in samples, odd)
//! [columns]
//! time = { name = "time_s", unit = "s" }
//! incident = { name = "incident_microstrain", unit = "microstrain" }
//! transmitted = { name = "transmitted_microstrain", unit = "microstrain" }
//! # a column in volts names its bridge; strain = 4 U / (active_arms · gauge_factor · excitation · gain)
//! # incident = { name = "ch1", unit = "V", gauge_factor = 2.1, excitation = "10 V", gain = 100, active_arms = 2 }
//! [bar]
//! elastic_modulus = "210 GPa"
//! density = "7800 kg/m^3"              # or wave_speed = "5189 m/s" (c0 = sqrt(E/rho))
//! diameter = "20 mm"
//! incident_gauge_to_specimen = "1020 mm"
//! transmitted_gauge_to_specimen = "770 mm"
//! poisson_ratio = 0.29                 # optional; needed by dispersion = true
//! # calibrated gauge-to-face travel times, when the laboratory measured them; default
//! # distance / c0 (c0 stays the impedance wave speed)
//! # incident_gauge_delay = "196.6 us"
//! # transmitted_gauge_delay = "148.4 us"
//! [specimen]
//! diameter = "8 mm"
//! length = "4 mm"
//! ```
//! Every `[bar]` and `[specimen]` key and `temperature` may instead sit in the CSV's `#`
//! header under the same name with `_` for `.` (`# bar_diameter: 20 mm`,
//! `# specimen_length: 4 mm`, `# bar_poisson_ratio: 0.29`, `# temperature: 293 K`); the
//! TOML overrides the header.
//!
//! A record in the LANL standard raw format (`lanl_raw`) needs only a short TOML; the
//! file states bars, gauges, gains, specimen and temperature, but not the bridge:
//! ```toml
//! kind = "shpb"
//! format = "lanl-raw"
//! data = "20061201_1148HE_CuOFE_273K.raw"
//! polarity = "compression-positive"
//! active_arms = 2
//! ```
//! Strains are stored compression negative, in strain [-]: a record declared
//! compression-positive is flipped on loading. Whether the pulses agree with the declared
//! polarity is checked by the processing (`shpb::pulses`).

use super::error::ExperimentError;
use super::header::{self, Source};
use super::lanl_raw::RawRecord;
use super::processing::{Alignment, Processing, SavitzkyGolay};
use super::sidecar::{ColumnSpec, Sidecar};
use super::table::CsvTable;
use super::units::Dimension;
use serde::Deserialize;
use std::f64::consts::PI;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ShpbFile {
    /// Checked by `Sidecar::parse_kind` before this type is parsed.
    #[allow(dead_code)]
    kind: Spanned<String>,
    name: Option<String>,
    data: Spanned<String>,
    temperature: Option<Spanned<String>>,
    polarity: Option<Spanned<String>>,
    alignment: Option<Spanned<String>>,
    dispersion: Option<Spanned<bool>>,
    savitzky_golay: Option<FilterSpec>,
    columns: ShpbColumns,
    #[serde(default)]
    bar: BarSpec,
    #[serde(default)]
    specimen: SpecimenSpec,
}

/// The `format` key alone, read before the rest of the file.
#[derive(Deserialize)]
struct FormatOnly {
    format: Option<Spanned<String>>,
}

/// The TOML of a LANL standard raw record.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LanlFile {
    /// Checked by `Sidecar::parse_kind` before this type is parsed, and `format` by
    /// `ShpbExperiment::load`.
    #[allow(dead_code)]
    kind: Spanned<String>,
    #[allow(dead_code)]
    format: Spanned<String>,
    name: Option<String>,
    data: Spanned<String>,
    polarity: Option<Spanned<String>>,
    alignment: Option<Spanned<String>>,
    dispersion: Option<Spanned<bool>>,
    savitzky_golay: Option<FilterSpec>,
    active_arms: Spanned<u32>,
}

/// `savitzky_golay = { window = 31, order = 3 }`: window in samples (odd).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FilterSpec {
    window: usize,
    order: usize,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ShpbColumns {
    time: ColumnSpec,
    incident: GaugeColumnSpec,
    transmitted: GaugeColumnSpec,
}

/// A strain-gauge column: in a strain unit, or in volts with its bridge.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GaugeColumnSpec {
    name: Spanned<String>,
    unit: Spanned<String>,
    gauge_factor: Option<Spanned<f64>>,
    excitation: Option<Spanned<String>>,
    gain: Option<Spanned<f64>>,
    active_arms: Option<Spanned<u32>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct BarSpec {
    elastic_modulus: Option<Spanned<String>>,
    density: Option<Spanned<String>>,
    wave_speed: Option<Spanned<String>>,
    diameter: Option<Spanned<String>>,
    incident_gauge_to_specimen: Option<Spanned<String>>,
    transmitted_gauge_to_specimen: Option<Spanned<String>>,
    incident_gauge_delay: Option<Spanned<String>>,
    transmitted_gauge_delay: Option<Spanned<String>>,
    poisson_ratio: Option<Spanned<f64>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct SpecimenSpec {
    diameter: Option<Spanned<String>>,
    length: Option<Spanned<String>>,
}

/// Wave speeds of SHPB bars, from polymer (PMMA ≈ 2000 m/s, nylon lower) to steel and
/// titanium (≈ 5000 m/s) with margin [m/s].
pub const PLAUSIBLE_WAVE_SPEED: (f64, f64) = (1000.0, 8000.0);

/// The incident and transmitted bars (same material and diameter).
#[derive(Debug, Clone, PartialEq)]
pub struct Bar {
    /// Young's modulus E_b [Pa].
    pub elastic_modulus_pa: f64,
    /// Density ρ_b [kg/m³].
    pub density_kg_m3: f64,
    /// Bar diameter [m].
    pub diameter_m: f64,
    /// Distance from the incident-bar gauge to the specimen face [m].
    pub incident_gauge_to_specimen_m: f64,
    /// Distance from the transmitted-bar gauge to the specimen face [m].
    pub transmitted_gauge_to_specimen_m: f64,
    /// Calibrated travel times from the incident and transmitted gauges to the specimen
    /// faces [s], when the laboratory measured them (`None`: distance over c0).
    pub incident_delay_calibrated_s: Option<f64>,
    pub transmitted_delay_calibrated_s: Option<f64>,
    /// Poisson's ratio ν of the bars, for the dispersion correction [-].
    pub poisson_ratio: Option<f64>,
}

impl Bar {
    /// Bar wave speed c0 = √(E_b/ρ_b) [m/s].
    pub fn wave_speed_m_per_s(&self) -> f64 {
        (self.elastic_modulus_pa / self.density_kg_m3).sqrt()
    }

    /// The bar wave speed if it lies in `PLAUSIBLE_WAVE_SPEED` (bars of steel, titanium,
    /// aluminium, magnesium, polymers), else what is wrong and the likely cause (from the
    /// density when it was stated, `stated_density`).
    pub fn check_wave_speed(&self, stated_density: bool) -> Result<f64, String> {
        let c0 = self.wave_speed_m_per_s();
        let (low, high) = PLAUSIBLE_WAVE_SPEED;
        if (low..=high).contains(&c0) {
            return Ok(c0);
        }
        let (e, rho) = (self.elastic_modulus_pa, self.density_kg_m3);
        let likely = if stated_density && rho < 100.0 {
            format!("the density {rho} kg/m³ looks like g/cm³")
        } else if stated_density && rho > 30e3 {
            format!("the density {rho} kg/m³ is beyond any metal's")
        } else if e < 1e9 {
            format!(
                "the modulus {e:e} Pa looks like a value in MPa or GPa written in a smaller unit"
            )
        } else {
            "check the modulus and the density (or the wave speed)".into()
        };
        Err(format!(
            "bar wave speed c0 = √(E/ρ) = {c0:.0} m/s is outside the {low:.0}-{high:.0} m/s of SHPB bars: {likely}"
        ))
    }

    /// `nu` if it is a Poisson ratio, in (0, 0.5), else what is wrong.
    pub fn check_poisson_ratio(nu: f64) -> Result<f64, String> {
        if nu > 0.0 && nu < 0.5 {
            Ok(nu)
        } else {
            Err(format!(
                "{nu}: expected a Poisson ratio between 0 and 0.5 (steel 0.29, titanium 0.32)"
            ))
        }
    }

    /// Cross-section A_b = π d²/4 [m²].
    pub fn area_m2(&self) -> f64 {
        PI * self.diameter_m * self.diameter_m / 4.0
    }

    /// Travel time from the incident gauge to the specimen face [s]: calibrated, or d_i/c0.
    pub fn incident_delay_s(&self) -> f64 {
        self.incident_delay_calibrated_s
            .unwrap_or(self.incident_gauge_to_specimen_m / self.wave_speed_m_per_s())
    }

    /// Travel time from the specimen face to the transmitted gauge [s]: calibrated, or
    /// d_t/c0.
    pub fn transmitted_delay_s(&self) -> f64 {
        self.transmitted_delay_calibrated_s
            .unwrap_or(self.transmitted_gauge_to_specimen_m / self.wave_speed_m_per_s())
    }
}

/// The cylindrical specimen, undeformed.
#[derive(Debug, Clone, PartialEq)]
pub struct Specimen {
    /// Diameter [m].
    pub diameter_m: f64,
    /// Length L_s between the bar faces [m].
    pub length_m: f64,
}

impl Specimen {
    /// Cross-section A_s = π d²/4 [m²].
    pub fn area_m2(&self) -> f64 {
        PI * self.diameter_m * self.diameter_m / 4.0
    }

    /// What is wrong when the specimen is not narrower than `bar`: it sits between the
    /// bar faces, and the stress σ = E_b A_b ε_t / A_s of a specimen as wide as the bar or
    /// wider is a sign of a unit written wrong ("8 m" for "8 mm").
    pub fn too_wide_for(&self, bar: &Bar) -> Option<String> {
        let (d, bar_d) = (self.diameter_m, bar.diameter_m);
        (d >= bar_d).then(|| {
            format!(
                "{d:e} m is not smaller than the bar diameter {bar_d:e} m: the specimen sits \
                 between the bar faces (a unit written wrong, e.g. \"8 m\" for \"8 mm\"?)"
            )
        })
    }
}

/// An SHPB record in SI units, strains compression negative.
#[derive(Debug, Clone)]
pub struct ShpbExperiment {
    pub name: String,
    /// The CSV the samples were read from.
    pub data_file: PathBuf,
    pub bar: Bar,
    pub specimen: Specimen,
    /// Test temperature [K].
    pub temperature_k: f64,
    /// Sample times [s], strictly increasing.
    pub time_s: Vec<f64>,
    /// Incident-bar gauge strain [-] (incident and reflected pulses).
    pub incident: Vec<f64>,
    /// Transmitted-bar gauge strain [-].
    pub transmitted: Vec<f64>,
    /// How the processing moves the pulses to the specimen faces.
    pub processing: Processing,
    /// What the reader noticed and decided (a density in g/cm³ under a kg/m³ label,
    /// gains that disagree), for the report.
    pub notes: Vec<String>,
}

impl ShpbExperiment {
    /// Read an SHPB experiment TOML and the CSV it names.
    pub fn load(toml_file: &Path) -> Result<ShpbExperiment, ExperimentError> {
        let sidecar = Sidecar::read(toml_file)?;
        match sidecar.parse::<FormatOnly>()?.format {
            None => {}
            Some(f) if f.get_ref() == "csv" => {}
            Some(f) if f.get_ref() == "lanl-raw" => return load_lanl(&sidecar, toml_file),
            Some(f) => {
                return Err(sidecar.invalid(
                    "format",
                    f.span(),
                    format!(
                        "\"{}\": expected \"csv\" (the default) or \"lanl-raw\"",
                        f.get_ref()
                    ),
                ))
            }
        }
        let spec: ShpbFile = sidecar.parse_kind("shpb")?;
        let sign = polarity_sign(&sidecar, spec.polarity.as_ref())?;
        let data_file = sidecar.data_path(&spec.data)?;
        let table = CsvTable::read_rows(&data_file, 2)?;
        let temperature_k = sidecar
            .metadata(
                &table,
                ("temperature", spec.temperature.as_ref()),
                header::TEMPERATURE_KEYS,
                Dimension::Temperature,
            )?
            .0;
        let meta = Metadata {
            sidecar: &sidecar,
            table: &table,
        };
        let bar = meta.bar(&spec.bar)?;
        let specimen = Specimen {
            diameter_m: meta.required(
                "specimen.diameter",
                &spec.specimen.diameter,
                Dimension::Length,
            )?,
            length_m: meta.required("specimen.length", &spec.specimen.length, Dimension::Length)?,
        };
        if let Some(problem) = specimen.too_wide_for(&bar) {
            let span = spec.specimen.diameter.as_ref().map_or(0..0, |d| d.span());
            return Err(sidecar.invalid("specimen.diameter", span, problem));
        }
        let time_s = sidecar.column(&table, "columns.time", &spec.columns.time, Dimension::Time)?;
        sidecar.check_time_increases(&table, &spec.columns.time, &time_s)?;
        let flip = |v: Vec<f64>| -> Vec<f64> { v.into_iter().map(|x| sign * x).collect() };
        let incident = flip(gauge_strain(
            &sidecar,
            &table,
            "columns.incident",
            &spec.columns.incident,
        )?);
        let transmitted = flip(gauge_strain(
            &sidecar,
            &table,
            "columns.transmitted",
            &spec.columns.transmitted,
        )?);
        Ok(ShpbExperiment {
            name: spec.name.unwrap_or_else(|| stem(toml_file)),
            data_file,
            specimen,
            temperature_k,
            time_s,
            incident,
            transmitted,
            processing: processing(
                &sidecar,
                ProcessingKeys {
                    alignment: spec.alignment.as_ref(),
                    dispersion: spec.dispersion.as_ref(),
                    savitzky_golay: spec.savitzky_golay.as_ref(),
                },
                &bar,
            )?,
            bar,
            notes: Vec::new(),
        })
    }
}

/// Bar and specimen metadata of a CSV record: each key from the TOML, else from the
/// CSV's `#` header under the same name with `_` for `.` (`# bar_diameter: 20 mm`,
/// `# specimen_length: 4 mm`, `# bar_poisson_ratio: 0.29`).
struct Metadata<'a> {
    sidecar: &'a Sidecar,
    table: &'a CsvTable,
}

impl Metadata<'_> {
    fn optional(
        &self,
        key: &str,
        value: &Option<Spanned<String>>,
        dimension: Dimension,
    ) -> Result<Option<(f64, Source)>, ExperimentError> {
        let header_key = key.replace('.', "_");
        self.sidecar.optional_metadata(
            self.table,
            (key, value.as_ref()),
            &[(header_key.as_str(), "")],
            dimension,
        )
    }

    fn required(
        &self,
        key: &str,
        value: &Option<Spanned<String>>,
        dimension: Dimension,
    ) -> Result<f64, ExperimentError> {
        let header_key = key.replace('.', "_");
        let found = self.sidecar.metadata(
            self.table,
            (key, value.as_ref()),
            &[(header_key.as_str(), "")],
            dimension,
        )?;
        Ok(found.0)
    }

    /// An error about the value read from `source` (`span`: its place in the TOML).
    fn invalid(
        &self,
        source: &Source,
        span: Option<Range<usize>>,
        problem: String,
    ) -> ExperimentError {
        match source {
            Source::Toml { key } => self.sidecar.invalid(key, span.unwrap_or(0..0), problem),
            Source::Header { key, line } => ExperimentError::BadHeader {
                file: self.table.file.clone(),
                line: *line,
                key: key.clone(),
                problem,
            },
        }
    }

    fn bar(&self, b: &BarSpec) -> Result<Bar, ExperimentError> {
        let elastic_modulus_pa = self.required(
            "bar.elastic_modulus",
            &b.elastic_modulus,
            Dimension::Modulus,
        )?;
        if b.density.is_some() && b.wave_speed.is_some() {
            let span = b.density.as_ref().map_or(0..0, |d| d.span());
            return Err(self.sidecar.invalid(
                "bar.density",
                span,
                "the bar needs exactly one of `density` and `wave_speed`",
            ));
        }
        let density = match &b.wave_speed {
            Some(_) => None,
            None => self.optional("bar.density", &b.density, Dimension::Density)?,
        };
        let stated_density = density.is_some();
        let (density_kg_m3, source, span) = match density {
            Some((rho, source)) => (rho, source, b.density.as_ref().map(|d| d.span())),
            None => {
                let (c0, source) = self
                    .optional("bar.wave_speed", &b.wave_speed, Dimension::Velocity)?
                    .ok_or_else(|| ExperimentError::MissingMetadata {
                        toml: self.sidecar.file.clone(),
                        csv: self.table.file.clone(),
                        key: "bar.density` or `bar.wave_speed".into(),
                        header_keys: "`bar_density`, `bar_wave_speed`".into(),
                    })?;
                let span = b.wave_speed.as_ref().map(|c| c.span());
                (elastic_modulus_pa / (c0 * c0), source, span)
            }
        };
        let delay = |key: &str, value: &Option<Spanned<String>>| {
            Ok::<_, ExperimentError>(self.optional(key, value, Dimension::Time)?.map(|d| d.0))
        };
        let bar = Bar {
            elastic_modulus_pa,
            density_kg_m3,
            diameter_m: self.required("bar.diameter", &b.diameter, Dimension::Length)?,
            incident_gauge_to_specimen_m: self.required(
                "bar.incident_gauge_to_specimen",
                &b.incident_gauge_to_specimen,
                Dimension::Length,
            )?,
            transmitted_gauge_to_specimen_m: self.required(
                "bar.transmitted_gauge_to_specimen",
                &b.transmitted_gauge_to_specimen,
                Dimension::Length,
            )?,
            incident_delay_calibrated_s: delay(
                "bar.incident_gauge_delay",
                &b.incident_gauge_delay,
            )?,
            transmitted_delay_calibrated_s: delay(
                "bar.transmitted_gauge_delay",
                &b.transmitted_gauge_delay,
            )?,
            poisson_ratio: self.poisson_ratio(b)?,
        };
        bar.check_wave_speed(stated_density)
            .map_err(|problem| self.invalid(&source, span, problem))?;
        Ok(bar)
    }

    /// Poisson's ratio of the bars (TOML `bar.poisson_ratio` or header
    /// `bar_poisson_ratio`), which must lie in (0, 0.5).
    fn poisson_ratio(&self, b: &BarSpec) -> Result<Option<f64>, ExperimentError> {
        let found = match &b.poisson_ratio {
            Some(nu) => Some((
                *nu.get_ref(),
                Source::Toml {
                    key: "bar.poisson_ratio".into(),
                },
            )),
            // a ratio, read as a strain of unit "1"
            None => self.sidecar.optional_metadata(
                self.table,
                ("bar.poisson_ratio", None),
                &[("bar_poisson_ratio", "1")],
                Dimension::Strain,
            )?,
        };
        found
            .map(|(nu, source)| {
                Bar::check_poisson_ratio(nu).map_err(|problem| {
                    self.invalid(&source, b.poisson_ratio.as_ref().map(|v| v.span()), problem)
                })
            })
            .transpose()
    }
}

fn stem(toml_file: &Path) -> String {
    toml_file
        .file_stem()
        .map_or_else(|| "shpb".into(), |s| s.to_string_lossy().into_owned())
}

/// The keys that choose the processing, as written in the TOML.
struct ProcessingKeys<'a> {
    alignment: Option<&'a Spanned<String>>,
    dispersion: Option<&'a Spanned<bool>>,
    savitzky_golay: Option<&'a FilterSpec>,
}

/// The `alignment` (default geometric), `dispersion` (default off; on, it needs the bar's
/// Poisson ratio) and `savitzky_golay` (default none) keys.
fn processing(
    sidecar: &Sidecar,
    keys: ProcessingKeys,
    bar: &Bar,
) -> Result<Processing, ExperimentError> {
    let ProcessingKeys {
        alignment,
        dispersion,
        savitzky_golay,
    } = keys;
    let filter = savitzky_golay
        .map(|f| {
            SavitzkyGolay::new(f.window, f.order).map_err(|problem| {
                sidecar.invalid(
                    "savitzky_golay",
                    sidecar.table_span("savitzky_golay"),
                    problem,
                )
            })
        })
        .transpose()?;
    let alignment = match alignment {
        None => Alignment::Geometric,
        Some(a) => a
            .get_ref()
            .parse()
            .map_err(|problem: String| sidecar.invalid("alignment", a.span(), problem))?,
    };
    if let (Some(d), None) = (dispersion.filter(|d| *d.get_ref()), bar.poisson_ratio) {
        return Err(sidecar.invalid(
            "dispersion",
            d.span(),
            "the dispersion correction needs the bars' Poisson ratio: state bar.poisson_ratio",
        ));
    }
    Ok(Processing {
        alignment,
        dispersion: dispersion.is_some_and(|d| *d.get_ref()),
        filter,
    })
}

/// +1 for a record stored compression negative (the default), −1 for one declared
/// `polarity = "compression-positive"`.
fn polarity_sign(
    sidecar: &Sidecar,
    polarity: Option<&Spanned<String>>,
) -> Result<f64, ExperimentError> {
    match polarity.map(|p| (p.get_ref().as_str(), p.span())) {
        None | Some(("compression-negative", _)) => Ok(1.0),
        Some(("compression-positive", _)) => Ok(-1.0),
        Some((other, span)) => Err(sidecar.invalid(
            "polarity",
            span,
            format!("\"{other}\": expected \"compression-negative\" (the default) or \"compression-positive\""),
        )),
    }
}

/// A LANL standard raw record (`lanl_raw`) with its TOML: bars, gauges, gains, specimen
/// and temperature from the file (`RawRecord::bar`, `RawRecord::gauge_strain`), the
/// bridge and polarity from the TOML.
fn load_lanl(sidecar: &Sidecar, toml_file: &Path) -> Result<ShpbExperiment, ExperimentError> {
    let spec: LanlFile = sidecar.parse_kind("shpb")?;
    let sign = polarity_sign(sidecar, spec.polarity.as_ref())?;
    let arms = *spec.active_arms.get_ref();
    if ![1, 2, 4].contains(&arms) {
        return Err(sidecar.invalid("active_arms", spec.active_arms.span(), "expected 1, 2 or 4"));
    }
    let data_file = sidecar.data_path(&spec.data)?;
    let raw = RawRecord::read(&data_file)?;
    raw.check_compression()?;
    let mut notes = raw.notes.clone();
    let bar = raw.bar(&mut notes)?;
    let scale = sign * 4.0 / f64::from(arms);
    let incident =
        raw.gauge_strain("Incident", "Incident/Reflected Bar Gain", scale, &mut notes)?;
    let transmitted = raw.gauge_strain("Transmitted", "Transmitted Bar Gain", scale, &mut notes)?;
    Ok(ShpbExperiment {
        name: spec.name.unwrap_or_else(|| stem(toml_file)),
        specimen: Specimen {
            diameter_m: raw.number("Initial Sample Diameter", Some(Dimension::Length))?,
            length_m: raw.number("Initial Sample Length", Some(Dimension::Length))?,
        },
        temperature_k: raw.number("Test Temperature", Some(Dimension::Temperature))?,
        time_s: raw.time_s(),
        incident,
        transmitted,
        processing: processing(
            sidecar,
            ProcessingKeys {
                alignment: spec.alignment.as_ref(),
                dispersion: spec.dispersion.as_ref(),
                savitzky_golay: spec.savitzky_golay.as_ref(),
            },
            &bar,
        )?,
        bar,
        notes,
        data_file,
    })
}

/// Gauge strain [-] from a strain column, or from a bridge voltage U:
/// ε = 4 U / (n_active · k · U_ex · gain) (small-signal Wheatstone bridge).
fn gauge_strain(
    sidecar: &Sidecar,
    table: &CsvTable,
    key: &str,
    spec: &GaugeColumnSpec,
) -> Result<Vec<f64>, ExperimentError> {
    let column = ColumnSpec {
        name: spec.name.clone(),
        unit: spec.unit.clone(),
    };
    let bridge_keys = [
        spec.gauge_factor
            .as_ref()
            .map(|v| ("gauge_factor", v.span())),
        spec.excitation.as_ref().map(|v| ("excitation", v.span())),
        spec.gain.as_ref().map(|v| ("gain", v.span())),
        spec.active_arms.as_ref().map(|v| ("active_arms", v.span())),
    ];
    if Dimension::Voltage.to_si(spec.unit.get_ref()).is_none() {
        if let Some((bridge_key, span)) = bridge_keys.into_iter().flatten().next() {
            return Err(sidecar.invalid(
                &format!("{key}.{bridge_key}"),
                span,
                "bridge settings belong to a column in volts (unit \"V\" or \"mV\")",
            ));
        }
        return sidecar.column(table, key, &column, Dimension::Strain);
    }
    let missing = |what: &str| {
        sidecar.invalid(
            &format!("{key}.unit"),
            spec.unit.span(),
            format!("a column in volts needs `{what}` (gauge_factor, excitation, active_arms; gain defaults to 1)"),
        )
    };
    let positive = |name: &str, v: &Spanned<f64>| {
        if *v.get_ref() > 0.0 && v.get_ref().is_finite() {
            Ok(*v.get_ref())
        } else {
            Err(sidecar.invalid(
                &format!("{key}.{name}"),
                v.span(),
                "must be a positive number",
            ))
        }
    };
    let gauge_factor = positive(
        "gauge_factor",
        spec.gauge_factor
            .as_ref()
            .ok_or_else(|| missing("gauge_factor"))?,
    )?;
    let excitation = sidecar.positive(
        &format!("{key}.excitation"),
        spec.excitation
            .as_ref()
            .ok_or_else(|| missing("excitation"))?,
        Dimension::Voltage,
    )?;
    let gain = spec
        .gain
        .as_ref()
        .map_or(Ok(1.0), |g| positive("gain", g))?;
    let arms = spec
        .active_arms
        .as_ref()
        .ok_or_else(|| missing("active_arms"))?;
    if ![1, 2, 4].contains(arms.get_ref()) {
        return Err(sidecar.invalid(
            &format!("{key}.active_arms"),
            arms.span(),
            "expected 1, 2 or 4",
        ));
    }
    let volts = sidecar.column(table, key, &column, Dimension::Voltage)?;
    let per_volt = 4.0 / (f64::from(*arms.get_ref()) * gauge_factor * excitation * gain);
    Ok(volts.into_iter().map(|u| u * per_volt).collect())
}
