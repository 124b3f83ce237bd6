//! Tensile experiments: a CSV of time and engineering strain (or extension over a gauge
//! length) and engineering stress (or force over the initial cross-section), plus a TOML
//! that states units, temperature, nominal rate, geometry and the valid window.
//!
//! ```toml
//! kind = "tensile"
//! name = "304L 1e-2/s ring 1-17"        # optional, default: the TOML's file stem
//! data = "path/relative/to/this.csv"
//! temperature = "297.04 K"
//! nominal_strain_rate = "0.01 1/s"
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

use super::error::ExperimentError;
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
    kind: Spanned<String>,
    name: Option<String>,
    data: Spanned<String>,
    temperature: Spanned<String>,
    nominal_strain_rate: Spanned<String>,
    columns: Spanned<TensileColumns>,
    geometry: Option<GeometrySpec>,
    window: Option<Spanned<WindowSpec>>,
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
    /// Initial cross-section [m²], if the TOML states it.
    pub area_m2: Option<f64>,
    /// Gauge length [m], if the TOML states it.
    pub gauge_length_m: Option<f64>,
    used: Range<usize>,
}

impl TensileExperiment {
    /// Read a tensile experiment TOML and the CSV it names.
    pub fn load(toml_file: &Path) -> Result<TensileExperiment, ExperimentError> {
        let sidecar = Sidecar::read(toml_file)?;
        let spec: TensileFile = sidecar.parse()?;
        sidecar.expect_kind(&spec.kind, "tensile")?;
        let temperature_k =
            sidecar.positive("temperature", &spec.temperature, Dimension::Temperature)?;
        let nominal_strain_rate_per_s = sidecar.positive(
            "nominal_strain_rate",
            &spec.nominal_strain_rate,
            Dimension::StrainRate,
        )?;
        let g = spec.geometry.as_ref();
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

        let data_file = sidecar.relative_path(spec.data.get_ref());
        let table = CsvTable::read(&data_file)?;
        if table.len() < 2 {
            return Err(ExperimentError::TooFewRows {
                file: data_file,
                found: table.len(),
                needed: 2,
            });
        }
        let cols = spec.columns.get_ref();
        let columns_span = spec.columns.span();
        let time_s = sidecar.column(&table, "columns.time", &cols.time, Dimension::Time)?;
        sidecar.check_time_increases(&table, &cols.time, &time_s)?;
        let eng_strain = match (&cols.strain, &cols.extension) {
            (Some(s), None) => sidecar.column(&table, "columns.strain", s, Dimension::Strain)?,
            (None, Some(x)) => {
                let l0 = gauge_length_m.ok_or_else(|| {
                    sidecar.invalid(
                        "columns.extension",
                        x.name.span(),
                        "an extension column needs `geometry.gauge_length`",
                    )
                })?;
                let extension =
                    sidecar.column(&table, "columns.extension", x, Dimension::Length)?;
                let strain: Vec<f64> = extension.iter().map(|u| u / l0).collect();
                let (limit, _) = Dimension::Strain.plausible_magnitude();
                let how = format!("over the gauge length {l0:e} m as a strain, beyond {limit}: is the extension's unit or the gauge length wrong?");
                let source = (&extension[..], "m");
                sidecar.check_plausible(&table, x, source, &strain, limit, &how)?;
                strain
            }
            _ => {
                return Err(sidecar.invalid(
                    "columns",
                    columns_span,
                    "expected exactly one of `strain` and `extension`",
                ))
            }
        };
        let eng_stress_pa = match (&cols.stress, &cols.force) {
            (Some(s), None) => sidecar.column(&table, "columns.stress", s, Dimension::Stress)?,
            (None, Some(f)) => {
                let a0 = area_m2.ok_or_else(|| {
                    sidecar.invalid(
                        "columns.force",
                        f.name.span(),
                        "a force column needs `geometry.area` or `geometry.diameter`",
                    )
                })?;
                let force = sidecar.column(&table, "columns.force", f, Dimension::Force)?;
                let stress: Vec<f64> = force.iter().map(|f| f / a0).collect();
                let (limit, _) = Dimension::Stress.plausible_magnitude();
                let how = format!("Pa over the area A0 = {a0:e} m² as a stress, beyond {limit:e} Pa: is the force's unit or the cross-section wrong?");
                let source = (&force[..], "N");
                sidecar.check_plausible(&table, f, source, &stress, limit, &how)?;
                stress
            }
            _ => {
                return Err(sidecar.invalid(
                    "columns",
                    columns_span,
                    "expected exactly one of `stress` and `force`",
                ))
            }
        };

        let used = match &spec.window {
            Some(w) => used_range(&sidecar, w, &time_s, &eng_strain, &eng_stress_pa)?,
            None => up_to_max(&eng_stress_pa, 0..time_s.len()),
        };
        let name = spec.name.unwrap_or_else(|| {
            toml_file
                .file_stem()
                .map_or_else(|| "tensile".into(), |s| s.to_string_lossy().into_owned())
        });
        Ok(TensileExperiment {
            name,
            data_file,
            time_s,
            eng_strain,
            eng_stress_pa,
            temperature_k,
            nominal_strain_rate_per_s,
            area_m2,
            gauge_length_m,
            used,
        })
    }

    /// Indices of the samples inside the valid window (by default from the first sample
    /// up to and including the maximum engineering stress).
    pub fn used_range(&self) -> Range<usize> {
        self.used.clone()
    }
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
    window: &Spanned<WindowSpec>,
    time: &[f64],
    strain: &[f64],
    stress: &[f64],
) -> Result<Range<usize>, ExperimentError> {
    let w = window.get_ref();
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
            window.span(),
            format!(
                "the window holds {} samples, at least 2 needed",
                range.len()
            ),
        ));
    }
    Ok(range)
}
