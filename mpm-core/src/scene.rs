//! Scene files (TOML): grid, time, materials by file, bodies from primitives, rigid
//! bodies, boundary conditions, control points and outputs. Unknown keys and wrong types
//! are rejected by the parser with the key named; every value is then checked and an
//! error names the field (e.g. `bodies[1].shape.radius`). Paths are relative to the scene
//! file. Units SI.
//!
//! ```toml
//! kinematics = "plane-strain"      # "plane-strain" | "axisymmetric" | "3d"
//! [grid]                           # spacing [m], origin [m], shift amplitudes [m], seed
//! [time]                           # end [s], dt [s] (optional), safety, scheme = "musl" (default)|"usl"|"usf"
//! [solver]                         # damping [1/s], mass_cutoff, body_force [m/s²], domain, blowup_factor,
//!                                  # bulk_viscosity = [C1, C2] (default [0.06, 1.5]; [0, 0] for none)
//! [[materials]]                    # name, file = "../materials/x.toml" or neo_hooke = {E, nu, rho}
//! [[bodies]]                       # name, material, shape = {type = "box"|"disk"|"sphere"|"cylinder"|"polygon", ...},
//!                                  # particles_per_cell, velocity
//! [[rigid_bodies]]                 # name, shape = {type = "half-space"|"box"|"polygon"|"triangles", ...},
//!                                  # penalty, friction, search_interval, translation = [[t, u...]], rotation
//! [[velocity_bcs]]                 # nodes = {plane|below|above = "x", at}, fixed = ["x", ...], value = [...],
//!                                  # one_sided = true (a wall the body may leave; below/above nodes)
//! [[springs]]                      # region = {min, max}, directions, stiffness
//! [[tractions]]                    # region = {min, max}, force [N]
//! [[control_points]]               # name, position
//! [output]                         # history_every (steps), snapshots (count)
//! ```

use crate::boundary::{NodeSet, SpringBc, VelocityBc};
use crate::discretize::{fill, Shape};
use crate::kinematics::Kinematics;
use crate::rigid::{
    convex_from_polygon, convex_from_triangles, recast, Motion, RigidBody, Rotation, Table,
};
use crate::solver::{Scheme, Settings, Solver};
use crate::viscosity::BulkViscosity;
use materials::limits::PARTICLES;
use materials::{load_material, Material, NeoHooke};
use nalgebra::{SVector, Unit, Vector3};
use serde::Deserialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum SceneError {
    #[error("{file}: cannot read: {reason}")]
    Io {
        file: PathBuf,
        reason: std::io::Error,
    },
    #[error("{file}: {message}")]
    Syntax { file: PathBuf, message: String },
    #[error("{file}: field `{field}`: {problem}")]
    Field {
        file: PathBuf,
        field: String,
        problem: String,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub kinematics: String,
    pub grid: GridSpec,
    pub time: TimeSpec,
    #[serde(default)]
    pub solver: SolverSpec,
    pub materials: Vec<MaterialSpec>,
    pub bodies: Vec<BodySpec>,
    #[serde(default)]
    pub rigid_bodies: Vec<RigidSpec>,
    #[serde(default)]
    pub velocity_bcs: Vec<VelocityBcSpec>,
    #[serde(default)]
    pub springs: Vec<SpringSpec>,
    #[serde(default)]
    pub tractions: Vec<TractionSpec>,
    #[serde(default)]
    pub control_points: Vec<ControlPointSpec>,
    #[serde(default)]
    pub output: OutputSpec,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    pub spacing: f64,
    pub origin: Option<Vec<f64>>,
    pub shift: Option<Vec<f64>>,
    #[serde(default)]
    pub seed: u64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    pub end: f64,
    pub dt: Option<f64>,
    pub safety: Option<f64>,
    pub scheme: Option<String>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    pub damping: Option<f64>,
    pub mass_cutoff: Option<f64>,
    pub body_force: Option<Vec<f64>>,
    pub domain: Option<BoxSpec>,
    pub blowup_factor: Option<f64>,
    pub bulk_viscosity: Option<[f64; 2]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    pub min: Vec<f64>,
    pub max: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeoHookeSpec {
    #[serde(rename = "E")]
    pub e: f64,
    pub nu: f64,
    pub rho: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub name: String,
    pub file: Option<String>,
    pub neo_hooke: Option<NeoHookeSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ShapeSpec {
    Box {
        min: Vec<f64>,
        max: Vec<f64>,
    },
    Disk {
        center: Vec<f64>,
        radius: f64,
    },
    Sphere {
        center: Vec<f64>,
        radius: f64,
    },
    Cylinder {
        start: Vec<f64>,
        end: Vec<f64>,
        radius: f64,
    },
    Polygon {
        vertices: Vec<Vec<f64>>,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub name: String,
    pub material: String,
    pub shape: ShapeSpec,
    #[serde(default = "two")]
    pub particles_per_cell: usize,
    pub velocity: Option<Vec<f64>>,
}

fn two() -> usize {
    2
}

#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum RigidShapeSpec {
    HalfSpace {
        point: Vec<f64>,
        normal: Vec<f64>,
    },
    Box {
        min: Vec<f64>,
        max: Vec<f64>,
    },
    Polygon {
        vertices: Vec<Vec<f64>>,
    },
    Triangles {
        vertices: Vec<Vec<f64>>,
        triangles: Vec<[usize; 3]>,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotationSpec {
    pub center: Vec<f64>,
    pub axis: Vec<f64>,
    /// (t [s], angle [rad]) knots.
    pub angle: Vec<[f64; 2]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigidSpec {
    pub name: String,
    pub shape: RigidShapeSpec,
    pub penalty: f64,
    #[serde(default)]
    pub friction: f64,
    pub search_interval: Option<usize>,
    /// (t [s], u_1, ..., u_D [m]) knots.
    pub translation: Option<Vec<Vec<f64>>>,
    pub rotation: Option<RotationSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSetSpec {
    pub plane: Option<String>,
    pub below: Option<String>,
    pub above: Option<String>,
    pub at: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VelocityBcSpec {
    pub nodes: NodeSetSpec,
    pub fixed: Vec<String>,
    pub value: Option<Vec<f64>>,
    #[serde(default)]
    pub one_sided: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSpec {
    pub region: BoxSpec,
    pub directions: Vec<String>,
    pub stiffness: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    pub region: BoxSpec,
    pub force: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControlPointSpec {
    pub name: String,
    pub position: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    #[serde(default = "one")]
    pub history_every: usize,
    #[serde(default = "ten")]
    pub snapshots: usize,
}

fn one() -> usize {
    1
}
fn ten() -> usize {
    10
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            history_every: 1,
            snapshots: 10,
        }
    }
}

/// A built scene: a solver of the right dimension and the run settings.
pub enum Simulation {
    Planar(Solver<2>),
    Solid(Solver<3>),
}

pub struct Scene {
    pub simulation: Simulation,
    pub end: f64,
    pub output: OutputSpec,
}

/// Field-checking context: names the file and builds errors.
struct Check<'a> {
    file: &'a Path,
}

impl Check<'_> {
    fn err(&self, field: impl Into<String>, problem: impl Into<String>) -> SceneError {
        SceneError::Field {
            file: self.file.into(),
            field: field.into(),
            problem: problem.into(),
        }
    }
    fn positive(&self, field: &str, v: f64) -> Result<f64, SceneError> {
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(field, format!("must be a positive number, got {v}")))
        }
    }
    fn non_negative(&self, field: &str, v: f64) -> Result<f64, SceneError> {
        if v >= 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(field, format!("must be >= 0, got {v}")))
        }
    }
    fn vector<const D: usize>(
        &self,
        field: &str,
        v: &[f64],
    ) -> Result<SVector<f64, D>, SceneError> {
        if v.len() != D {
            return Err(self.err(field, format!("needs {D} components, got {}", v.len())));
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(self.err(field, "components must be finite"));
        }
        Ok(SVector::from_column_slice(v))
    }
    fn axis<const D: usize>(&self, field: &str, name: &str) -> Result<usize, SceneError> {
        match ["x", "y", "z"][..D].iter().position(|a| *a == name) {
            Some(i) => Ok(i),
            None => Err(self.err(
                field,
                format!(
                    "unknown axis `{name}` (use one of x, y{})",
                    if D == 3 { ", z" } else { "" }
                ),
            )),
        }
    }
    fn boxed<const D: usize>(
        &self,
        field: &str,
        b: &BoxSpec,
    ) -> Result<(SVector<f64, D>, SVector<f64, D>), SceneError> {
        let (lo, hi) = (
            self.vector::<D>(&format!("{field}.min"), &b.min)?,
            self.vector::<D>(&format!("{field}.max"), &b.max)?,
        );
        if (0..D).any(|i| lo[i] >= hi[i]) {
            return Err(self.err(field, "min must be below max in every direction"));
        }
        Ok((lo, hi))
    }
}

/// Read and validate a scene file.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|reason| SceneError::Io {
        file: path.into(),
        reason,
    })?;
    let spec: SceneFile = toml::from_str(&text).map_err(|e| SceneError::Syntax {
        file: path.into(),
        message: e.to_string(),
    })?;
    let check = Check { file: path };
    let kinematics = match spec.kinematics.as_str() {
        "plane-strain" => Kinematics::PlaneStrain,
        "axisymmetric" => Kinematics::Axisymmetric,
        "3d" => Kinematics::Solid,
        other => {
            return Err(check.err(
                "kinematics",
                format!("`{other}` is not one of plane-strain, axisymmetric, 3d"),
            ))
        }
    };
    let dir = path.parent().unwrap_or(Path::new("."));
    let simulation = match kinematics {
        Kinematics::Solid => Simulation::Solid(build::<3>(&spec, kinematics, &check, dir)?),
        _ => Simulation::Planar(build::<2>(&spec, kinematics, &check, dir)?),
    };
    let end = check.positive("time.end", spec.time.end)?;
    if spec.output.history_every == 0 {
        return Err(check.err("output.history_every", "must be at least 1"));
    }
    Ok(Scene {
        simulation,
        end,
        output: spec.output,
    })
}

fn build<const D: usize>(
    spec: &SceneFile,
    kinematics: Kinematics,
    check: &Check,
    dir: &Path,
) -> Result<Solver<D>, SceneError> {
    let mut settings = Settings::<D>::new(
        kinematics,
        check.positive("grid.spacing", spec.grid.spacing)?,
    );
    if let Some(o) = &spec.grid.origin {
        settings.origin = check.vector("grid.origin", o)?;
    }
    if let Some(a) = &spec.grid.shift {
        let a: SVector<f64, D> = check.vector("grid.shift", a)?;
        if a.iter().any(|x| *x < 0.0) {
            return Err(check.err("grid.shift", "amplitudes must be >= 0"));
        }
        if kinematics == Kinematics::Axisymmetric && a[0] != 0.0 {
            return Err(check.err(
                "grid.shift",
                "the radial amplitude must be 0 in an axisymmetric scene (the axis is a grid line)",
            ));
        }
        settings.grid_shift = Some((a, spec.grid.seed));
    }
    settings.dt = spec
        .time
        .dt
        .map(|dt| check.positive("time.dt", dt))
        .transpose()?;
    if let Some(s) = spec.time.safety {
        settings.safety = check.positive("time.safety", s)?;
    }
    settings.scheme = match spec.time.scheme.as_deref().unwrap_or("musl") {
        "usl" => Scheme::Usl,
        "usf" => Scheme::Usf,
        "musl" => Scheme::Musl,
        other => {
            return Err(check.err(
                "time.scheme",
                format!("`{other}` is not one of usl, usf, musl"),
            ))
        }
    };
    let sv = &spec.solver;
    if let Some(d) = sv.damping {
        settings.damping = check.non_negative("solver.damping", d)?;
    }
    if let Some(c) = sv.mass_cutoff {
        settings.mass_cutoff = check.non_negative("solver.mass_cutoff", c)?;
    }
    if let Some(b) = &sv.body_force {
        settings.body_force = check.vector("solver.body_force", b)?;
    }
    if let Some(d) = &sv.domain {
        settings.domain = Some(check.boxed("solver.domain", d)?);
    }
    if let Some(f) = sv.blowup_factor {
        settings.blowup_factor = check.positive("solver.blowup_factor", f)?;
    }
    if let Some([linear, quadratic]) = sv.bulk_viscosity {
        check.non_negative("solver.bulk_viscosity[0]", linear)?;
        check.non_negative("solver.bulk_viscosity[1]", quadratic)?;
        settings.bulk_viscosity =
            (linear > 0.0 || quadratic > 0.0).then_some(BulkViscosity { linear, quadratic });
    }
    let mut solver = Solver::new(settings);

    let mut materials: HashMap<&str, Arc<dyn Material>> = HashMap::new();
    for (k, m) in spec.materials.iter().enumerate() {
        let field = format!("materials[{k}]");
        let material: Arc<dyn Material> = match (&m.file, &m.neo_hooke) {
            (Some(f), None) => Arc::new(
                load_material(dir.join(f))
                    .map_err(|e| check.err(format!("{field}.file"), e.to_string()))?
                    .model,
            ),
            (None, Some(n)) => {
                check.positive(&format!("{field}.neo_hooke.E"), n.e)?;
                check.positive(&format!("{field}.neo_hooke.rho"), n.rho)?;
                if !(-1.0 < n.nu && n.nu < 0.5) {
                    return Err(check.err(
                        format!("{field}.neo_hooke.nu"),
                        format!("must be in (-1, 0.5), got {}", n.nu),
                    ));
                }
                Arc::new(NeoHooke::new(n.e, n.nu, n.rho))
            }
            _ => return Err(check.err(field, "give exactly one of `file` or `neo_hooke`")),
        };
        if materials.insert(m.name.as_str(), material).is_some() {
            return Err(check.err(
                format!("{field}.name"),
                format!("`{}` is defined twice", m.name),
            ));
        }
    }

    let h = solver.settings.spacing;
    let mut particles = 0.0;
    for (k, b) in spec.bodies.iter().enumerate() {
        let field = format!("bodies[{k}]");
        let material = materials
            .get(b.material.as_str())
            .ok_or_else(|| {
                check.err(
                    format!("{field}.material"),
                    format!("no material named `{}`", b.material),
                )
            })?
            .clone();
        let sf = format!("{field}.shape");
        let shape = match &b.shape {
            ShapeSpec::Box { min, max } => {
                let (min, max) = check.boxed::<D>(
                    &sf,
                    &BoxSpec {
                        min: min.clone(),
                        max: max.clone(),
                    },
                )?;
                Shape::Box { min, max }
            }
            ShapeSpec::Disk { center, radius } | ShapeSpec::Sphere { center, radius } => {
                let want = if matches!(b.shape, ShapeSpec::Disk { .. }) {
                    2
                } else {
                    3
                };
                if want != D {
                    return Err(check.err(format!("{sf}.type"), format!("needs a {want}D scene")));
                }
                Shape::Ball {
                    center: check.vector(&format!("{sf}.center"), center)?,
                    radius: check.positive(&format!("{sf}.radius"), *radius)?,
                }
            }
            ShapeSpec::Cylinder { start, end, radius } => {
                if D != 3 {
                    return Err(check.err(
                        format!("{sf}.type"),
                        "cylinder needs a 3d scene (use a box in (r, z) for an axisymmetric one)",
                    ));
                }
                Shape::Cylinder {
                    start: check.vector(&format!("{sf}.start"), start)?,
                    end: check.vector(&format!("{sf}.end"), end)?,
                    radius: check.positive(&format!("{sf}.radius"), *radius)?,
                }
            }
            ShapeSpec::Polygon { vertices } => {
                if D != 2 || vertices.len() < 3 {
                    return Err(check.err(sf, "polygon needs a 2D scene and at least 3 vertices"));
                }
                let vertices = vertices
                    .iter()
                    .enumerate()
                    .map(|(i, v)| check.vector::<D>(&format!("{sf}.vertices[{i}]"), v))
                    .collect::<Result<_, _>>()?;
                Shape::Polygon { vertices }
            }
        };
        let r_min = shape.bounds().0[0];
        if kinematics == Kinematics::Axisymmetric && r_min < 0.0 {
            return Err(check.err(
                sf,
                format!("reaches r = {r_min} m < 0: an axisymmetric body lies in r ≥ 0 (the axis is r = 0)"),
            ));
        }
        if b.particles_per_cell == 0 {
            return Err(check.err(format!("{field}.particles_per_cell"), "must be at least 1"));
        }
        let velocity = b
            .velocity
            .as_ref()
            .map(|v| check.vector::<D>(&format!("{field}.velocity"), v))
            .transpose()?
            .unwrap_or(SVector::zeros());
        let s = h / b.particles_per_cell as f64;
        let (lo, hi) = shape.bounds();
        let estimate: f64 = (0..D)
            .map(|i| ((hi[i] - lo[i]) / s[i]).ceil() + 1.0)
            .product();
        particles += estimate;
        PARTICLES
            .check(particles, || {
                format!("this body's bounding box {lo:?} .. {hi:?} m at a point spacing of {s:?} m (grid.spacing / particles_per_cell) holds about {estimate:.3e}")
            })
            .map_err(|e| check.err(sf.clone(), e.to_string()))?;
        let points = fill(&shape, s, kinematics);
        if points.is_empty() {
            return Err(check.err(sf, "holds no material point (smaller than a sub-cell?)"));
        }
        solver.add_body(&b.name, material, &points, velocity);
    }

    for (k, r) in spec.rigid_bodies.iter().enumerate() {
        let field = format!("rigid_bodies[{k}]");
        let penalty = check.positive(&format!("{field}.penalty"), r.penalty)?;
        let friction = check.non_negative(&format!("{field}.friction"), r.friction)?;
        let sf = format!("{field}.shape");
        let mut body = match &r.shape {
            RigidShapeSpec::HalfSpace { point, normal } => {
                let n: SVector<f64, D> = check.vector(&format!("{sf}.normal"), normal)?;
                if n.norm() == 0.0 {
                    return Err(check.err(format!("{sf}.normal"), "must not be zero"));
                }
                RigidBody::half_space(
                    &r.name,
                    check.vector(&format!("{sf}.point"), point)?,
                    n,
                    penalty,
                    friction,
                )
            }
            RigidShapeSpec::Box { min, max } => {
                let (min, max) = check.boxed::<D>(
                    &sf,
                    &BoxSpec {
                        min: min.clone(),
                        max: max.clone(),
                    },
                )?;
                RigidBody::boxed(&r.name, min, max, penalty, friction)
            }
            RigidShapeSpec::Polygon { vertices } => {
                if D != 2 || vertices.len() < 3 {
                    return Err(check.err(sf, "polygon needs a 2D scene and at least 3 vertices"));
                }
                let v: Vec<SVector<f64, 2>> = vertices
                    .iter()
                    .enumerate()
                    .map(|(i, v)| check.vector::<2>(&format!("{sf}.vertices[{i}]"), v))
                    .collect::<Result<_, _>>()?;
                recast(convex_from_polygon(&r.name, &v, penalty, friction))
            }
            RigidShapeSpec::Triangles {
                vertices,
                triangles,
            } => {
                if D != 3 || triangles.len() < 4 {
                    return Err(check.err(
                        sf,
                        "triangles need a 3d scene and a closed surface (at least 4 triangles)",
                    ));
                }
                let v: Vec<Vector3<f64>> = vertices
                    .iter()
                    .enumerate()
                    .map(|(i, v)| check.vector::<3>(&format!("{sf}.vertices[{i}]"), v))
                    .collect::<Result<_, _>>()?;
                if let Some(t) = triangles
                    .iter()
                    .position(|t| t.iter().any(|&i| i >= v.len()))
                {
                    return Err(
                        check.err(format!("{sf}.triangles[{t}]"), "vertex index out of range")
                    );
                }
                recast(convex_from_triangles(
                    &r.name, &v, triangles, penalty, friction,
                ))
            }
        };
        if let Some(n) = r.search_interval {
            if n == 0 {
                return Err(check.err(format!("{field}.search_interval"), "must be at least 1"));
            }
            body.search_interval = n;
        }
        let mut motion = Motion::default();
        if let Some(t) = &r.translation {
            let knots = t
                .iter()
                .enumerate()
                .map(|(i, row)| {
                    if row.len() != D + 1 {
                        return Err(check.err(
                            format!("{field}.translation[{i}]"),
                            format!("needs [t, {D} displacements]"),
                        ));
                    }
                    Ok((
                        row[0],
                        check.vector::<D>(&format!("{field}.translation[{i}]"), &row[1..])?,
                    ))
                })
                .collect::<Result<Vec<_>, _>>()?;
            if knots.is_empty() || knots.windows(2).any(|w| w[1].0 <= w[0].0) {
                return Err(check.err(
                    format!("{field}.translation"),
                    "needs knots with increasing times",
                ));
            }
            motion.translation = Some(Table { knots });
        }
        if let Some(rot) = &r.rotation {
            let axis: Vector3<f64> = check.vector(&format!("{field}.rotation.axis"), &rot.axis)?;
            if axis.norm() == 0.0 || (D == 2 && (axis[0] != 0.0 || axis[1] != 0.0)) {
                return Err(check.err(
                    format!("{field}.rotation.axis"),
                    "must be non-zero (and along z in 2D)",
                ));
            }
            let center: Vector3<f64> =
                check.vector(&format!("{field}.rotation.center"), &rot.center)?;
            let knots: Vec<(f64, f64)> = rot.angle.iter().map(|k| (k[0], k[1])).collect();
            if knots.is_empty() || knots.windows(2).any(|w| w[1].0 <= w[0].0) {
                return Err(check.err(
                    format!("{field}.rotation.angle"),
                    "needs [t, angle] knots with increasing times",
                ));
            }
            motion.rotation = Some(Rotation {
                center,
                axis: Unit::new_normalize(axis),
                angle: Table { knots },
            });
        }
        body.motion = motion;
        solver.add_rigid_body(body);
    }

    let shifted = solver
        .settings
        .grid_shift
        .is_some_and(|(a, _)| a.iter().any(|x| *x > 0.0));
    for (k, bc) in spec.velocity_bcs.iter().enumerate() {
        let field = format!("velocity_bcs[{k}]");
        let n = &bc.nodes;
        let nodes = match (&n.plane, &n.below, &n.above) {
            (Some(a), None, None) => NodeSet::Plane {
                axis: check.axis::<D>(&format!("{field}.nodes.plane"), a)?,
                at: n.at,
            },
            (None, Some(a), None) => NodeSet::Below {
                axis: check.axis::<D>(&format!("{field}.nodes.below"), a)?,
                at: n.at,
            },
            (None, None, Some(a)) => NodeSet::Above {
                axis: check.axis::<D>(&format!("{field}.nodes.above"), a)?,
                at: n.at,
            },
            _ => {
                return Err(check.err(
                    format!("{field}.nodes"),
                    "give exactly one of plane, below, above",
                ))
            }
        };
        let values = bc.value.clone().unwrap_or(vec![0.0; bc.fixed.len()]);
        if values.len() != bc.fixed.len() {
            return Err(check.err(format!("{field}.value"), "needs one value per fixed axis"));
        }
        let mut velocity = [None; D];
        for (a, v) in bc.fixed.iter().zip(values) {
            velocity[check.axis::<D>(&format!("{field}.fixed"), a)?] = Some(v);
        }
        if bc.one_sided && matches!(nodes, NodeSet::Plane { .. }) {
            return Err(check.err(
                format!("{field}.one_sided"),
                "a one-sided wall needs `below` or `above` nodes (the side the body is not on)",
            ));
        }
        if shifted {
            return Err(check.err(
                field.to_string(),
                "velocity conditions act on grid nodes, and the grid shift (grid.shift) moves \
                 the nodes off the plane, so the wall would move with the grid; use [[springs]] \
                 (eq. 12.1) or a rigid half-space in [[rigid_bodies]] instead",
            ));
        }
        solver.velocity_bcs.push(VelocityBc {
            nodes,
            velocity,
            one_sided: bc.one_sided,
        });
    }

    let inside = |solver: &Solver<D>, lo: SVector<f64, D>, hi: SVector<f64, D>| -> Vec<usize> {
        (0..solver.particles.len())
            .filter(|&i| (0..D).all(|k| (lo[k]..=hi[k]).contains(&solver.particles.position[i][k])))
            .collect()
    };
    for (k, s) in spec.springs.iter().enumerate() {
        let field = format!("springs[{k}]");
        let (lo, hi) = check.boxed::<D>(&format!("{field}.region"), &s.region)?;
        let mut directions = [false; D];
        for a in &s.directions {
            directions[check.axis::<D>(&format!("{field}.directions"), a)?] = true;
        }
        let particles = inside(&solver, lo, hi);
        if particles.is_empty() {
            return Err(check.err(format!("{field}.region"), "holds no particle"));
        }
        solver.springs.push(SpringBc {
            particles,
            directions,
            stiffness: check.positive(&format!("{field}.stiffness"), s.stiffness)?,
        });
    }
    for (k, t) in spec.tractions.iter().enumerate() {
        let field = format!("tractions[{k}]");
        let (lo, hi) = check.boxed::<D>(&format!("{field}.region"), &t.region)?;
        let particles = inside(&solver, lo, hi);
        if particles.is_empty() {
            return Err(check.err(format!("{field}.region"), "holds no particle"));
        }
        let force = check.vector(&format!("{field}.force"), &t.force)?;
        solver.add_traction(&particles, force);
    }
    for (k, c) in spec.control_points.iter().enumerate() {
        let x = check.vector(&format!("control_points[{k}].position"), &c.position)?;
        let p = solver.nearest_particle(&x);
        solver.control_points.push((c.name.clone(), p));
    }
    if solver.particles.is_empty() {
        return Err(check.err("bodies", "the scene has no particles"));
    }
    Ok(solver)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenes() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/scenes")
    }

    #[test]
    fn every_shipped_scene_loads() {
        let mut count = 0;
        for entry in std::fs::read_dir(scenes()).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                load(&path).unwrap_or_else(|e| panic!("{e}"));
                count += 1;
            }
        }
        assert!(count >= 9, "{count} scenes");
    }

    #[test]
    fn errors_name_the_field() {
        let dir = std::env::temp_dir().join("mpw_scene_test");
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.toml");
        let text = std::fs::read_to_string(scenes().join("colliding_disks.toml")).unwrap();
        std::fs::write(
            &path,
            text.replace(
                "radius = 0.2 }\nvelocity = [-0.1",
                "radius = -0.2 }\nvelocity = [-0.1",
            ),
        )
        .unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(e.contains("bodies[1].shape.radius"), "{e}");
        std::fs::write(
            &path,
            text.replace("spacing = 0.05", "spacing = 0.05\nspaceing = 1"),
        )
        .unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(e.contains("spaceing"), "{e}");
    }

    /// The shipped axisymmetric Taylor scene with its material path made absolute, to be
    /// written elsewhere with a change.
    fn axisymmetric_taylor_text() -> String {
        std::fs::read_to_string(scenes().join("taylor_bar_axisymmetric.toml"))
            .unwrap()
            .replace(
                "../materials/",
                &format!("{}/", scenes().join("../materials").display()),
            )
    }

    #[test]
    fn walls_need_a_side_and_do_not_move_with_the_grid_shift() {
        let dir = std::env::temp_dir().join("mpw_scene_wall_test");
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.toml");
        let text = axisymmetric_taylor_text();
        std::fs::write(&path, text.replace("below = \"y\"", "plane = \"y\"")).unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(e.contains("velocity_bcs[0].one_sided"), "{e}");
        let shifted = text.replace("[time]", "shift = [0.0, 1e-5]\n\n[time]");
        std::fs::write(&path, shifted).unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(
            e.contains("velocity_bcs[0]") && e.contains("springs"),
            "{e}"
        );
    }

    /// The shipped Taylor bars carry exactly the bar's mass ρ π R² L (the 3D cylinder's
    /// lattice fill had +3.45 % at 4 cells across the radius, issue 8), and an
    /// axisymmetric body across the axis is rejected.
    #[test]
    fn bodies_carry_exactly_their_mass_and_stay_off_the_negative_radius() {
        let (radius, length) = (0.00381, 0.0254);
        let bar = 8960.0 * std::f64::consts::PI * radius * radius * length;
        let axi = load(&scenes().join("taylor_bar_axisymmetric.toml")).unwrap();
        let solid = load(&scenes().join("taylor_bar_3d.toml")).unwrap();
        for m in [axi, solid].map(|scene| match scene.simulation {
            Simulation::Planar(s) => s.particles.mass.iter().sum::<f64>(),
            Simulation::Solid(s) => s.particles.mass.iter().sum::<f64>(),
        }) {
            assert!((m / bar - 1.0).abs() < 1e-10, "{m} vs {bar}");
        }
        let dir = std::env::temp_dir().join("mpw_scene_axis_test");
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.toml");
        let text = axisymmetric_taylor_text();
        std::fs::write(
            &path,
            text.replace("min = [0.0, 0.0]", "min = [-0.001, 0.0]"),
        )
        .unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(e.contains("bodies[0].shape") && e.contains("r ≥ 0"), "{e}");
    }

    #[test]
    fn a_scene_runs_and_writes_history_and_snapshots() {
        let dir = std::env::temp_dir().join("mpw_run_test");
        let _ = std::fs::remove_dir_all(&dir);
        let mut scene = load(&scenes().join("single_particle.toml")).unwrap();
        scene.end = 1.0;
        let summary = crate::run::run_scene(scene, &dir, |_| {}, |_, _| {}).unwrap();
        assert!(summary.failure.is_none());
        assert_eq!(summary.steps, 63);
        let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
        assert_eq!(history.lines().count(), 1 + 1 + 63);
        let snapshot = std::fs::read(dir.join("snapshot_00010.vtk")).unwrap();
        assert!(snapshot.starts_with(b"# vtk DataFile"));
    }
    /// Sizes derived from a scene are bounded before anything of that size is allocated
    /// (issue 16): a spacing of 1 nm on the colliding disks (4e17 points) is an error that
    /// names the body; an end time of 1e30 s stops at step 0 naming `time.end`; a point
    /// thrown 1e12 m away (2e13 cells) stops the run instead of allocating the grid.
    #[test]
    fn sizes_from_a_scene_are_bounded_before_allocation() {
        let dir = std::env::temp_dir().join("mpw_scene_limits_test");
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.toml");
        let text = std::fs::read_to_string(scenes().join("colliding_disks.toml")).unwrap();
        std::fs::write(&path, text.replace("spacing = 0.05", "spacing = 1e-9")).unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(
            e.contains("bodies[0].shape") && e.contains("material points"),
            "{e}"
        );
        std::fs::write(&path, text.replace("end = 3.5", "end = 1e30")).unwrap();
        let summary = crate::run::run_scene(load(&path).unwrap(), &dir, |_| {}, |_, _| {}).unwrap();
        let failure = summary.failure.unwrap();
        assert_eq!(summary.steps, 0);
        assert!(
            matches!(failure.cause, crate::Cause::TooManySteps(_)),
            "{failure}"
        );
        assert!(failure.to_string().contains("time.end = 1e30"), "{failure}");
        // the failure keeps its output, as any other (mpw simulate charts the history)
        let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
        assert_eq!(history.lines().count(), 1 + 2);
        let mut scene = load(&scenes().join("colliding_disks.toml")).unwrap();
        let Simulation::Planar(solver) = &mut scene.simulation else {
            unreachable!()
        };
        solver.initialize();
        solver.particles.position[0][1] = 1e12;
        let e = solver.step().unwrap_err();
        assert!(matches!(e.cause, crate::Cause::GridTooLarge(_)), "{e}");
    }
}
