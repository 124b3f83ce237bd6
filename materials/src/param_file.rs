//! Material parameter files (TOML) with validation of every field.
//!
//! ```toml
//! name = "AISI 4340"
//! model = "johnson-cook"          # "neo-hooke" | "j2" | "johnson-cook" | "composed"
//! return_map = "principal"        # optional: "principal" (default) | "reference"
//! [elastic]      # E [Pa], nu [-], rho [kg/m³]
//! [johnson_cook] # A, B [Pa], N, C, M [-], alpha_dot0 [1/s], theta_m [K]
//! [voce]         # (j2) tau0, tau_inf, h [Pa], eta [-]
//! [thermal]      # (johnson-cook, composed) theta0 [K], c_theta [J/(kg K)], alpha_sigma [1/K],
//!                #   gamma_tq [-]
//! ```
//! A composed flow-stress law (`flow_stress::composed`) names each factor's law in its
//! section, beside that law's parameters:
//! ```toml
//! model = "composed"
//! [hardening]    # law = "power" (A, B, N) | "voce" (tau0, tau_inf, eta, h)
//!                #   | "power-voce" (A, B, N, Q [Pa], beta [-])
//! [rate]         # law = "none" | "johnson-cook" (C, alpha_dot0) | "huh-kang" (C, C2,
//!                #   alpha_dot0) | "cowper-symonds" (D_cs [1/s], p_cs [-])
//! [softening]    # law = "none" | "johnson-cook" (M, theta_m) | "exponential"
//!                #   (lambda_theta [1/K], theta_m [K])
//! ```
//! An unknown or missing key, a value out of range, or a wrong type is an error in the
//! common format of input files (`toml_place`): `file:line:column: `field`: problem`, at the
//! key (or at its section when the key is missing), with the allowed range.

use crate::any_model::AnyModel;
use crate::elastic::Elastic;
use crate::flow_stress::{
    hardening, rate, softening, Composed, FlowStress, Hardening, JohnsonCookLaw, RateSensitivity,
    ThermalSoftening, Voce,
};
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
        let values = self.values(table, section, &spec)?;
        Ok(values.try_into().expect("one value per key"))
    }

    /// `numbers` for a list of keys.
    fn values(
        &self,
        table: &Table,
        section: &str,
        spec: &[(&str, Range)],
    ) -> Result<Vec<f64>, ParamFileError> {
        for key in table.keys() {
            if !spec.iter().any(|(k, _)| k == key) {
                let allowed: Vec<&str> = spec.iter().map(|(k, _)| *k).collect();
                return Err(self.err(
                    format!("{section}.{key}"),
                    format!("unknown key; allowed: {}", allowed.join(", ")),
                ));
            }
        }
        let mut out = vec![0.0; spec.len()];
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

    /// What a file may give `name`; θm must besides lie above the file's θ0.
    fn accepted_above(name: &str, theta0: f64) -> Range {
        if name == "theta_m" {
            Range {
                lo: theta0,
                lo_open: true,
                hint: "the melting temperature in K, above theta0",
                ..accepted(name)
            }
        } else {
            accepted(name)
        }
    }

    /// The `[johnson_cook]` section: eq. 4.52.
    fn johnson_cook(&self, root: &Table, theta0: f64) -> Result<FlowStress, ParamFileError> {
        let [a, b, n, c, m, alpha_dot0, theta_m] = self.numbers(
            self.section(root, "johnson_cook")?,
            "johnson_cook",
            ["A", "B", "N", "C", "M", "alpha_dot0", "theta_m"]
                .map(|n| (n, Self::accepted_above(n, theta0))),
        )?;
        Ok(FlowStress::JohnsonCook(JohnsonCookLaw {
            a,
            b,
            n,
            c,
            m,
            alpha_dot0,
            theta_m,
        }))
    }

    /// The `[hardening]`, `[rate]` and `[softening]` sections of a composed law.
    fn composed(&self, root: &Table, theta0: f64) -> Result<Composed, ParamFileError> {
        let (law, values) = self.factor(
            root,
            "hardening",
            &hardening::KEYWORDS,
            theta0,
            Hardening::names_of,
        )?;
        let hardening = Hardening::from_keyword(law, values).expect("a known law");
        let (law, values) = self.factor(
            root,
            "rate",
            &rate::KEYWORDS,
            theta0,
            RateSensitivity::names_of,
        )?;
        let rate = RateSensitivity::from_keyword(law, values).expect("a known law");
        let (law, values) = self.factor(
            root,
            "softening",
            &softening::KEYWORDS,
            theta0,
            ThermalSoftening::names_of,
        )?;
        let softening = ThermalSoftening::from_keyword(law, values).expect("a known law");
        Ok(Composed {
            hardening,
            rate,
            softening,
        })
    }

    /// One factor's section: its `law` (one of `keywords`) and that law's parameters, each
    /// in its accepted range.
    fn factor<'t>(
        &self,
        root: &'t Table,
        section: &str,
        keywords: &[&str],
        theta0: f64,
        names_of: impl Fn(&str) -> Option<&'static [&'static str]>,
    ) -> Result<(&'t str, impl Fn(&str) -> f64), ParamFileError> {
        let table = self.section(root, section)?;
        let field = format!("{section}.law");
        let expected = format!("expected one of \"{}\"", keywords.join("\", \""));
        let law = match table.get("law") {
            Some(Value::String(law)) => law.as_str(),
            Some(_) => return Err(self.err(field, format!("{expected} (a string)"))),
            None => return Err(self.err(field, format!("missing; {expected}"))),
        };
        let names = names_of(law)
            .ok_or_else(|| self.err(&field, format!("unknown law \"{law}\"; {expected}")))?;
        let mut parameters = table.clone();
        parameters.remove("law");
        let spec: Vec<(&str, Range)> = (names.iter())
            .map(|&n| (n, Self::accepted_above(n, theta0)))
            .collect();
        let values = self.values(&parameters, section, &spec)?;
        Ok((law, move |name: &str| {
            values[names
                .iter()
                .position(|n| *n == name)
                .expect("a name of the law")]
        }))
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
            "missing; expected \"neo-hooke\", \"j2\", \"johnson-cook\" or \"composed\"",
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
        "composed" => &[
            "name",
            "model",
            "return_map",
            "elastic",
            "hardening",
            "rate",
            "softening",
            "thermal",
        ],
        other => {
            return Err(r.err(
                "model",
                format!(
                    "unknown model \"{other}\"; expected \"neo-hooke\", \"j2\", \"johnson-cook\" or \"composed\""
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
    let metal = matches!(model_kind, "johnson-cook" | "composed");
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
            let flow = if model_kind == "composed" {
                FlowStress::Composed(r.composed(&root, theta0)?)
            } else {
                r.johnson_cook(&root, theta0)?
            };
            AnyModel::ElastoPlastic(ElastoPlastic {
                elastic,
                flow,
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
