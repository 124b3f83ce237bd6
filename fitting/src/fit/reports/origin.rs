//! Where a fit's parameters come from, read back from its `report.toml`: the material it
//! was fitted with, the strain rates, temperatures and strains its experiments covered,
//! the parameter pairs the data did not identify, the parameters stopped at a bound, whether
//! the fit was interrupted and what the models' runs warned about (molten points).
//! A solver card carries these as comment lines (`caveats`): outside the covered ranges
//! the parameters are an extrapolation.

use anyhow::{bail, Context, Result};
use serde::Deserialize;
use std::path::{Path, PathBuf};

#[derive(Deserialize)]
struct ReportFile {
    set: String,
    material_name: Option<String>,
    material_file: Option<String>,
    #[serde(default)]
    stages: Vec<StageRow>,
    #[serde(default)]
    experiments: Vec<ExperimentRow>,
    #[serde(default)]
    interrupted: bool,
}

#[derive(Deserialize)]
struct StageRow {
    free: Vec<String>,
    #[serde(default)]
    not_identified: Vec<String>,
    #[serde(default)]
    at_bounds: Vec<String>,
}

#[derive(Deserialize)]
struct ExperimentRow {
    name: String,
    #[serde(default)]
    warnings: Vec<String>,
    rate_per_s: f64,
    temperature_k: f64,
    strain_range: Option<[f64; 2]>,
}

/// What a fit report says about the origin of its parameters.
#[derive(Debug, Clone)]
pub struct FitOrigin {
    pub report: PathBuf,
    pub set: String,
    pub material_name: String,
    pub material_file: PathBuf,
    /// Parameters some stage fitted (the others were the material file's).
    pub fitted: Vec<String>,
    pub experiments: usize,
    /// [smallest, largest] over the experiments: strain rate [1/s], temperature [K],
    /// specimen strain [-] (`None` when no experiment states it).
    pub rates_per_s: [f64; 2],
    pub temperatures_k: [f64; 2],
    pub strains: Option<[f64; 2]>,
    pub not_identified: Vec<String>,
    pub at_bounds: Vec<String>,
    /// The fit was stopped before it ended (a partial report).
    pub interrupted: bool,
    /// What the models' runs warned about at the fitted parameters, as `experiment: warning`.
    pub model_warnings: Vec<String>,
}

fn span(values: impl Iterator<Item = f64>) -> Option<[f64; 2]> {
    values.fold(None, |acc, v| match acc {
        None => Some([v, v]),
        Some([lo, hi]) => Some([lo.min(v), hi.max(v)]),
    })
}

impl FitOrigin {
    pub fn read(report: &Path) -> Result<FitOrigin> {
        let text = std::fs::read_to_string(report)
            .with_context(|| format!("{}: cannot read the fit report", report.display()))?;
        let r: ReportFile = toml::from_str(&text)
            .map_err(|e| anyhow::anyhow!("{}: not a fit report: {e}", report.display()))?;
        let (Some(material_name), Some(material_file)) = (r.material_name, r.material_file) else {
            bail!(
                "{}: the report does not name its material (written by an older mpw): name the material file too",
                report.display()
            );
        };
        let (Some(rates), Some(temperatures)) = (
            span(r.experiments.iter().map(|e| e.rate_per_s)),
            span(r.experiments.iter().map(|e| e.temperature_k)),
        ) else {
            bail!("{}: the report lists no experiments", report.display());
        };
        let mut fitted: Vec<String> = r.stages.iter().flat_map(|s| s.free.clone()).collect();
        fitted.sort();
        fitted.dedup();
        Ok(FitOrigin {
            report: report.to_path_buf(),
            set: r.set,
            material_name,
            material_file: PathBuf::from(material_file),
            fitted,
            experiments: r.experiments.len(),
            rates_per_s: rates,
            temperatures_k: temperatures,
            strains: span(
                r.experiments
                    .iter()
                    .filter_map(|e| e.strain_range)
                    .flatten(),
            ),
            not_identified: r
                .stages
                .iter()
                .flat_map(|s| s.not_identified.clone())
                .collect(),
            at_bounds: r.stages.iter().flat_map(|s| s.at_bounds.clone()).collect(),
            interrupted: r.interrupted,
            model_warnings: r
                .experiments
                .iter()
                .flat_map(|e| e.warnings.iter().map(|w| format!("{}: {w}", e.name)))
                .collect(),
        })
    }

    /// The ranges the fit covered, as one sentence.
    pub fn coverage(&self) -> String {
        let range = |[lo, hi]: [f64; 2], unit: &str| match lo == hi {
            true => format!("{} {unit}", short(lo)),
            false => format!("{} to {} {unit}", short(lo), short(hi)),
        };
        let strains = self
            .strains
            .map(|s| format!(", strains {}", range(s, "")).trim_end().to_string())
            .unwrap_or_default();
        format!(
            "fitted ({}) to {} experiment(s) of \"{}\": strain rates {}, temperatures {}{strains}; outside these ranges the parameters are an extrapolation",
            self.fitted.join(", "),
            self.experiments,
            self.set,
            range(self.rates_per_s, "1/s"),
            range(self.temperatures_k, "K"),
        )
    }

    /// What a user of the parameters must know: the coverage, then whether the fit was
    /// interrupted, every pair the data do not identify and every parameter that ended on a
    /// bound.
    pub fn caveats(&self) -> Vec<String> {
        let mut out = vec![self.coverage()];
        if self.interrupted {
            out.push("WARNING: the fit was interrupted: these are its best values so far, not an optimum, and later stages did not run".into());
        }
        out.extend(self.not_identified.iter().map(|p| format!("WARNING: {p}")));
        out.extend(
            self.at_bounds
                .iter()
                .map(|b| format!("WARNING: the fit stopped with {b}, not at an optimum")),
        );
        out.extend(self.model_warnings.iter().map(|w| format!("WARNING: {w}")));
        out
    }

    /// Whether the caveats hold more than the coverage.
    pub fn has_warnings(&self) -> bool {
        self.interrupted
            || !self.not_identified.is_empty()
            || !self.at_bounds.is_empty()
            || !self.model_warnings.is_empty()
    }
}

/// A value with four significant digits, without trailing zeros (`1e-4`, `1800`, `0.01`).
fn short(x: f64) -> String {
    let s = format!("{x:.3e}");
    let v: f64 = s.parse().unwrap_or(x);
    if (1e-3..1e5).contains(&v.abs()) {
        format!("{v}")
    } else {
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        format!("{m}e{e}")
    }
}

#[cfg(test)]
mod tests {
    use super::short;

    #[test]
    fn short_numbers_read_as_written() {
        assert_eq!(short(1e-4), "1e-4");
        assert_eq!(short(1800.0), "1800");
        assert_eq!(short(297.04), "297");
        assert_eq!(short(0.0123456), "0.01235");
        assert_eq!(short(2.5e6), "2.5e6");
    }
}
