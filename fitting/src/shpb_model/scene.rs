//! An SHPB scene file: the MPM model of one SHPB record (`mpw simulate` runs it). Paths
//! are relative to the scene file.
//!
//! ```toml
//! kind = "shpb"
//! experiment = "../experiments/shpb_steel_945/test_01.toml"  # its processed face signals drive the model
//! material = "../materials/steel_945.toml"                    # Johnson-Cook file or fit report (with --params)
//! level = "mpm-axisymmetric"      # or "mpm-3d-quarter" (symmetry planes x = 0, y = 0), "mpm-3d"
//! drive = "incident-pulse"        # or "measured-velocity" (the thesis's)
//! layers = 20                     # points along the specimen (thesis B1-B3: 20, 40, 60)
//! friction = 0.1                  # Coulomb μ at both faces
//! contact_factor = 1.0            # contact frequency ω_c over c/s
//! safety = 0.3                    # CFL safety factor
//! shape_function = "linear"       # default; any kernel of `mpm_core::shape` ("cpdi" is the
//!                                 #   fit level's default and converges, see `fit::levels::mpm_shpb`)
//! ```

use super::{record, Drive, ModelSettings, ShpbModel};
use crate::experiment::ShpbExperiment;
use crate::shpb::{analyze, ShpbAnalysis};
use anyhow::{bail, Context, Result};
use materials::plasticity::ElastoPlastic;
use serde::Deserialize;
use std::path::{Path, PathBuf};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    kind: String,
    experiment: PathBuf,
    material: PathBuf,
    level: String,
    drive: String,
    layers: usize,
    /// Left out: the defaults of `ModelSettings::new`.
    friction: Option<f64>,
    contact_factor: Option<f64>,
    safety: Option<f64>,
    shape_function: Option<String>,
}

/// A loaded SHPB scene: the record, its processed face signals and the model settings.
#[derive(Clone)]
pub struct ShpbScene {
    pub experiment: ShpbExperiment,
    pub analysis: ShpbAnalysis,
    pub material_file: PathBuf,
    pub settings: ModelSettings,
}

/// Whether `path` is an SHPB scene (`kind = "shpb"`) rather than an mpm-core scene.
pub fn is_shpb_scene(path: &Path) -> bool {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| t.parse::<toml::Table>().ok())
        .and_then(|t| t.get("kind").and_then(|k| k.as_str().map(|k| k == "shpb")))
        .unwrap_or(false)
}

impl ShpbScene {
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("{}: cannot read", path.display()))?;
        let f: SceneFile = toml::from_str(&text)
            .map_err(|e| anyhow::anyhow!("{}", materials::toml_place::describe(path, &text, &e)))?;
        let field = |name: &str, problem: String| {
            let offset = materials::toml_place::find_key(&text, None, name).start;
            let at = materials::toml_place::Location::in_text(path, &text, offset);
            anyhow::anyhow!("{at}: `{name}`: {problem}")
        };
        if f.kind != "shpb" {
            bail!(field("kind", format!("\"{}\", expected \"shpb\"", f.kind)));
        }
        let drive: Drive = f.drive.parse().map_err(|e| field("drive", e))?;
        let mut settings = ModelSettings::new(f.layers, drive);
        settings.level = f.level.parse().map_err(|e| field("level", e))?;
        settings.friction = f.friction.unwrap_or(settings.friction);
        settings.contact_factor = f.contact_factor.unwrap_or(settings.contact_factor);
        settings.safety = f.safety.unwrap_or(settings.safety);
        if !(2..=2000).contains(&f.layers) {
            bail!(field(
                "layers",
                format!("{} points along the specimen, expected 2 to 2000", f.layers)
            ));
        }
        if !(0.0..=1.0).contains(&settings.friction) {
            bail!(field(
                "friction",
                format!(
                    "{}, expected a Coulomb coefficient between 0 and 1",
                    settings.friction
                )
            ));
        }
        if !(settings.contact_factor > 0.1 && settings.contact_factor <= 10.0) {
            bail!(field(
                "contact_factor",
                format!("{}, expected 0.1 < factor <= 10", settings.contact_factor)
            ));
        }
        if !(settings.safety > 0.0 && settings.safety <= 1.0) {
            bail!(field(
                "safety",
                format!("{}, expected 0 < safety <= 1", settings.safety)
            ));
        }
        if let Some(name) = &f.shape_function {
            settings.shape_function = name
                .parse()
                .map_err(|e: String| field("shape_function", e))?;
        }
        let dir = path.parent().unwrap_or(Path::new("."));
        let experiment = ShpbExperiment::load(&dir.join(&f.experiment))?;
        let analysis = analyze(&experiment)
            .with_context(|| format!("processing {}", experiment.data_file.display()))?;
        Ok(ShpbScene {
            experiment,
            analysis,
            material_file: dir.join(&f.material),
            settings,
        })
    }

    /// Sample times of the record's plateau window [s], where model and record are compared.
    pub fn plateau_times(&self) -> Vec<f64> {
        let a = &self.analysis;
        a.plateau.range.clone().map(|k| a.time_s[k]).collect()
    }

    /// The model of this record with `material`, which starts at the test temperature.
    pub fn model(&self, material: &ElastoPlastic) -> Result<ShpbModel> {
        record::model(&self.experiment, &self.analysis, self.settings, material)
    }

    /// `material` starting at the test temperature.
    pub fn material(&self, material: &ElastoPlastic) -> std::sync::Arc<dyn materials::Material> {
        record::preheated(material, self.experiment.temperature_k)
    }
}
