//! Forces on the points from outside the continuum, three stages of a step:
//! - `AppliedForces`: applied (traction) forces times the load factor of
//!   `traction_history` at t_n, then the forces of every registered point condition
//!   (boundary springs, eq. 12.1), in the order registered;
//! - `ContactForces`: penalty contact with every rigid body (eq. 9.2-9.7), as surface
//!   loads (module `surface_loads`). Candidates are searched every `search_interval`
//!   steps within a margin that covers the travel of points and body until the next
//!   search;
//! - `BarFaces`: a face on an elastic bar moves with its contact force and the penalty
//!   springs of the points pressing on it (module `bar`).

use super::surface_loads::SurfaceLoad;
use super::Solver;
use crate::bar::ContactSprings;
use crate::contact::{candidate_force, Candidate, ContactForce};
use crate::parallel;
use nalgebra::SVector;
use rayon::prelude::*;

impl<const D: usize> Solver<D> {
    /// Applied forces times the load factor at t_n, then every point condition's forces.
    pub(super) fn applied_forces(&mut self) {
        let p = &self.particles;
        let factor = self
            .traction_history
            .as_ref()
            .map_or(1.0, |h| h.at(self.time));
        for (f, applied) in self.scratch.force.iter_mut().zip(&p.applied_force) {
            *f = applied * factor;
        }
        for condition in &self.conditions {
            condition.add_forces(self.time, p, &mut self.scratch.force);
        }
    }

    /// Penalty contact forces (eq. 9.2-9.7) of every rigid body on the points, as surface
    /// loads, with each body's total force and, for a bar-driven face, the springs of the
    /// points pressing on it.
    pub(super) fn contact_forces(&mut self) {
        let p = &self.particles;
        self.scratch.loads.clear();
        let (t, dt, step, h) = (self.time, self.dt, self.step, self.grid.min_spacing());
        // the fastest point, for the search margin: only computed when a search is due
        let mut max_speed = None;
        for rc in &mut self.rigid {
            let body = &rc.body;
            let pose = body.motion.pose(t);
            // a bar-driven face moves with the contact force: searched every step
            let interval = match body.motion.bar {
                Some(_) => 1,
                None => body.search_interval.max(1),
            };
            if step % interval == 0 {
                // margin: particle travel plus body travel until the next search, plus a cell
                let later = body.motion.pose(t + interval as f64 * dt);
                let reach = body.bounds.map_or_else(
                    || {
                        let (lo, hi) = (
                            self.grid.node_position(0),
                            self.grid.node_position(self.grid.nodes.len() - 1),
                        );
                        (hi - lo).norm() + (lo - pose.center).norm()
                    },
                    |(c, r)| (c - pose.center).norm() + r,
                );
                let turn = (later.rotation - pose.rotation).norm();
                let max_speed = *max_speed.get_or_insert_with(|| {
                    let speeds = p.velocity.par_iter();
                    let fastest = |most: f64, v: &SVector<f64, D>| most.max(v.norm());
                    parallel::fold(speeds, parallel::light(p.len()), 0.0, fastest, f64::max)
                });
                let margin = h
                    + 2.0 * interval as f64 * dt * max_speed
                    + (later.translation - pose.translation).norm()
                    + turn * reach;
                let near = |i: usize| {
                    let xb = pose.to_body(&p.position[i]);
                    let near = match body.bounds {
                        Some((c, r)) => (xb - c).norm() < r + margin,
                        None => body.nearest_plane(&xb).0 < margin,
                    };
                    near.then_some(i)
                };
                let points = (0..p.len()).into_par_iter();
                let candidates = parallel::filter_map(points, parallel::light(p.len()), near);
                rc.contact.set_candidates(candidates);
            }
            let c = &mut rc.contact;
            let candidates = c.candidates.par_iter().zip(c.attachment.par_iter_mut());
            let force = |(&i, a): (&usize, &mut _)| {
                let point = Candidate {
                    x: &p.position[i],
                    mass: p.mass[i],
                    f: &p.deformation[i],
                    half_size: &p.half_size[i],
                };
                candidate_force(body, &pose, point, a)
            };
            let cut = parallel::light(p.len());
            let forces = parallel::map(candidates, cut, force);
            c.force = SVector::zeros();
            c.active = 0;
            // the springs a bar-driven face pushes on, along its axis
            let bar_axis = body.motion.bar.as_ref().map(|b| b.axis);
            let mut springs = ContactSprings::default();
            for (&i, f) in c.candidates.iter().zip(&forces) {
                if let Some(ContactForce { force: f, at }) = *f {
                    self.scratch.loads.push(SurfaceLoad {
                        particle: i,
                        at,
                        force: f,
                        weights: 0..0,
                    });
                    c.force -= f;
                    c.active += 1;
                    if let Some(axis) = bar_axis {
                        let k = body.penalty_of(p.mass[i]);
                        springs.stiffness += k;
                        springs.velocity += k * p.velocity[i].dot(&axis);
                    }
                }
            }
            if springs.stiffness > 0.0 {
                springs.velocity /= springs.stiffness;
            }
            c.springs = springs;
        }
    }

    /// Every face on an elastic bar moves with its contact force (compression positive:
    /// the specimen pushes the face against its axis) and its contact springs.
    pub(super) fn bar_faces(&mut self) {
        let (t, dt) = (self.time, self.dt);
        for rc in &mut self.rigid {
            if let Some(bar) = &mut rc.body.motion.bar {
                let c = &rc.contact;
                bar.advance(t, dt, -c.force.dot(&bar.axis), c.springs);
            }
        }
    }
}
