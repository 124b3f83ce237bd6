//! Bodies of a scene: a primitive shape filled with material points (module
//! `discretize`) or a mesh with one point per element (module `mesh`), its material and
//! initial velocity, the particle budget checked first.

use super::check::Check;
use super::spec::{BodySpec, SceneFile, ShapeSpec};
use super::SceneError;
use crate::discretize::{fill, Geometry};
use crate::kinematics::Kinematics;
use crate::limits::PARTICLES;
use crate::mesh::{self, MeshPoint};
use crate::shape::ShapeFunction;
use crate::solver::Solver;
use materials::{AnyModel, Material};
use nalgebra::SVector;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// The shape of body `b` (field `field`) checked against the scene's dimension.
fn shape<const D: usize>(
    b: &BodySpec,
    field: &str,
    check: &Check,
) -> Result<Geometry<D>, SceneError> {
    let sf = format!("{field}.shape");
    let shape = match &b.shape {
        ShapeSpec::Box { min, max } => {
            let (min, max) = check.corners::<D>(&sf, min, max)?;
            Geometry::Box { min, max }
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
            Geometry::Ball {
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
            Geometry::Cylinder {
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
            Geometry::Polygon { vertices }
        }
        ShapeSpec::Mesh { .. } => unreachable!("mesh bodies are read by `mesh_points`"),
    };
    Ok(shape)
}

/// The points of a mesh body (module `mesh`), its file relative to the scene's.
fn mesh_points<const D: usize>(
    file: &str,
    kinematics: Kinematics,
    check: &Check,
) -> Result<Vec<MeshPoint<D>>, SceneError> {
    let path = check.file.parent().unwrap_or(Path::new(".")).join(file);
    let mesh = mesh::read::<D>(&path).map_err(SceneError::Mesh)?;
    mesh::points(&mesh, kinematics).map_err(SceneError::Mesh)
}

pub(super) fn add_bodies<const D: usize>(
    solver: &mut Solver<D>,
    spec: &SceneFile,
    check: &Check,
    materials: &HashMap<&str, AnyModel>,
) -> Result<(), SceneError> {
    let (h, kinematics) = (solver.settings.spacing, solver.settings.kinematics);
    let mut particles = 0.0;
    for (k, b) in spec.bodies.iter().enumerate() {
        let field = format!("bodies[{k}]");
        let model = materials.get(b.material.as_str()).ok_or_else(|| {
            check.err(
                format!("{field}.material"),
                format!("no material named `{}`", b.material),
            )
        })?;
        let material: Arc<dyn Material> = Arc::new(*model);
        let sf = format!("{field}.shape");
        let velocity = b
            .velocity
            .as_ref()
            .map(|v| check.vector::<D>(&format!("{field}.velocity"), v))
            .transpose()?
            .unwrap_or(SVector::zeros());
        let kernel = (b.shape_function.as_deref())
            .map(str::parse::<ShapeFunction>)
            .transpose()
            .map_err(|e| check.err(format!("{field}.shape_function"), e))?;
        if let ShapeSpec::Mesh { file } = &b.shape {
            let points = mesh_points::<D>(file, kinematics, check)?;
            particles += points.len() as f64;
            PARTICLES
                .check(particles, || {
                    format!("the mesh {file} has {} elements", points.len())
                })
                .map_err(|e| check.err(sf.clone(), e.to_string()))?;
            let r_min = (points.iter())
                .map(|p| p.0[0] - p.2.half_extent()[0])
                .fold(f64::INFINITY, f64::min);
            if kinematics == Kinematics::Axisymmetric && r_min < 0.0 {
                return Err(check.err(
                    sf,
                    format!(
                        "an element reaches r = {r_min} m < 0: an axisymmetric body lies in r ≥ 0"
                    ),
                ));
            }
            let block = solver.add_mesh_body(&b.name, material, &points, velocity);
            solver.blocks[block].shape_function = kernel;
            continue;
        }
        let shape = shape::<D>(b, &field, check)?;
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
        let s = match (&b.points, &shape) {
            (None, _) => h / b.particles_per_cell as f64,
            (Some(n), Geometry::Box { min, max }) if n.len() == D && n.iter().all(|&k| k > 0) => {
                SVector::from_fn(|i, _| (max[i] - min[i]) / n[i] as f64)
            }
            (Some(_), Geometry::Box { .. }) => {
                return Err(check.err(
                    format!("{field}.points"),
                    format!("expected {D} positive counts, one per axis"),
                ))
            }
            (Some(_), _) => return Err(check.err(format!("{field}.points"), "is for box shapes")),
        };
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
        let block = solver.add_body(&b.name, material, &points, velocity);
        solver.blocks[block].shape_function = kernel;
        if solver.kernel_of(block).needs_domains() {
            solver.set_half_size(block, s * 0.5);
        }
    }
    Ok(())
}
