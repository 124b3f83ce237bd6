//! Derivatives of penalty contact with rigid bodies of prescribed motion (eq. 9.3-9.7):
//! the force on a point in contact, f = κ (X_A − X), depends on the parameters through
//! the point's x and F (the nearest point of its domain) and through the attachment
//! point X_A, which the pass carries from step to step with its derivatives. The loads
//! go to the grid as in the run (`surface_loads::load_shares`), and the body's total
//! force, the observed face force of an SHPB model, is their sum.
//!
//! Whether a point touches and whether it sticks or slides follow the run.

use super::{join_all, Dual, Tangent};
use crate::contact::{candidate_force, Candidate, ContactForce};
use crate::solver::surface_loads::load_shares;
use crate::solver::Solver;
use nalgebra::SVector;

/// A contact force on point `particle` with its derivatives, acting at `at` [m].
pub(super) struct DualLoad<const D: usize, const P: usize> {
    particle: usize,
    at: SVector<Dual<P>, D>,
    force: SVector<Dual<P>, D>,
}

impl<const D: usize, const P: usize> Tangent<D, P> {
    /// After the contact stage (which searched the candidates): every body's forces on
    /// the points in contact with their derivatives, the attachment points carried on.
    pub(super) fn contact(&mut self, s: &Solver<D>) {
        self.loads.clear();
        let n = s.particles.len();
        for (b, rc) in s.rigid.iter().enumerate() {
            let pose = rc.body.motion.pose(s.time);
            let mut old = std::mem::replace(&mut self.attachment[b], vec![None; n]);
            let mut total = SVector::zeros();
            let c = &rc.contact;
            for (&i, real) in c.candidates.iter().zip(&c.attachment) {
                let (x, f) = (self.position(s, i), self.deformation(s, i));
                let point = Candidate {
                    x: &x,
                    mass: s.particles.mass[i],
                    f: &f,
                    half_size: &s.particles.half_size[i],
                };
                let attachment = &mut old[i];
                let force = candidate_force(&rc.body, &pose, point, attachment);
                debug_assert_eq!(force.is_some(), real.is_some(), "contact of point {i}");
                if let (Some(ContactForce { force, at }), Some(real), Some(dual)) =
                    (force, real.as_ref(), attachment.as_ref())
                {
                    self.attachment[b][i] = Some(join_all(real, dual));
                    self.loads.push(DualLoad {
                        particle: i,
                        at,
                        force,
                    });
                    total -= force;
                }
            }
            self.contact_force[b] = total;
        }
    }

    /// Add the contact loads to the nodal forces (after the point forces of a force map),
    /// shared among the nodes as the run shares them.
    pub(super) fn add_surface_loads(&mut self, s: &Solver<D>) {
        let mut shares = Vec::new();
        for load in &self.loads {
            let real = s.scratch.weights.stencil(load.particle);
            let (node, weight, _) = self.stencils.of(load.particle);
            let own = real.node.iter().map(|&m| {
                let entries = node.iter().zip(weight).filter(|(k, _)| **k == m);
                let n = entries.fold(Dual::from_re(0.0), |sum, (_, w)| sum + w);
                (m as usize, n)
            });
            shares.clear();
            load_shares(&s.grid, s.mass_cutoff, &load.at, own, &mut shares);
            for &(m, w) in &shares {
                self.nodes[m].force += load.force * w;
            }
        }
    }

    /// Total contact force on rigid body `body` at the current step (world frame) [N]
    /// with its derivatives.
    pub fn contact_force(&self, s: &Solver<D>, body: usize) -> SVector<Dual<P>, D> {
        join_all(&s.rigid[body].contact.force, &self.contact_force[body])
    }
}
