//! The model description: serde types for the whole scene (grid, time, solver, materials
//! by file or inline, bodies, rigid bodies and their motions, conditions, control points,
//! output). They load from TOML, serialize back to it, and can be built and changed in
//! code; `scene::build` checks every value and discretizes. Units SI.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
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
    /// (t [s], factor [-]) samples scaling every traction over time.
    pub traction_history: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    pub control_points: Vec<ControlPointSpec>,
    #[serde(default)]
    pub output: OutputSpec,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    pub spacing: f64,
    pub origin: Option<Vec<f64>>,
    pub shift: Option<Vec<f64>>,
    #[serde(default)]
    pub seed: u64,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    pub end: f64,
    pub dt: Option<f64>,
    pub safety: Option<f64>,
    pub scheme: Option<String>,
}

#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    pub damping: Option<f64>,
    pub mass_cutoff: Option<f64>,
    pub body_force: Option<Vec<f64>>,
    pub domain: Option<BoxSpec>,
    pub blowup_factor: Option<f64>,
    pub bulk_viscosity: Option<[f64; 2]>,
    /// Fraction of PIC in the points' velocity update, 0 to 1 (default 0).
    pub pic_fraction: Option<f64>,
    /// A kernel of `shape::ShapeFunction::NAMES` (default "cpdi", `SCENE_DEFAULT`).
    pub shape_function: Option<String>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    pub min: Vec<f64>,
    pub max: Vec<f64>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NeoHookeSpec {
    #[serde(rename = "E")]
    pub e: f64,
    pub nu: f64,
    pub rho: f64,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub name: String,
    /// A parameter file, relative to the scene file.
    pub file: Option<String>,
    pub neo_hooke: Option<NeoHookeSpec>,
    /// The contents of a parameter file, inline (`model = "johnson-cook"`, `[elastic]`, ...).
    pub parameters: Option<toml::Table>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
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
    /// A quadrilateral / hexahedral mesh file (module `mesh`), relative to the scene
    /// file: one point per element.
    Mesh {
        file: String,
    },
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub name: String,
    pub material: String,
    pub shape: ShapeSpec,
    #[serde(default = "two")]
    pub particles_per_cell: usize,
    /// A box filled with exactly this many points along each axis (spacing = edge / count,
    /// as the thesis counts n_x × n_y), instead of `particles_per_cell`.
    pub points: Option<Vec<usize>>,
    pub velocity: Option<Vec<f64>>,
    /// This body's kernel (`shape::ShapeFunction::NAMES`); default the scene's.
    pub shape_function: Option<String>,
}

fn two() -> usize {
    2
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
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

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RotationSpec {
    pub center: Vec<f64>,
    pub axis: Vec<f64>,
    /// (t [s], angle [rad]) knots.
    pub angle: Vec<[f64; 2]>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
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

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSetSpec {
    pub plane: Option<String>,
    pub below: Option<String>,
    pub above: Option<String>,
    /// The coordinate of `plane`, `below` or `above` [m].
    pub at: Option<f64>,
    /// The nodes inside an axis-aligned box (a support under part of a body).
    pub inside: Option<BoxSpec>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct VelocityBcSpec {
    pub nodes: NodeSetSpec,
    pub fixed: Vec<String>,
    pub value: Option<Vec<f64>>,
    #[serde(default)]
    pub one_sided: bool,
    /// (t [s], factor [-]) samples scaling `value` over time.
    pub history: Option<Vec<[f64; 2]>>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSpec {
    pub region: BoxSpec,
    pub directions: Vec<String>,
    pub stiffness: f64,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    pub region: BoxSpec,
    pub force: Vec<f64>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ControlPointSpec {
    pub name: String,
    pub position: Vec<f64>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    #[serde(default = "one")]
    pub history_every: usize,
    #[serde(default = "ten")]
    pub snapshots: usize,
    /// Material parameters to carry exact derivatives along (`solver::Tangent`): the
    /// control points' sensitivities go to `derivatives.csv`. Empty: none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub derivatives: Vec<String>,
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
            derivatives: Vec::new(),
        }
    }
}
