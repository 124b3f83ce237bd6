//! Rigid bodies of a scene: half-spaces, boxes, convex polygons and triangulated convex
//! surfaces (module `rigid`), with penalty, friction, search interval, and a translation
//! and a rotation given as time signals.

use super::check::Check;
use super::spec::{RigidShapeSpec, RigidSpec, SceneFile};
use super::SceneError;
use crate::rigid::{
    convex_from_polygon, convex_from_triangles, recast, Motion, RigidBody, Rotation,
};
use crate::solver::Solver;
use materials::signal::TimeSignal;
use nalgebra::{SVector, Unit, Vector3};

fn rigid_shape<const D: usize>(
    r: &RigidSpec,
    sf: &str,
    (penalty, friction): (f64, f64),
    check: &Check,
) -> Result<RigidBody<D>, SceneError> {
    let sf = sf.to_string();
    let body = match &r.shape {
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
            let (min, max) = check.corners::<D>(&sf, min, max)?;
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
                return Err(check.err(format!("{sf}.triangles[{t}]"), "vertex index out of range"));
            }
            recast(convex_from_triangles(
                &r.name, &v, triangles, penalty, friction,
            ))
        }
    };
    Ok(body)
}

fn motion<const D: usize>(
    r: &RigidSpec,
    field: &str,
    check: &Check,
) -> Result<Motion<D>, SceneError> {
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
        let signal = TimeSignal::from_samples(knots)
            .map_err(|e| check.err(format!("{field}.translation"), e.to_string()))?;
        motion.translation = Some(signal);
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
        let angle = TimeSignal::from_samples(rot.angle.iter().map(|k| (k[0], k[1])))
            .map_err(|e| check.err(format!("{field}.rotation.angle"), e.to_string()))?;
        motion.rotation = Some(Rotation {
            center,
            axis: Unit::new_normalize(axis),
            angle,
        });
    }
    Ok(motion)
}

pub(super) fn add_rigid_bodies<const D: usize>(
    solver: &mut Solver<D>,
    spec: &SceneFile,
    check: &Check,
) -> Result<(), SceneError> {
    for (k, r) in spec.rigid_bodies.iter().enumerate() {
        let field = format!("rigid_bodies[{k}]");
        let penalty = check.positive(&format!("{field}.penalty"), r.penalty)?;
        let friction = check.non_negative(&format!("{field}.friction"), r.friction)?;
        let sf = format!("{field}.shape");
        let mut body = rigid_shape::<D>(r, &sf, (penalty, friction), check)?;
        if let Some(n) = r.search_interval {
            if n == 0 {
                return Err(check.err(format!("{field}.search_interval"), "must be at least 1"));
            }
            body.search_interval = n;
        }
        body.motion = motion::<D>(r, &field, check)?;
        solver.add_rigid_body(body);
    }
    Ok(())
}
