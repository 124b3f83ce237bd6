//! Experiment-set files (TOML): which experiments, at which model level, with which
//! weights and windows, which parameters are free (bounds, start) and which fixed, and the
//! stages of a staged fit.
//!
//! ```toml
//! name = "42CrMo4 QT660, synthetic"
//! material = "../materials/42crmo4_qt660.toml"   # base parameter set (fixed values)
//! optimizer = "lm"            # "lm" (each model's Jacobian: AD, or finite differences of
//!                             #   an MPM level) | "lm-fd" | "nelder-mead"
//! starts = 3                  # multi-start: the given start plus random starts
//! seed = 1                    # of the random starts
//! ftol = 1e-9                 # optional: LM stops when S falls by less than this fraction
//!                             #   (an MPM level's noise asks for ≈ 1e-5)
//! [fixed]                     # optional overrides of the base set (SI)
//! gamma_tq = 0.9
//! [truth]                     # optional: known parameters (synthetic data), reported
//! A = 801e6
//! [[parameter]]               # free parameters: SI bounds and start
//! name = "A"
//! lower = 300e6
//! upper = 2000e6
//! start = 600e6
//! [[experiment]]
//! file = "qs_tension.toml"    # an experiment TOML (fitting::experiment), relative to this file
//! weight = 1.0                # optional, default 1
//! level = "single-point"      # model level: "single-point" | "mpm-axisymmetric" |
//!                             #   "mpm-3d-quarter" | "mpm-3d" (SHPB only: the MPM model with
//!                             #   friction and inertia, `fit::levels::mpm_shpb`; a 3D level costs
//!                             #   ≈ 30× the axisymmetric one at 20 points along)
//! layers = 20                 # MPM levels: points along the specimen (default 20)
//! friction = 0.1              # MPM levels: Coulomb μ at the faces (default 0.1)
//! shape_function = "cpdi"     # MPM levels: "cpdi" (default) or any other kernel
//!                             #   (`mpm_core::shape`; "linear" drifts under refinement,
//!                             #   "ugimp" converges slowly, `fit::levels::mpm_shpb`)
//! drive = "measured-velocity" # MPM levels: the incident face follows the measured
//!                             #   v1 − v2 (default), or "incident-pulse": both faces on elastic
//!                             #   bars, only ε_i drives, the model predicts ε_r and ε_t
//! jacobian = "exact"          # MPM levels: "finite-difference" (default, one run per free
//!                             #   parameter) or "exact": the derivatives carried through one
//!                             #   run (either drive; linear, cpdi, cpgimp or ugimp)
//! thermal = "isothermal"      # tensile: "isothermal" | "adiabatic" (default: adiabatic above 1 1/s)
//! window = [15e-6, 115e-6]    # shpb (required): window [s] after the incident pulse start at the
//!                             #   faces, or "plateau": the strain-rate plateau of `shpb::analyze`
//! forces = "both"             # shpb: "both" (F1 and F2) | "f1" | "f2" (1-wave: transmitted bar)
//! max_equilibrium_ratio = 0.2 # shpb, optional: reject the record if the mean R = 2|F1 − F2|/|F1 + F2|
//!                             #   over the window exceeds this
//! max_samples = 300           # optional: thin the window to at most this many samples
//! [[stage]]                   # optional; default: one stage, all parameters, all experiments
//! free = ["A", "B", "N"]
//! experiments = ["qs_tension"]   # experiment names (the TOML file stems)
//! [[candidate]]               # optional: another flow-stress law to fit to the same
//!                             #   experiments; `mpw fit` then chooses among the set's own
//! name = "Huh-Kang rate"      #   law and every candidate by leave-one-group-out prediction
//! material = "../materials/ss304l_huh_kang.toml"
//! free = ["A", "B", "N", "C", "C2"]  # bounds from the set's [[parameter]] of that name,
//! [[candidate.parameter]]     #   or from the candidate's own entries (which come first)
//! name = "C2"
//! lower = 0.0
//! upper = 0.05
//! start = 0.001
//! ```
//! Paths are relative to the set file's folder.

use anyhow::{bail, Context, Result};
use materials::toml_place;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SetFile {
    pub name: String,
    pub material: String,
    #[serde(default = "default_optimizer")]
    pub optimizer: String,
    #[serde(default = "one")]
    pub starts: usize,
    #[serde(default)]
    pub seed: u64,
    /// Levenberg-Marquardt stops when S falls by less than this fraction in a step.
    pub ftol: Option<f64>,
    #[serde(default)]
    pub fixed: BTreeMap<String, f64>,
    #[serde(default)]
    pub truth: BTreeMap<String, f64>,
    /// Free parameters; none: the set can only be evaluated (`mpw predict`).
    #[serde(default, rename = "parameter")]
    pub parameters: Vec<ParameterEntry>,
    #[serde(rename = "experiment")]
    pub experiments: Vec<ExperimentEntry>,
    #[serde(default, rename = "stage")]
    pub stages: Vec<StageEntry>,
    /// Other flow-stress laws to fit to the same experiments and compare by prediction.
    #[serde(default, rename = "candidate")]
    pub candidates: Vec<CandidateEntry>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CandidateEntry {
    pub name: String,
    pub material: String,
    pub free: Vec<String>,
    /// Bounds and starts of free parameters the set's [[parameter]] entries do not give
    /// (or give otherwise for this law).
    #[serde(default, rename = "parameter")]
    pub parameters: Vec<ParameterEntry>,
}

fn default_optimizer() -> String {
    "lm".into()
}

fn one() -> usize {
    1
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterEntry {
    pub name: String,
    pub lower: f64,
    pub upper: f64,
    pub start: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExperimentEntry {
    pub file: String,
    #[serde(default = "unit_weight")]
    pub weight: f64,
    #[serde(default = "single_point")]
    pub level: String,
    pub thermal: Option<String>,
    pub window: Option<Window>,
    pub forces: Option<String>,
    pub max_equilibrium_ratio: Option<f64>,
    pub max_samples: Option<usize>,
    pub layers: Option<usize>,
    pub friction: Option<f64>,
    pub shape_function: Option<String>,
    pub drive: Option<String>,
    pub jacobian: Option<String>,
}

/// An SHPB fit window: explicit times [s] or the strain-rate plateau (`"plateau"`).
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum Window {
    Times([f64; 2]),
    Named(String),
}

fn unit_weight() -> f64 {
    1.0
}

fn single_point() -> String {
    "single-point".into()
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StageEntry {
    pub free: Vec<String>,
    pub experiments: Vec<String>,
}

impl SetFile {
    /// The set file at `path` and its text.
    pub fn read(path: &Path) -> Result<(SetFile, String)> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("{}: cannot read", path.display()))?;
        let set: SetFile = toml::from_str(&text)
            .map_err(|e| anyhow::anyhow!("{}", toml_place::describe(path, &text, &e)))?;
        let at = |key: &str| {
            toml_place::Location::in_text(path, &text, toml_place::find_key(&text, None, key).start)
        };
        if !["lm", "lm-fd", "nelder-mead"].contains(&set.optimizer.as_str()) {
            bail!(
                "{}: `optimizer`: \"{}\", expected \"lm\", \"lm-fd\" or \"nelder-mead\"",
                at("optimizer"),
                set.optimizer
            );
        }
        if set.starts == 0 {
            bail!("{}: `starts`: must be at least 1", at("starts"));
        }
        if !set.candidates.is_empty() && !set.stages.is_empty() {
            bail!(
                "{}: a set with [[candidate]] laws fits each in one stage; remove the [[stage]] entries",
                at("stage")
            );
        }
        Ok((set, text))
    }

    /// This set with the `k`-th candidate's material and free parameters in place of its
    /// own, and no candidates.
    pub fn with_candidate(mut self, k: usize) -> Result<SetFile> {
        let candidate = self.candidates[k].clone();
        let mut parameters = Vec::new();
        for name in &candidate.free {
            let own = candidate.parameters.iter().find(|p| &p.name == name);
            let shared = self.parameters.iter().find(|p| &p.name == name);
            match own.or(shared) {
                Some(p) => parameters.push(p.clone()),
                None => bail!(
                    "`candidate.free` of \"{}\": no bounds for `{name}`: add a [[parameter]] or [[candidate.parameter]] entry named \"{name}\"",
                    candidate.name
                ),
            }
        }
        if let Some(extra) =
            (candidate.parameters.iter()).find(|p| !candidate.free.contains(&p.name))
        {
            bail!(
                "`candidate.parameter` of \"{}\": `{}` is not in its `free` list",
                candidate.name,
                extra.name
            );
        }
        self.name = format!("{}: {}", self.name, candidate.name);
        self.material = candidate.material;
        self.parameters = parameters;
        self.candidates.clear();
        Ok(self)
    }
}

/// Resolve `path` (relative to the set file's `folder`).
pub fn resolve(folder: &Path, path: &str) -> PathBuf {
    folder.join(path)
}
