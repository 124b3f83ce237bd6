//! A loaded experiment set: the base material with its fixed overrides, the experiments
//! as objective blocks at their model level, the free parameters and the stages.

use crate::experiment::{load_experiments, Experiment, ShpbExperiment, TensileExperiment};
use crate::fit::evaluations::{Evaluations, InProcess};
use crate::fit::levels::model::{with_values, ExperimentModel, Material};
use crate::fit::levels::mpm_shpb::{FaceForces, Jacobian, MpmShpb};
use crate::fit::levels::shpb_input::face_signals;
use crate::fit::levels::shpb_specimen::ShpbSpecimen;
use crate::fit::levels::single_point::SinglePoint;
use crate::fit::levels::tensile::{Tensile, Thermal};
use crate::fit::objective::{Block, StressStrain};
use crate::fit::optimize::lm::LmOptions;
use crate::fit::params::FreeParam;
use crate::fit::sets::set_file::{resolve, ExperimentEntry, SetFile, Window};
use crate::shpb::{analyze, ShpbAnalysis};
use crate::shpb_model::{record, Drive, ModelLevel, ModelSettings};
use anyhow::{anyhow, bail, Context, Result};
use materials::material::Model;
use materials::toml_place::{find_key, Location};
use materials::AnyModel;
use mpm_core::shape::ShapeFunction;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A problem with one key of an `[[experiment]]` entry; `FitSet::load` places it at that
/// key's line (`materials::toml_place`).
#[derive(Debug)]
struct FieldError {
    key: &'static str,
    problem: String,
}

impl std::fmt::Display for FieldError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "`{}`: {}", self.key, self.problem)
    }
}

impl std::error::Error for FieldError {}

fn field(key: &'static str, problem: impl Into<String>) -> anyhow::Error {
    FieldError {
        key,
        problem: problem.into(),
    }
    .into()
}

/// Default thinning of an experiment's window.
pub const DEFAULT_MAX_SAMPLES: usize = 300;

/// One stage of a fit: free parameters (indices into `FitSet::params`) and experiments
/// (indices into `FitSet::blocks`).
#[derive(Debug, Clone)]
pub struct Stage {
    pub free: Vec<usize>,
    pub experiments: Vec<usize>,
}

pub struct FitSet {
    pub name: String,
    pub file: PathBuf,
    /// The material file the set names, and the name it gives the material.
    pub material_file: PathBuf,
    pub material_name: String,
    pub base: Material,
    pub params: Vec<FreeParam>,
    pub blocks: Vec<Block>,
    pub stages: Vec<Stage>,
    pub optimizer: String,
    pub starts: usize,
    /// Relative decrease of S below which LM stops.
    pub ftol: f64,
    pub seed: u64,
    pub truth: BTreeMap<String, f64>,
    /// Where the fit's model runs go (`FitSet::load`: this process; `mpw fit --executor`
    /// sends the expensive ones to a process pool or Slurm).
    pub evaluations: Arc<dyn Evaluations>,
}

impl FitSet {
    pub fn load(path: &Path) -> Result<FitSet> {
        let (set, text) = SetFile::read(path)?;
        Self::build(set, &text, path)
    }

    /// The set as written, then one set per `[[candidate]]` law (its material and free
    /// parameters, the same experiments), each with the law's name: the material's for the
    /// set as written, the `[[candidate]]`'s own for the others.
    pub fn load_candidates(path: &Path) -> Result<Vec<(String, FitSet)>> {
        let (set, text) = SetFile::read(path)?;
        let written = Self::build(set.clone(), &text, path)?;
        let mut sets = vec![(written.material_name.clone(), written)];
        for (k, candidate) in set.candidates.iter().enumerate() {
            let built = (set.clone().with_candidate(k))
                .and_then(|set| Self::build(set, &text, path))
                .with_context(|| {
                    format!("{}: [[candidate]] \"{}\"", path.display(), candidate.name)
                })?;
            sets.push((candidate.name.clone(), built));
        }
        Ok(sets)
    }

    /// A set built in memory, without a file: `blocks` fitted over every parameter of
    /// `params` in one stage, one start, in this process, LM's default tolerance.
    pub fn in_memory(
        name: &str,
        base: Material,
        params: Vec<FreeParam>,
        blocks: Vec<Block>,
    ) -> FitSet {
        FitSet {
            name: name.to_string(),
            file: PathBuf::from(format!("{name} (in memory)")),
            material_file: PathBuf::new(),
            material_name: name.to_string(),
            base,
            stages: vec![Stage {
                free: (0..params.len()).collect(),
                experiments: (0..blocks.len()).collect(),
            }],
            params,
            blocks,
            optimizer: "lm".into(),
            starts: 1,
            ftol: LmOptions::default().ftol,
            seed: 0,
            truth: BTreeMap::new(),
            evaluations: Arc::new(InProcess),
        }
    }

    fn build(set: SetFile, text: &str, path: &Path) -> Result<FitSet> {
        let folder = path.parent().unwrap_or(Path::new("."));
        // `file:line:column: `key`` of a key at the top level or of the k-th entry of a table
        let place = |table: Option<(&str, usize)>, key: &str| {
            let at = Location::in_text(path, &text, find_key(&text, table, key).start);
            match table {
                Some((t, _)) => format!("{at}: `{t}.{key}`"),
                None => format!("{at}: `{key}`"),
            }
        };
        let here = |key: &str| place(None, key);
        let material_file = resolve(folder, &set.material);
        let loaded = materials::load_material(&material_file)?;
        let material_name = loaded.name.clone();
        let base = match loaded.model {
            AnyModel::ElastoPlastic(m) => m,
            _ => bail!(
                "{}: the material must be elasto-plastic (Johnson-Cook)",
                here("material")
            ),
        };
        for (table, names) in [("fixed", &set.fixed), ("truth", &set.truth)] {
            for name in names.keys() {
                if base.param(name).is_none() {
                    bail!(
                        "{}: unknown parameter; known: {:?}",
                        place(Some((table, 0)), name),
                        base.param_names()
                    );
                }
            }
        }
        let names: Vec<&str> = set.fixed.keys().map(String::as_str).collect();
        let values: Vec<f64> = set.fixed.values().copied().collect();
        let base = with_values(&base, &names, &values);
        let mut params = Vec::new();
        for (k, p) in set.parameters.iter().enumerate() {
            if base.param(&p.name).is_none() {
                bail!(
                    "{}: unknown parameter \"{}\"; known: {:?}",
                    place(Some(("parameter", k)), "name"),
                    p.name,
                    base.param_names()
                );
            }
            params.push(
                FreeParam::new(&p.name, p.lower, p.upper, p.start)
                    .with_context(|| place(Some(("parameter", k)), "name"))?,
            );
        }
        let mut blocks = Vec::new();
        for (k, entry) in set.experiments.iter().enumerate() {
            let file = resolve(folder, &entry.file);
            let experiments =
                load_experiments(&file).with_context(|| place(Some(("experiment", k)), "file"))?;
            for exp in experiments {
                let block = build_block(&base, &exp, entry).map_err(|e| {
                    let record = format!("(record `{}` of {})", exp.name(), file.display());
                    match e.downcast_ref::<FieldError>() {
                        Some(f) => anyhow!(
                            "{}: {} {record}",
                            place(Some(("experiment", k)), f.key),
                            f.problem
                        ),
                        None => e.context(format!(
                            "{} {record}",
                            place(Some(("experiment", k)), "file")
                        )),
                    }
                })?;
                blocks.push(block);
            }
        }
        let stages = if set.stages.is_empty() {
            vec![Stage {
                free: (0..params.len()).collect(),
                experiments: (0..blocks.len()).collect(),
            }]
        } else {
            let mut stages = Vec::new();
            for (si, s) in set.stages.iter().enumerate() {
                let free = s
                    .free
                    .iter()
                    .map(|n| {
                        params.iter().position(|p| &p.name == n).ok_or_else(|| {
                            anyhow::anyhow!(
                                "{}: `{n}` is not a [[parameter]]",
                                place(Some(("stage", si)), "free")
                            )
                        })
                    })
                    .collect::<Result<Vec<_>>>()?;
                let experiments = s
                    .experiments
                    .iter()
                    .map(|n| {
                        blocks
                            .iter()
                            .position(|b: &Block| &b.name == n)
                            .ok_or_else(|| {
                                anyhow::anyhow!(
                                    "{}: no experiment named `{n}`; names: {:?}",
                                    place(Some(("stage", si)), "experiments"),
                                    blocks.iter().map(|b| b.name.clone()).collect::<Vec<_>>()
                                )
                            })
                    })
                    .collect::<Result<Vec<_>>>()?;
                stages.push(Stage { free, experiments });
            }
            stages
        };
        Ok(FitSet {
            name: set.name,
            file: path.to_path_buf(),
            material_file,
            material_name,
            base,
            params,
            blocks,
            stages,
            optimizer: set.optimizer,
            starts: set.starts,
            ftol: match set.ftol {
                Some(f) if !(f > 0.0 && f < 0.1) => {
                    bail!(
                        "{}: {f}, expected a fraction between 0 and 0.1",
                        here("ftol")
                    )
                }
                f => f.unwrap_or(LmOptions::default().ftol),
            },
            seed: set.seed,
            truth: set.truth,
            evaluations: Arc::new(InProcess),
        })
    }
}

/// Every `stride`-th index of `range` so that at most `max` remain (the last kept).
fn thin(range: std::ops::Range<usize>, max: usize) -> Vec<usize> {
    let n = range.len();
    let stride = n.div_ceil(max.max(1)).max(1);
    let mut idx: Vec<usize> = range.clone().step_by(stride).collect();
    if let Some(&last) = idx.last() {
        if last != range.end - 1 {
            idx.push(range.end - 1);
        }
    }
    idx
}

/// The model levels of a set file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Level {
    SinglePoint,
    Mpm(ModelLevel),
}

fn build_block(base: &Material, exp: &Experiment, entry: &ExperimentEntry) -> Result<Block> {
    let level = match entry.level.as_str() {
        "single-point" => Level::SinglePoint,
        mpm => Level::Mpm(
            mpm.parse()
                .map_err(|e: String| field("level", format!("{e}, or \"single-point\"")))?,
        ),
    };
    let mpm_fields = [
        entry.layers.is_some(),
        entry.friction.is_some(),
        entry.shape_function.is_some(),
        entry.drive.is_some(),
        entry.jacobian.is_some(),
    ];
    if level == Level::SinglePoint && mpm_fields.contains(&true) {
        return Err(field("level", "`layers`, `friction`, `shape_function`, `drive` and `jacobian` belong to the MPM levels (level = \"mpm-axisymmetric\", ...)"));
    }
    let max = entry.max_samples.unwrap_or(DEFAULT_MAX_SAMPLES);
    match (exp, level) {
        (Experiment::Tensile(e), Level::SinglePoint) => tensile_block(base, e, entry, max),
        (Experiment::Tensile(_), Level::Mpm(_)) => {
            return Err(field(
                "level",
                "the MPM level models the SHPB test only; a tensile test is \"single-point\"",
            ))
        }
        (Experiment::Shpb(e), level) => shpb_block(base, e, entry, max, level),
    }
}

fn tensile_block(
    base: &Material,
    e: &TensileExperiment,
    entry: &ExperimentEntry,
    max: usize,
) -> Result<Block> {
    if entry.window.is_some() || entry.forces.is_some() || entry.max_equilibrium_ratio.is_some() {
        return Err(field("file", "`window`, `forces` and `max_equilibrium_ratio` are for SHPB experiments; a tensile window goes in the experiment TOML"));
    }
    let thermal = match entry.thermal.as_deref() {
        Some("isothermal") => Thermal::Isothermal,
        Some("adiabatic") => Thermal::Adiabatic,
        None if e.nominal_strain_rate_per_s > 1.0 => Thermal::Adiabatic,
        None => Thermal::Isothermal,
        Some(other) => {
            return Err(field(
                "thermal",
                format!("\"{other}\", expected \"isothermal\" or \"adiabatic\""),
            ))
        }
    };
    // The model follows the record from its first sample (its own strain-time history)
    // and is compared at the thinned samples of the valid window.
    let idx = thin(e.used_range(), max);
    let pick = |v: &[f64]| idx.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    let (t, strain, stress) = (pick(&e.time_s), pick(&e.eng_strain), pick(&e.eng_stress_pa));
    let model = Tensile::new(
        base,
        &e.time_s,
        &e.eng_strain,
        &idx,
        thermal,
        e.temperature_k,
    )
    .with_context(|| {
        format!(
            "{}: the tensile model of `{}`",
            e.data_file.display(),
            e.name
        )
    })?;
    let mut block = Block::new(
        &e.name,
        Box::new(SinglePoint::new(model)),
        stress,
        t,
        strain,
        "engineering strain [-]",
        "engineering stress [MPa]",
        1e-6,
        entry.weight,
    )?;
    block.rate_per_s = e.nominal_strain_rate_per_s;
    block.temperature_k = e.temperature_k;
    block.group = Some(format!(
        "{} 1/s, {:.1} K",
        e.nominal_strain_rate_per_s, e.temperature_k
    ));
    block.strain_range = range_of(&block.x);
    block.metadata_source = format!(
        "rate: {}; temperature: {}",
        e.rate_source, e.temperature_source
    );
    Ok(block)
}

/// The MPM model of record `e` (processed into `analysis`) at `level` and its `samples`
/// (indices of the analysis), with the entry's layers, friction, shape functions (CPDI unless named:
/// `mpm_shpb`) and drive (the measured face velocity unless named).
fn mpm_block_model(
    base: &Material,
    e: &ShpbExperiment,
    analysis: &ShpbAnalysis,
    entry: &ExperimentEntry,
    samples: &[usize],
    forces: FaceForces,
    level: ModelLevel,
) -> Result<MpmShpb> {
    let drive = match &entry.drive {
        Some(name) => name.parse().map_err(|e: String| field("drive", e))?,
        None => Drive::MeasuredVelocity,
    };
    let mut settings = ModelSettings::new(entry.layers.unwrap_or(20), drive);
    settings.level = level;
    settings.friction = entry.friction.unwrap_or(settings.friction);
    settings.shape_function = match &entry.shape_function {
        Some(name) => name
            .parse()
            .map_err(|e: String| field("shape_function", e))?,
        None => ShapeFunction::SCENE_DEFAULT,
    };
    if !(2..=400).contains(&settings.layers) {
        return Err(field(
            "layers",
            format!(
                "{}, expected 2 to 400 points along the specimen",
                settings.layers
            ),
        ));
    }
    if !(0.0..=1.0).contains(&settings.friction) {
        return Err(field(
            "friction",
            format!(
                "{}, expected a Coulomb coefficient between 0 and 1",
                settings.friction
            ),
        ));
    }
    let jacobian = match &entry.jacobian {
        Some(name) => name.parse().map_err(|e: String| field("jacobian", e))?,
        None => Jacobian::FiniteDifference,
    };
    if jacobian == Jacobian::Exact {
        if !mpm_core::solver::carries(settings.shape_function) {
            return Err(field(
                "jacobian",
                format!(
                    "\"exact\" needs shape_function \"cpdi\", \"cpgimp\", \"ugimp\" or \"linear\", not \"{}\"",
                    settings.shape_function.name()
                ),
            ));
        }
    }
    let times = samples.iter().map(|&k| analysis.time_s[k]).collect();
    let model = record::model(e, analysis, settings, base)?;
    Ok(MpmShpb::new(model, times, forces, e.temperature_k).with_jacobian(jacobian))
}

/// Mean of R = 2 |F1 − F2| / |F1 + F2| over `range` [-].
fn mean_equilibrium_ratio(f1: &[f64], f2: &[f64], range: std::ops::Range<usize>) -> f64 {
    let n = range.len() as f64;
    range
        .map(|k| 2.0 * (f1[k] - f2[k]).abs() / (f1[k] + f2[k]).abs())
        .sum::<f64>()
        / n
}

fn shpb_block(
    base: &Material,
    e: &ShpbExperiment,
    entry: &ExperimentEntry,
    max: usize,
    level: Level,
) -> Result<Block> {
    if entry.thermal.is_some() {
        return Err(field("thermal", "an SHPB specimen is always adiabatic"));
    }
    let channel = match entry.forces.as_deref() {
        None | Some("both") => FaceForces::Both,
        Some("f1") => FaceForces::F1,
        Some("f2") => FaceForces::F2,
        Some(other) => {
            return Err(field(
                "forces",
                format!("\"{other}\", expected \"both\", \"f1\" or \"f2\""),
            ))
        }
    };
    let analysis = analyze(e)?;
    let face = face_signals(&analysis);
    let range = match &entry.window {
        None => return Err(field("file", "an SHPB experiment needs its specimen-face time window `window = [t_min, t_max]` in s, or \"plateau\"")),
        Some(Window::Named(name)) if name == "plateau" => face.plateau.start.max(1)..face.plateau.end,
        Some(Window::Named(other)) => {
            return Err(field("window", format!("\"{other}\", expected [t_min, t_max] or \"plateau\"")))
        }
        Some(Window::Times([t0, t1])) => {
            let (t0, t1) = (*t0, *t1);
            if !(0.0 <= t0 && t0 < t1) {
                return Err(field("window", format!("[{t0}, {t1}] must satisfy 0 <= t_min < t_max")));
            }
            let end = *face.time_s.last().unwrap();
            if t1 > end {
                return Err(field("window", format!(
                    "t_max = {t1:e} s is past the analysed record, which ends at {end:e} s after the incident pulse start"
                )));
            }
            let inside: Vec<usize> = (1..face.time_s.len())
                .filter(|&k| face.time_s[k] >= t0 && face.time_s[k] <= t1)
                .collect();
            if inside.is_empty() {
                return Err(field("window", format!("no samples in [{t0:e}, {t1:e}] s")));
            }
            inside[0]..inside[inside.len() - 1] + 1
        }
    };
    if range.is_empty() {
        return Err(field("window", "no samples in the window"));
    }
    let ratio = mean_equilibrium_ratio(&face.f1_n, &face.f2_n, range.clone());
    if let Some(limit) = entry.max_equilibrium_ratio {
        if ratio.is_nan() || ratio > limit {
            return Err(field("max_equilibrium_ratio", format!(
                "the mean equilibrium ratio over the window is {ratio:.3}, above {limit}: the specimen is not in equilibrium"
            )));
        }
    }
    let samples: Vec<usize> = thin(range, max);
    let model: Box<dyn ExperimentModel> = match level {
        Level::SinglePoint => Box::new(SinglePoint::new(ShpbSpecimen::new(
            base,
            &face.time_s,
            &face.velocity_m_per_s,
            &samples,
            e.specimen.length_m,
            e.specimen.area_m2(),
            e.temperature_k,
            channel.count(),
        )?)),
        Level::Mpm(level) => Box::new(mpm_block_model(
            base, e, &analysis, entry, &samples, channel, level,
        )?),
    };
    let first = if channel == FaceForces::F2 {
        &face.f2_n
    } else {
        &face.f1_n
    };
    let mut measured: Vec<f64> = samples.iter().map(|&k| first[k]).collect();
    let times: Vec<f64> = samples.iter().map(|&k| face.time_s[k]).collect();
    let mut x: Vec<f64> = times.iter().map(|t| t * 1e6).collect();
    if channel == FaceForces::Both {
        measured.extend(samples.iter().map(|&k| face.f2_n[k]));
        x.extend(times.iter().map(|t| t * 1e6));
    }
    let mut block = Block::new(
        &e.name,
        model,
        measured,
        times,
        x,
        "specimen-face time [µs]",
        "force, compression positive [kN]",
        1e-3,
        entry.weight,
    )?;
    block.channels = match channel {
        FaceForces::Both => vec!["F1".into(), "F2".into()],
        FaceForces::F1 => vec!["F1".into()],
        FaceForces::F2 => vec!["F2".into()],
    };
    block.equilibrium_ratio = ratio;
    let strain: Vec<f64> = samples
        .iter()
        .map(|&k| analysis.true_strain[k].abs())
        .collect();
    block.strain_range = range_of(&strain);
    block.stress_strain = Some(StressStrain::new(strain, e.specimen.area_m2()));
    block.temperature_k = e.temperature_k;
    let strain_rate: Vec<f64> = samples
        .iter()
        .map(|&k| face.velocity_m_per_s[k] / e.specimen.length_m)
        .collect();
    block.rate_per_s = strain_rate.iter().sum::<f64>() / strain_rate.len() as f64;
    Ok(block)
}

/// [smallest, largest] of `values` (NaN for none).
fn range_of(values: &[f64]) -> [f64; 2] {
    values
        .iter()
        .fold([f64::NAN, f64::NAN], |[lo, hi], &v| [lo.min(v), hi.max(v)])
}
