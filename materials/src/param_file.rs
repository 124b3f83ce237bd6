//! Material parameter files (TOML) with validation of every field.
//!
//! ```toml
//! name = "AISI 4340"
//! model = "johnson-cook"          # "neo-hooke" | "j2" | "johnson-cook"
//! return_map = "principal"        # optional: "principal" (default) | "reference"
//! [elastic]      # E [Pa], nu [-], rho [kg/m³]
//! [johnson_cook] # A, B [Pa], N, C, M [-], alpha_dot0 [1/s], theta_m [K]
//! [voce]         # (j2) tau0, tau_inf, h [Pa], eta [-]
//! [thermal]      # (johnson-cook) theta0 [K], c_theta [J/(kg K)], alpha_sigma [1/K], gamma_tq [-]
//! ```
//! An unknown or missing key, a value out of range, or a wrong type is an error in the
//! common format of input files (`toml_place`): `file:line:column: `field`: problem`, at the
//! key (or at its section when the key is missing), with the allowed range.

use crate::any_model::AnyModel;
use crate::elastic::Elastic;
use crate::flow_stress::{FlowStress, JohnsonCookLaw, Voce};
use crate::neo_hooke::NeoHooke;
use crate::parameters::{accepted, Range};
use crate::plasticity::{ElastoPlastic, ReturnMap, Thermal};
use crate::toml_place::{describe, Location};
use std::path::{Path, PathBuf};
use thiserror::Error;
use toml::{Table, Value};

#[derive(Debug, Error)]
pub enum ParamFileError {
    #[error("{file}: cannot read: {reason}")]
    Io {
        file: PathBuf,
        reason: std::io::Error,
    },
    /// TOML syntax or a value toml cannot read, as `toml_place::describe` words it.
    #[error("{0}")]
    Syntax(String),
    #[error("{}: `{field}`: {problem}", located(file, at))]
    Field {
        file: PathBuf,
        /// The key, or its section when the key is missing; `None` when neither is found.
        at: Option<Location>,
        field: String,
        problem: String,
    },
}

/// `file:line:column`, or `file` alone when the place is unknown.
fn located(file: &Path, at: &Option<Location>) -> String {
    match at {
        Some(at) => at.to_string(),
        None => file.display().to_string(),
    }
}

/// A loaded parameter file.
#[derive(Debug, Clone)]
pub struct MaterialFile {
    pub name: String,
    pub model: AnyModel<f64>,
}

struct Reader<'a> {
    file: &'a Path,
    text: &'a str,
    /// The same text with spans, to give each field its line.
    spans: toml_edit::ImDocument<&'a str>,
}

impl Reader<'_> {
    fn err(&self, field: impl Into<String>, problem: impl Into<String>) -> ParamFileError {
        let field = field.into();
        ParamFileError::Field {
            file: self.file.to_path_buf(),
            at: self
                .offset_of(&field)
                .map(|k| Location::in_text(self.file, self.text, k)),
            field,
            problem: problem.into(),
        }
    }

    /// Byte offset of a dotted field (`elastic.E`): of its key, else of the deepest table
    /// found.
    fn offset_of(&self, field: &str) -> Option<usize> {
        let mut table = self.spans.as_table();
        let mut span = None;
        for part in field.split('.') {
            if let Some(key) = table.key(part) {
                span = key.span().or(span);
            }
            match table.get(part).and_then(|item| item.as_table()) {
                Some(inner) => {
                    span = inner.span().or(span);
                    table = inner;
                }
                None => break,
            }
        }
        span.map(|s| s.start)
    }

    fn section<'t>(&self, root: &'t Table, name: &str) -> Result<&'t Table, ParamFileError> {
        match root.get(name) {
            Some(Value::Table(t)) => Ok(t),
            Some(_) => Err(self.err(name, "expected a table [section]")),
            None => Err(self.err(name, "missing section")),
        }
    }

    /// Read the named keys of a section with their ranges; reject unknown keys.
    fn numbers<const K: usize>(
        &self,
        table: &Table,
        section: &str,
        spec: [(&str, Range); K],
    ) -> Result<[f64; K], ParamFileError> {
        for key in table.keys() {
            if !spec.iter().any(|(k, _)| k == key) {
                let allowed: Vec<&str> = spec.iter().map(|(k, _)| *k).collect();
                return Err(self.err(
                    format!("{section}.{key}"),
                    format!("unknown key; allowed: {}", allowed.join(", ")),
                ));
            }
        }
        let mut out = [0.0; K];
        for (slot, (key, range)) in out.iter_mut().zip(spec.iter()) {
            let field = format!("{section}.{key}");
            let v = match table.get(*key) {
                Some(Value::Float(x)) => *x,
                Some(Value::Integer(i)) => *i as f64,
                Some(_) => return Err(self.err(field, "expected a number")),
                None => {
                    return Err(self.err(
                        field,
                        format!("missing; expected a number in {}", range.describe()),
                    ))
                }
            };
            if !range.contains(v) {
                let hint = if range.hint.is_empty() {
                    String::new()
                } else {
                    format!(": {}", range.hint)
                };
                return Err(self.err(
                    field,
                    format!(
                        "value {v} outside the allowed range {}{hint}",
                        range.describe()
                    ),
                ));
            }
            *slot = v;
        }
        Ok(out)
    }

    fn string<'t>(&self, root: &'t Table, key: &str) -> Result<Option<&'t str>, ParamFileError> {
        match root.get(key) {
            Some(Value::String(s)) => Ok(Some(s)),
            Some(_) => Err(self.err(key, "expected a string")),
            None => Ok(None),
        }
    }
}

/// Parse a parameter file from its text; `file` names it in errors.
pub fn parse_material(text: &str, file: &Path) -> Result<MaterialFile, ParamFileError> {
    let root: Table = text
        .parse()
        .map_err(|e: toml::de::Error| ParamFileError::Syntax(describe(file, text, &e)))?;
    let spans = toml_edit::ImDocument::parse(text)
        .map_err(|e| ParamFileError::Syntax(format!("{}: {e}", file.display())))?;
    let r = Reader { file, text, spans };
    let model_kind = r.string(&root, "model")?.ok_or_else(|| {
        r.err(
            "model",
            "missing; expected \"neo-hooke\", \"j2\" or \"johnson-cook\"",
        )
    })?;
    let allowed_top: &[&str] = match model_kind {
        "neo-hooke" => &["name", "model", "elastic"],
        "j2" => &["name", "model", "return_map", "elastic", "voce"],
        "johnson-cook" => &[
            "name",
            "model",
            "return_map",
            "elastic",
            "johnson_cook",
            "thermal",
        ],
        other => {
            return Err(r.err(
                "model",
                format!(
                    "unknown model \"{other}\"; expected \"neo-hooke\", \"j2\" or \"johnson-cook\""
                ),
            ))
        }
    };
    for key in root.keys() {
        if !allowed_top.contains(&key.as_str()) {
            return Err(r.err(
                key.as_str(),
                format!(
                    "unknown key for model \"{model_kind}\"; allowed: {}",
                    allowed_top.join(", ")
                ),
            ));
        }
    }
    let name = r.string(&root, "name")?.unwrap_or("unnamed").to_string();
    let metal = model_kind == "johnson-cook";
    let (e_range, rho_range) = if metal {
        (accepted("E"), accepted("rho"))
    } else {
        (Range::positive(), Range::positive())
    };
    let [e, nu, rho] = r.numbers(
        r.section(&root, "elastic")?,
        "elastic",
        [("E", e_range), ("nu", accepted("nu")), ("rho", rho_range)],
    )?;
    let elastic = Elastic { e, nu, rho };
    let return_map = match r.string(&root, "return_map")? {
        None | Some("principal") => ReturnMap::Principal,
        Some("reference") => ReturnMap::Reference,
        Some(other) => {
            return Err(r.err(
                "return_map",
                format!("unknown \"{other}\"; expected \"principal\" or \"reference\""),
            ))
        }
    };
    let model = match model_kind {
        "neo-hooke" => AnyModel::NeoHooke(NeoHooke {
            elastic,
            theta0: 293.15,
        }),
        "j2" => {
            let [tau0, tau_inf, eta, h] = r.numbers(
                r.section(&root, "voce")?,
                "voce",
                ["tau0", "tau_inf", "eta", "h"].map(|n| (n, accepted(n))),
            )?;
            AnyModel::ElastoPlastic(ElastoPlastic {
                elastic,
                flow: FlowStress::Voce(Voce {
                    tau0,
                    tau_inf,
                    eta,
                    h,
                }),
                thermal: Thermal {
                    theta0: 293.15,
                    c_theta: 1.0,
                    alpha_sigma: 0.0,
                    gamma_tq: 0.0,
                },
                return_map,
            })
        }
        _ => {
            let [theta0, c_theta, alpha_sigma, gamma_tq] = r.numbers(
                r.section(&root, "thermal")?,
                "thermal",
                ["theta0", "c_theta", "alpha_sigma", "gamma_tq"].map(|n| (n, accepted(n))),
            )?;
            let [a, b, n, c, m, alpha_dot0, theta_m] = r.numbers(
                r.section(&root, "johnson_cook")?,
                "johnson_cook",
                [
                    ("A", accepted("A")),
                    ("B", accepted("B")),
                    ("N", accepted("N")),
                    ("C", accepted("C")),
                    ("M", accepted("M")),
                    ("alpha_dot0", accepted("alpha_dot0")),
                    (
                        "theta_m",
                        Range {
                            lo: theta0,
                            lo_open: true,
                            hint: "the melting temperature in K, above theta0",
                            ..accepted("theta_m")
                        },
                    ),
                ],
            )?;
            AnyModel::ElastoPlastic(ElastoPlastic {
                elastic,
                flow: FlowStress::JohnsonCook(JohnsonCookLaw {
                    a,
                    b,
                    n,
                    c,
                    m,
                    alpha_dot0,
                    theta_m,
                }),
                thermal: Thermal {
                    theta0,
                    c_theta,
                    alpha_sigma,
                    gamma_tq,
                },
                return_map,
            })
        }
    };
    Ok(MaterialFile { name, model })
}

/// Load and validate a parameter file.
pub fn load_material(path: impl AsRef<Path>) -> Result<MaterialFile, ParamFileError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|reason| ParamFileError::Io {
        file: path.to_path_buf(),
        reason,
    })?;
    parse_material(&text, path)
}

/// Load a parameter file that must hold an elasto-plastic model (J2 or Johnson-Cook).
pub fn load_elasto_plastic(path: impl AsRef<Path>) -> Result<ElastoPlastic, ParamFileError> {
    let path = path.as_ref();
    match load_material(path)?.model {
        AnyModel::ElastoPlastic(m) => Ok(m),
        AnyModel::NeoHooke(_) => Err(ParamFileError::Field {
            file: path.to_path_buf(),
            at: None,
            field: "model".into(),
            problem: "expected \"j2\" or \"johnson-cook\" here, found a Neo-Hooke model".into(),
        }),
    }
}
