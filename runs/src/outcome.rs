//! What a run returns: its named results (name, value, unit), in the order the run gave
//! them, named series of values (a predicted curve), the failure that stopped its simulation if one did (a physical result of the
//! run, not an error of the task: a stability map counts them), and its warnings.
//!
//! Values are written as TOML floats in Rust's shortest round-trip form (NaN and ±inf
//! included), so that an outcome read back holds the computed values bit for bit.

use anyhow::Result;
use serde::{Deserialize, Serialize};
use std::path::Path;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutcomeValue {
    pub name: String,
    pub value: f64,
    pub unit: String,
}

/// A named series of values, e.g. a model's prediction at an experiment's samples.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutcomeSeries {
    pub name: String,
    pub unit: String,
    pub values: Vec<f64>,
}

#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Outcome {
    /// The simulation's failure (step, time, cause), if it stopped before its end.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
    #[serde(default)]
    pub warnings: Vec<String>,
    #[serde(default)]
    pub values: Vec<OutcomeValue>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub series: Vec<OutcomeSeries>,
}

impl Outcome {
    pub fn push(&mut self, name: &str, value: f64, unit: &str) {
        self.values.push(OutcomeValue {
            name: name.to_string(),
            value,
            unit: unit.to_string(),
        });
    }

    /// The value named `name`.
    pub fn value(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|v| v.name == name).map(|v| v.value)
    }

    /// The series named `name`.
    pub fn series(&self, name: &str) -> Option<&[f64]> {
        self.series
            .iter()
            .find(|s| s.name == name)
            .map(|s| &s.values[..])
    }

    /// Keep only the values named in `returns` (all when it is empty), in its order; a name
    /// the run does not give is an error that lists those it gives.
    pub fn keep(self, returns: &[String]) -> Result<Self> {
        if returns.is_empty() {
            return Ok(self);
        }
        let values = returns
            .iter()
            .map(|name| {
                self.values
                    .iter()
                    .find(|v| &v.name == name)
                    .cloned()
                    .ok_or_else(|| {
                        let given: Vec<&str> =
                            self.values.iter().map(|v| v.name.as_str()).collect();
                        anyhow::anyhow!(
                            "the run gives no result `{name}`; it gives {}",
                            given.join(", ")
                        )
                    })
            })
            .collect::<Result<_>>()?;
        Ok(Outcome { values, ..self })
    }

    pub fn write(&self, path: &Path) -> Result<()> {
        crate::atomic::write_toml(path, self)
    }

    pub fn read(path: &Path) -> Result<Self> {
        crate::atomic::read_toml(path, "the outcome")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_read_back_bit_for_bit_with_nan_and_infinity() {
        let mut o = Outcome::default();
        let values = [
            0.1 + 0.2,
            1.0 / 3.0,
            6.02214076e23,
            -5e-324,
            f64::INFINITY,
            f64::NAN,
        ];
        for (i, v) in values.iter().enumerate() {
            o.push(&format!("v{i}"), *v, "m");
        }
        o.failure = Some("step 3: inverted J".into());
        o.series.push(OutcomeSeries {
            name: "prediction".into(),
            unit: "N".into(),
            values: values.to_vec(),
        });
        let path = std::env::temp_dir().join(format!("runs-outcome-{}.toml", std::process::id()));
        o.write(&path).unwrap();
        let back = Outcome::read(&path).unwrap();
        for (a, b) in o.values.iter().zip(&back.values) {
            assert_eq!(a.value.to_bits(), b.value.to_bits(), "{}", a.name);
        }
        assert_eq!(back.failure, o.failure);
        let series = back.series("prediction").unwrap();
        for (a, b) in values.iter().zip(series) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
        std::fs::remove_file(&path).unwrap();
    }

    #[test]
    fn kept_values_follow_the_returns_and_a_missing_one_is_named() {
        let mut o = Outcome::default();
        o.push("a", 1.0, "m");
        o.push("b", 2.0, "s");
        let kept = o.clone().keep(&["b".into()]).unwrap();
        assert_eq!(kept.values.len(), 1);
        assert_eq!(kept.value("b"), Some(2.0));
        let e = o.keep(&["c".into()]).unwrap_err().to_string();
        assert_eq!(e, "the run gives no result `c`; it gives a, b");
    }
}
