//! Derivatives of penalty contact with rigid bodies of prescribed motion (eq. 9.3-9.7):
//! the force on a point in contact, f = κ (X_A − X), depends on the parameters through
//! the point's x and F (the nearest point of its domain) and through the attachment
//! point X_A, which the pass carries from step to step with its derivatives. The loads
//! go to the grid as in the run (`surface_loads::load_shares`), and the body's total
//! force, the observed face force of an SHPB model, is their sum.
//!
//! A face on an elastic bar (module `bar`) moves along its axis e with
//! v = (2 c0 ε_in − f/Z + (k_c Δt/Z) v_s) / (1 + k_c Δt/Z), so its displacement u carries
//! the derivatives of the compressive face force f and of the springs' mean velocity
//! v_s = Σ k_i v_i·e / Σ k_i (k_c and the springs in contact follow the run):
//! du ← du + Δt (−df/Z + (k_c Δt/Z) dv_s) / (1 + k_c Δt/Z). The face's pose moves by
//! du e, which the contact sees as the points moved back by it.
//!
//! Whether a point touches and whether it sticks or slides follow the run.

use super::{join, join_all, Dual, Tangent};
use crate::contact::{candidate_force, Candidate, ContactForce};
use crate::solver::surface_loads::load_shares;
use crate::solver::Solver;
use materials::scalar::c;
use nalgebra::SVector;

/// The derivatives of a face's state on its elastic bar (dual parts only).
#[derive(Clone, Copy)]
pub(super) struct FaceDerivatives<const P: usize> {
    /// Displacement u along the bar's axis [m].
    displacement: Dual<P>,
    /// Mean velocity v_s of the points in contact along the axis [m/s].
    springs_velocity: Dual<P>,
}

impl<const P: usize> FaceDerivatives<P> {
    /// A face at rest, or a body of prescribed motion.
    pub(super) fn at_rest() -> Self {
        FaceDerivatives {
            displacement: Dual::from_re(0.0),
            springs_velocity: Dual::from_re(0.0),
        }
    }
}

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
            let bar_axis = rc
                .body
                .motion
                .bar
                .as_ref()
                .map(|bar| bar.axis.map(c::<Dual<P>>));
            // the face's translation with its derivatives is its real pose's plus `shift`
            let shift =
                bar_axis.clone().unwrap_or_else(SVector::zeros) * self.faces[b].displacement;
            let mut old = std::mem::replace(&mut self.attachment[b], vec![None; n]);
            let mut total = SVector::zeros();
            let (mut stiffness, mut springs_velocity) = (0.0, Dual::from_re(0.0));
            let c = &rc.contact;
            for (&i, real) in c.candidates.iter().zip(&c.attachment) {
                let (x, f) = (self.position(s, i) - &shift, self.deformation(s, i));
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
                        at: at + &shift,
                        force,
                    });
                    total -= force;
                    if let Some(axis) = &bar_axis {
                        let k = rc.body.penalty_of(s.particles.mass[i]);
                        stiffness += k;
                        springs_velocity += self.velocity(s, i).dot(axis) * k;
                    }
                }
            }
            self.contact_force[b] = total;
            self.faces[b].springs_velocity = match stiffness > 0.0 {
                true => springs_velocity / stiffness,
                false => Dual::from_re(0.0),
            };
        }
    }

    /// After the bar faces moved: the derivatives of each face's displacement (module
    /// notes), from its contact force and springs of this step.
    pub(super) fn bar_faces(&mut self, s: &Solver<D>) {
        for (b, rc) in s.rigid.iter().enumerate() {
            let Some(bar) = &rc.body.motion.bar else {
                continue;
            };
            let z = bar.impedance();
            let implicit = rc.contact.springs.stiffness * s.dt / z;
            let axis = bar.axis.map(c::<Dual<P>>);
            let face = &mut self.faces[b];
            let force = -self.contact_force[b].dot(&axis);
            let velocity = (-force / z + face.springs_velocity * implicit) / (1.0 + implicit);
            face.displacement = join(0.0, face.displacement + velocity * s.dt);
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
