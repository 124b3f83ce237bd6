//! What both cuts share: how a run goes (`RunOptions`), and the plane-strain scene of a
//! rectangular workpiece filled with exactly n_x × n_y points (the thesis's count), on a
//! grid whose origin is the workpiece's corner (nodes on its boundaries), shifted by dx/2
//! every step or not. Each cut adds its tool and its conditions.

use mpm_core::scene::spec::{
    BodySpec, GridSpec, MaterialSpec, OutputSpec, SceneFile, ShapeSpec, SolverSpec, TimeSpec,
};

/// How one cut runs.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOptions {
    /// The points' shape functions (`mpm_core::shape::ShapeFunction::NAMES`).
    pub shape_function: String,
    /// A fixed time step [s]; `None`: the solver's stability limit times `safety`.
    pub dt: Option<f64>,
    pub safety: f64,
    /// Seed of the grid shift.
    pub seed: u64,
    /// History rows every this many steps; snapshots over the run.
    pub history_every: usize,
    pub snapshots: usize,
    /// The material file, as the scene names it (relative to the scene's folder).
    pub material_file: String,
    /// Material parameters to carry exact derivatives along (scene key
    /// `output.derivatives`; none: a plain run).
    pub derivatives: Vec<String>,
}

impl RunOptions {
    /// Linear shape functions, the solver's time step at safety 0.5, seed 1, a history
    /// row every 10 steps, 12 snapshots, with `material_file`, no derivatives.
    pub fn new(material_file: impl Into<String>) -> Self {
        RunOptions {
            shape_function: "linear".into(),
            dt: None,
            safety: 0.5,
            seed: 1,
            history_every: 10,
            snapshots: 12,
            material_file: material_file.into(),
            derivatives: Vec::new(),
        }
    }
}

/// The workpiece: its material's and body's names, size [m] and points along x and y.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Workpiece<'a> {
    pub material: &'a str,
    pub body: &'a str,
    pub size: [f64; 2],
    pub points: [usize; 2],
}

/// The scene of `workpiece` on a grid of `spacing` [m], shifted by dx/2 every step when
/// `shift`, run to `end` [s] with `options`; no tool and no conditions yet.
pub fn scene(
    workpiece: &Workpiece,
    spacing: f64,
    shift: bool,
    end: f64,
    options: &RunOptions,
) -> SceneFile {
    SceneFile {
        kinematics: "plane-strain".into(),
        grid: GridSpec {
            spacing,
            origin: Some(vec![0.0, 0.0]),
            shift: shift.then(|| vec![0.5 * spacing; 2]),
            seed: options.seed,
        },
        time: TimeSpec {
            end,
            dt: options.dt,
            safety: Some(options.safety),
            scheme: None,
        },
        solver: SolverSpec {
            shape_function: Some(options.shape_function.clone()),
            ..SolverSpec::default()
        },
        materials: vec![MaterialSpec {
            name: workpiece.material.into(),
            file: Some(options.material_file.clone()),
            neo_hooke: None,
            parameters: None,
        }],
        bodies: vec![BodySpec {
            name: workpiece.body.into(),
            material: workpiece.material.into(),
            shape: ShapeSpec::Box {
                min: vec![0.0, 0.0],
                max: workpiece.size.to_vec(),
            },
            particles_per_cell: 2,
            points: Some(workpiece.points.to_vec()),
            velocity: None,
            shape_function: None,
        }],
        rigid_bodies: Vec::new(),
        velocity_bcs: Vec::new(),
        springs: Vec::new(),
        tractions: Vec::new(),
        traction_history: None,
        control_points: Vec::new(),
        output: OutputSpec {
            history_every: options.history_every,
            snapshots: options.snapshots,
            derivatives: options.derivatives.clone(),
        },
    }
}
