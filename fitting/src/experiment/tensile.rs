//! Tensile experiments: a CSV of time and engineering strain (or extension over a gauge
//! length) and engineering stress (or force over the initial cross-section), plus a TOML
//! that states units, temperature, nominal rate, geometry and the valid window.
//!
//! ```toml
//! kind = "tensile"
//! name = "304L 1e-2/s ring 1-17"        # optional, default: the TOML's file stem
//! data = "path/relative/to/this.csv"  # or a folder, or a pattern: "304L/rate_0.01__*.csv"
//! temperature = "297.04 K"             # optional if the CSV header states it
//! nominal_strain_rate = "0.01 1/s"     # optional if the CSV header states it
//! [columns]
//! time = { name = "time_s", unit = "s" }
//! strain = { name = "engineering_strain", unit = "1" }     # or extension = {..., unit = "mm"}
//! stress = { name = "engineering_stress_pa", unit = "Pa" } # or force = {..., unit = "kN"}
//! [geometry]                 # needed for force (area or diameter) and extension (gauge_length)
//! diameter = "6 mm"          # or area = "28.27 mm^2"
//! gauge_length = "25 mm"
//! [window]                   # all optional
//! time_min = "0 s"
//! time_max = "100 s"
//! strain_min = 0.0
//! strain_max = 0.3
//! up_to_max_stress = true    # default: cut at the maximum engineering stress (necking)
//! ```
//! Engineering strain ε = ΔL/L0 [-], engineering stress σ = F/A0 [Pa]. All samples are
//! kept; `used_range()` says which of them a homogeneous model should be compared with.
//!
//! A `data` folder or pattern (`pattern`) makes one experiment per matching CSV, named
//! `<name>/<csv stem>`, all with the TOML's columns, geometry and window. Temperature and
//! nominal rate come from the TOML where it states them, otherwise from each CSV's `#`
//! header (`header::TEMPERATURE_KEYS`, `header::STRAIN_RATE_KEYS`); each experiment says
//! which it read.

use super::error::ExperimentError;
use super::header::{self, Source};
use super::pattern;
use super::sidecar::{ColumnSpec, Sidecar};
use super::table::CsvTable;
use super::units::Dimension;
use serde::Deserialize;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TensileFile {
    /// Checked by `Sidecar::parse_kind` before this type is parsed.
    #[allow(dead_code)]
    kind: Spanned<String>,
    name: Option<String>,
    data: Spanned<String>,
    temperature: Option<Spanned<String>>,
    nominal_strain_rate: Option<Spanned<String>>,
    columns: TensileColumns,
    geometry: Option<GeometrySpec>,
    window: Option<WindowSpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TensileColumns {
    time: ColumnSpec,
    strain: Option<ColumnSpec>,
    extension: Option<ColumnSpec>,
    stress: Option<ColumnSpec>,
    force: Option<ColumnSpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GeometrySpec {
    area: Option<Spanned<String>>,
    diameter: Option<Spanned<String>>,
    gauge_length: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WindowSpec {
    time_min: Option<Spanned<String>>,
    time_max: Option<Spanned<String>>,
    strain_min: Option<Spanned<f64>>,
    strain_max: Option<Spanned<f64>>,
    up_to_max_stress: Option<bool>,
}

/// A tensile test in SI units, with its full measured history.
#[derive(Debug, Clone)]
pub struct TensileExperiment {
    pub name: String,
    /// The CSV the samples were read from.
    pub data_file: PathBuf,
    /// Time [s] of each sample, strictly increasing.
    pub time_s: Vec<f64>,
    /// Engineering strain ΔL/L0 [-].
    pub eng_strain: Vec<f64>,
    /// Engineering stress F/A0 [Pa].
    pub eng_stress_pa: Vec<f64>,
    /// Test temperature [K].
    pub temperature_k: f64,
    /// Nominal engineering strain rate [1/s]; models should follow `time_s`/`eng_strain`.
    pub nominal_strain_rate_per_s: f64,
    /// Where the temperature and the nominal rate were read.
    pub temperature_source: Source,
    pub rate_source: Source,
    /// Initial cross-section [m²], if the TOML states it.
    pub area_m2: Option<f64>,
    /// Gauge length [m], if the TOML states it.
    pub gauge_length_m: Option<f64>,
    used: Range<usize>,
}

impl TensileExperiment {
    /// Read a tensile experiment TOML and the one CSV it names.
    pub fn load(toml_file: &Path) -> Result<TensileExperiment, ExperimentError> {
        let mut all = Self::load_all(toml_file)?;
        if all.len() != 1 {
            let sidecar = Sidecar::read(toml_file)?;
            let spec: TensileFile = sidecar.parse()?;
            return Err(sidecar.invalid(
                "data",
                spec.data.span(),
                format!("names {} records where one is expected", all.len()),
            ));
        }
        Ok(all.remove(0))
    }

    /// Read a tensile experiment TOML and every CSV it names (one, or the records of a
    /// folder or pattern, sorted by name).
    pub fn load_all(toml_file: &Path) -> Result<Vec<TensileExperiment>, ExperimentError> {
        let sidecar = Sidecar::read(toml_file)?;
        let spec: TensileFile = sidecar.parse_kind("tensile")?;
        let geometry = Geometry::read(&sidecar, spec.geometry.as_ref())?;
        let data = sidecar.data_path(&spec.data)?;
        let name = spec.name.clone().unwrap_or_else(|| {
            toml_file
                .file_stem()
                .map_or_else(|| "tensile".into(), |s| s.to_string_lossy().into_owned())
        });
        if !pattern::is_many(&data) {
            return Ok(vec![read_record(&sidecar, &spec, &geometry, data, name)?]);
        }
        let files = pattern::expand(&data).map_err(|reason| ExperimentError::Io {
            file: data.clone(),
            reason,
        })?;
        if files.is_empty() {
            return Err(sidecar.invalid(
                "data",
                spec.data.span(),
                format!("no file matches \"{}\"", data.display()),
            ));
        }
        files
            .into_iter()
            .map(|file| {
                let stem = file.file_stem().unwrap_or_default().to_string_lossy();
                let record = format!("{name}/{stem}");
                read_record(&sidecar, &spec, &geometry, file.clone(), record)
            })
            .collect()
    }

    /// Indices of the samples inside the valid window (by default from the first sample
    /// up to and including the maximum engineering stress).
    pub fn used_range(&self) -> Range<usize> {
        self.used.clone()
    }
}

/// Cross-section and gauge length as the TOML states them.
struct Geometry {
    area_m2: Option<f64>,
    gauge_length_m: Option<f64>,
}

impl Geometry {
    fn read(sidecar: &Sidecar, g: Option<&GeometrySpec>) -> Result<Geometry, ExperimentError> {
        let length = |key: &str, v: &Option<Spanned<String>>| {
            v.as_ref()
                .map(|v| sidecar.positive(&format!("geometry.{key}"), v, Dimension::Length))
                .transpose()
        };
        let gauge_length_m = g.map_or(Ok(None), |g| length("gauge_length", &g.gauge_length))?;
        let area_m2 = match g {
            Some(GeometrySpec {
                area: Some(_),
                diameter: Some(d),
                ..
            }) => {
                return Err(sidecar.invalid(
                    "geometry.diameter",
                    d.span(),
                    "give the cross-section as `area` or as `diameter`, not both",
                ))
            }
            Some(GeometrySpec { area: Some(a), .. }) => {
                Some(sidecar.positive("geometry.area", a, Dimension::Area)?)
            }
            Some(GeometrySpec { diameter: d, .. }) => {
                length("diameter", d)?.map(|d| std::f64::consts::PI * d * d / 4.0)
            }
            None => None,
        };
        Ok(Geometry {
            area_m2,
            gauge_length_m,
        })
    }
}

/// One record: the CSV `data_file` read with the TOML's columns, geometry and window.
fn read_record(
    sidecar: &Sidecar,
    spec: &TensileFile,
    geometry: &Geometry,
    data_file: PathBuf,
    name: String,
) -> Result<TensileExperiment, ExperimentError> {
    let table = CsvTable::read_rows(&data_file, 2)?;
    let (temperature_k, temperature_source) = sidecar.metadata(
        &table,
        ("temperature", spec.temperature.as_ref()),
        header::TEMPERATURE_KEYS,
        Dimension::Temperature,
    )?;
    let (nominal_strain_rate_per_s, rate_source) = sidecar.metadata(
        &table,
        ("nominal_strain_rate", spec.nominal_strain_rate.as_ref()),
        header::STRAIN_RATE_KEYS,
        Dimension::StrainRate,
    )?;
    let cols = &spec.columns;
    let time_s = sidecar.column(&table, "columns.time", &cols.time, Dimension::Time)?;
    sidecar.check_time_increases(&table, &cols.time, &time_s)?;
    let eng_strain = strain_column(sidecar, &table, spec, geometry)?;
    let eng_stress_pa = stress_column(sidecar, &table, spec, geometry)?;
    let used = match &spec.window {
        Some(w) => used_range(sidecar, w, &time_s, &eng_strain, &eng_stress_pa)?,
        None => up_to_max(&eng_stress_pa, 0..time_s.len()),
    };
    Ok(TensileExperiment {
        name,
        data_file,
        time_s,
        eng_strain,
        eng_stress_pa,
        temperature_k,
        nominal_strain_rate_per_s,
        temperature_source,
        rate_source,
        area_m2: geometry.area_m2,
        gauge_length_m: geometry.gauge_length_m,
        used,
    })
}

/// A quantity given either as its own column (`direct`) or as a raw column over a
/// geometric divisor (`raw`): strain or extension / gauge length, stress or force / area.
struct Either<'a> {
    direct: (&'static str, &'a Option<ColumnSpec>, Dimension),
    /// Key, column, dimension and SI unit of the raw column.
    raw: (
        &'static str,
        &'a Option<ColumnSpec>,
        Dimension,
        &'static str,
    ),
    /// The divisor [SI], or what is missing for it.
    divisor: Result<f64, &'static str>,
    /// How a derived value was formed and the likely mistake, from (divisor, limit).
    how: fn(f64, f64) -> String,
}

/// The values of `q` [SI]: the direct column, or the raw column over the divisor, each
/// derived value checked against the direct dimension's plausible magnitude.
fn direct_or_derived(
    sidecar: &Sidecar,
    table: &CsvTable,
    q: Either,
) -> Result<Vec<f64>, ExperimentError> {
    let (key, direct, dimension) = q.direct;
    let (raw_key, raw, raw_dimension, raw_unit) = q.raw;
    match (direct, raw) {
        (Some(c), None) => sidecar.column(table, &format!("columns.{key}"), c, dimension),
        (None, Some(c)) => {
            let divisor = q.divisor.map_err(|problem| {
                sidecar.invalid(&format!("columns.{raw_key}"), c.name.span(), problem)
            })?;
            let values = sidecar.column(table, &format!("columns.{raw_key}"), c, raw_dimension)?;
            let derived: Vec<f64> = values.iter().map(|v| v / divisor).collect();
            let (limit, _) = dimension.plausible_magnitude();
            let how = (q.how)(divisor, limit);
            sidecar.check_plausible(table, c, (&values, raw_unit), &derived, limit, &how)?;
            Ok(derived)
        }
        _ => Err(sidecar.invalid(
            "columns",
            sidecar.table_span("columns"),
            format!("expected exactly one of `{key}` and `{raw_key}`"),
        )),
    }
}

/// Engineering strain [-]: the strain column, or the extension over the gauge length.
fn strain_column(
    sidecar: &Sidecar,
    table: &CsvTable,
    spec: &TensileFile,
    geometry: &Geometry,
) -> Result<Vec<f64>, ExperimentError> {
    let cols = &spec.columns;
    let q = Either {
        direct: ("strain", &cols.strain, Dimension::Strain),
        raw: ("extension", &cols.extension, Dimension::Length, "m"),
        divisor: geometry
            .gauge_length_m
            .ok_or("an extension column needs `geometry.gauge_length`"),
        how: |l0, limit| {
            format!("over the gauge length {l0:e} m as a strain, beyond {limit}: is the extension's unit or the gauge length wrong?")
        },
    };
    direct_or_derived(sidecar, table, q)
}

/// Engineering stress [Pa]: the stress column, or the force over the cross-section.
fn stress_column(
    sidecar: &Sidecar,
    table: &CsvTable,
    spec: &TensileFile,
    geometry: &Geometry,
) -> Result<Vec<f64>, ExperimentError> {
    let cols = &spec.columns;
    let q = Either {
        direct: ("stress", &cols.stress, Dimension::Stress),
        raw: ("force", &cols.force, Dimension::Force, "N"),
        divisor: geometry
            .area_m2
            .ok_or("`geometry.area` or `geometry.diameter`"),
        how: |a0, limit| {
            format!("Pa over the area A0 = {a0:e} m² as a stress, beyond {limit:e} Pa: is the force's unit or the cross-section wrong?")
        },
    };
    direct_or_derived(sidecar, table, q)
}

/// Shorten `range` to end at (and include) its maximum of engineering stress.
fn up_to_max(stress: &[f64], range: Range<usize>) -> Range<usize> {
    let start = range.start;
    let peak = range.fold(
        start,
        |best, i| if stress[i] > stress[best] { i } else { best },
    );
    start..peak + 1
}

fn used_range(
    sidecar: &Sidecar,
    window: &WindowSpec,
    time: &[f64],
    strain: &[f64],
    stress: &[f64],
) -> Result<Range<usize>, ExperimentError> {
    let w = window;
    let span = |v: &[f64]| {
        v.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            })
    };
    let inside = |key: &str, at: Range<usize>, value: f64, data: &[f64]| {
        let (lo, hi) = span(data);
        if value < lo || value > hi {
            Err(ExperimentError::WindowOutsideData {
                at: sidecar.at(at),
                key: format!("window.{key}"),
                value,
                data_min: lo,
                data_max: hi,
            })
        } else {
            Ok(value)
        }
    };
    let time_bound =
        |key: &str, v: &Option<Spanned<String>>| -> Result<Option<f64>, ExperimentError> {
            match v {
                Some(v) => {
                    let t = sidecar.quantity(&format!("window.{key}"), v, Dimension::Time)?;
                    Ok(Some(inside(key, v.span(), t, time)?))
                }
                None => Ok(None),
            }
        };
    let strain_bound =
        |key: &str, v: &Option<Spanned<f64>>| -> Result<Option<f64>, ExperimentError> {
            v.as_ref()
                .map(|v| inside(key, v.span(), *v.get_ref(), strain))
                .transpose()
        };
    let t_min = time_bound("time_min", &w.time_min)?.unwrap_or(f64::NEG_INFINITY);
    let t_max = time_bound("time_max", &w.time_max)?.unwrap_or(f64::INFINITY);
    let e_min = strain_bound("strain_min", &w.strain_min)?.unwrap_or(f64::NEG_INFINITY);
    let e_max = strain_bound("strain_max", &w.strain_max)?.unwrap_or(f64::INFINITY);

    let n = time.len();
    let start = (0..n)
        .find(|&i| time[i] >= t_min && strain[i] >= e_min)
        .unwrap_or(n);
    let end = (start..n)
        .find(|&i| time[i] > t_max || strain[i] > e_max)
        .unwrap_or(n);
    let range = if w.up_to_max_stress.unwrap_or(true) && start < end {
        up_to_max(stress, start..end)
    } else {
        start..end
    };
    if range.len() < 2 {
        return Err(sidecar.invalid(
            "window",
            sidecar.table_span("window"),
            format!(
                "the window holds {} samples, at least 2 needed",
                range.len()
            ),
        ));
    }
    Ok(range)
}
