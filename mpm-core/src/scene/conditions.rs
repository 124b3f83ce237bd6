//! Conditions and probes of a scene: grid velocity conditions (module `boundary`), with an
//! optional time history; springs and tractions on the particles of a region; control
//! points (the particle nearest to a position).

use super::check::Check;
use super::spec::SceneFile;
use super::SceneError;
use crate::boundary::{NodeSet, SpringBc, VelocityBc};
use crate::solver::Solver;
use materials::signal::TimeSignal;
use nalgebra::SVector;
use std::sync::Arc;

pub(super) fn add_velocity_bcs<const D: usize>(
    solver: &mut Solver<D>,
    spec: &SceneFile,
    check: &Check,
) -> Result<(), SceneError> {
    let shifted = solver
        .settings
        .grid_shift
        .is_some_and(|(a, _)| a.iter().any(|x| *x > 0.0));
    for (k, bc) in spec.velocity_bcs.iter().enumerate() {
        let field = format!("velocity_bcs[{k}]");
        let n = &bc.nodes;
        let at = || {
            n.at.ok_or_else(|| {
                check.err(
                    format!("{field}.nodes.at"),
                    "missing: the coordinate of the plane [m]",
                )
            })
        };
        let nodes = match (&n.plane, &n.below, &n.above, &n.inside) {
            (Some(a), None, None, None) => NodeSet::Plane {
                axis: check.axis::<D>(&format!("{field}.nodes.plane"), a)?,
                at: at()?,
            },
            (None, Some(a), None, None) => NodeSet::Below {
                axis: check.axis::<D>(&format!("{field}.nodes.below"), a)?,
                at: at()?,
            },
            (None, None, Some(a), None) => NodeSet::Above {
                axis: check.axis::<D>(&format!("{field}.nodes.above"), a)?,
                at: at()?,
            },
            (None, None, None, Some(b)) if n.at.is_none() => {
                let (min, max) = check.boxed::<D>(&format!("{field}.nodes.inside"), b)?;
                NodeSet::Inside { min, max }
            }
            _ => return Err(check.err(
                format!("{field}.nodes"),
                "give exactly one of plane, below, above (each with at), or inside = {min, max}",
            )),
        };
        let values = bc.value.clone().unwrap_or(vec![0.0; bc.fixed.len()]);
        if values.len() != bc.fixed.len() {
            return Err(check.err(format!("{field}.value"), "needs one value per fixed axis"));
        }
        let mut velocity = [None; D];
        for (a, v) in bc.fixed.iter().zip(values) {
            velocity[check.axis::<D>(&format!("{field}.fixed"), a)?] = Some(v);
        }
        if bc.one_sided && matches!(nodes, NodeSet::Plane { .. } | NodeSet::Inside { .. }) {
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
        let history = match &bc.history {
            None => None,
            Some(h) => Some(
                TimeSignal::from_samples(h.iter().map(|k| (k[0], k[1])))
                    .map_err(|e| check.err(format!("{field}.history"), e.to_string()))?,
            ),
        };
        solver.velocity_bcs.push(VelocityBc {
            nodes,
            velocity,
            one_sided: bc.one_sided,
            history,
        });
    }
    Ok(())
}

pub(super) fn add_springs_and_tractions<const D: usize>(
    solver: &mut Solver<D>,
    spec: &SceneFile,
    check: &Check,
) -> Result<(), SceneError> {
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
        let particles = inside(solver, lo, hi);
        if particles.is_empty() {
            return Err(check.err(format!("{field}.region"), "holds no particle"));
        }
        solver.add_condition(Arc::new(SpringBc {
            particles,
            directions,
            stiffness: check.positive(&format!("{field}.stiffness"), s.stiffness)?,
        }));
    }
    for (k, t) in spec.tractions.iter().enumerate() {
        let field = format!("tractions[{k}]");
        let (lo, hi) = check.boxed::<D>(&format!("{field}.region"), &t.region)?;
        let particles = inside(solver, lo, hi);
        if particles.is_empty() {
            return Err(check.err(format!("{field}.region"), "holds no particle"));
        }
        let force = check.vector(&format!("{field}.force"), &t.force)?;
        solver.add_traction(&particles, force);
    }
    if let Some(h) = &spec.traction_history {
        let signal = TimeSignal::from_samples(h.iter().map(|k| (k[0], k[1])))
            .map_err(|e| check.err("traction_history", e.to_string()))?;
        solver.traction_history = Some(signal);
    }
    Ok(())
}

pub(super) fn add_control_points<const D: usize>(
    solver: &mut Solver<D>,
    spec: &SceneFile,
    check: &Check,
) -> Result<(), SceneError> {
    for (k, c) in spec.control_points.iter().enumerate() {
        let x = check.vector(&format!("control_points[{k}].position"), &c.position)?;
        let p = solver.nearest_particle(&x);
        solver.control_points.push((c.name.clone(), p));
    }
    Ok(())
}
