//! Grid solve (algorithm 10): nodal acceleration and velocity from the mapped mass,
//! momentum and force, the node mass cutoff, damping work and the velocity conditions
//! (eq. 7.28, and one-sided walls), whose prescribed values are taken once per step at
//! t_{n+1/2}.

use super::Solver;
use crate::boundary::VelocityBc;
use crate::grid::Node;
use crate::parallel;
use materials::scalar::{c, Scalar};
use nalgebra::SVector;
use rayon::prelude::*;

/// Nodes per parallel work item.
const CHUNK: usize = 2048;

/// Work of one chunk of nodes [J]: damping, prescribed velocities, and the absolute
/// value of the latter.
pub(super) type ChunkWork = (f64, f64, f64);

/// What every node of one grid solve shares.
pub(super) struct NodeSolve<'a, const D: usize> {
    dt: f64,
    alpha: f64,
    cutoff: f64,
    accelerate: bool,
    /// Velocity conditions and their prescribed components this step.
    bcs: Vec<(&'a VelocityBc<D>, [Option<f64>; D])>,
}

impl<'a, const D: usize> NodeSolve<'a, D> {
    /// The grid solve of `update` in the step from `time` over `dt` with damping α_d
    /// `damping` [1/s] and node mass cutoff `cutoff`; velocity conditions take their values
    /// at t_{n+1/2}.
    pub(super) fn new(
        bcs: &'a [VelocityBc<D>],
        (time, dt): (f64, f64),
        damping: f64,
        cutoff: f64,
        update: NodalUpdate,
    ) -> Self {
        let t_half = time + 0.5 * dt;
        NodeSolve {
            dt,
            alpha: damping,
            cutoff,
            accelerate: update == NodalUpdate::Accelerate,
            bcs: bcs.iter().map(|bc| (bc, bc.velocity_at(t_half))).collect(),
        }
    }

    /// a = (f − α_d p)/m and v = p/m + a Δt for a node above the mass cutoff (damping work
    /// into `w.0`), else v = p/m and a = 0; returns p/m. Written for any scalar: the
    /// derivative pass (`tangent`) runs it on dual nodes whose real parts are these.
    #[inline]
    pub(super) fn solve<T: Scalar>(&self, n: &mut Node<D, T>, w: &mut ChunkWork) -> SVector<T, D> {
        let v_old = n.momentum / n.mass;
        if self.accelerate && n.mass.re() > self.cutoff * n.heaviest {
            let damping = n.momentum * c::<T>(self.alpha);
            n.acceleration = (n.force - damping) / n.mass;
            n.velocity = v_old + n.acceleration * c::<T>(self.dt);
            w.0 -= damping.dot(&n.velocity).re() * self.dt;
        } else {
            n.acceleration = SVector::zeros();
            n.velocity = v_old;
        }
        v_old
    }

    /// Velocity conditions at a node at `x` (eq. 7.28; one-sided walls take the
    /// acceleration that brings p/m to v̄), with the work of the reaction impulse.
    #[inline]
    pub(super) fn constrain<T: Scalar>(
        &self,
        n: &mut Node<D, T>,
        x: &SVector<f64, D>,
        h: &SVector<f64, D>,
        v_old: &SVector<T, D>,
        w: &mut ChunkWork,
    ) {
        for (bc, velocity) in &self.bcs {
            if !bc.nodes.contains(x, h) {
                continue;
            }
            for (i, v) in velocity.iter().enumerate() {
                let Some(v) = *v else { continue };
                if !bc.acts(n.velocity[i].re(), v) {
                    continue;
                }
                if self.accelerate {
                    // work of the reaction impulse m (v̄ − v) on v̄
                    let dw = (n.mass * (c::<T>(v) - n.velocity[i])).re() * v;
                    w.1 += dw;
                    w.2 += dw.abs();
                }
                n.velocity[i] = c(v);
                n.acceleration[i] = if bc.one_sided {
                    // what takes p/m to v̄: the points feel the wall
                    (c::<T>(v) - v_old[i]) / c::<T>(self.dt)
                } else {
                    T::zero()
                };
            }
        }
    }
}

/// What the grid solve computes at the nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum NodalUpdate {
    /// a = (f − α_d p)/m and v = p/m + a Δt.
    Accelerate,
    /// v = p/m and a = 0 (USF before the stress update; MUSL's remapped velocity).
    VelocityOnly,
}

impl<const D: usize> Solver<D> {
    /// Grid solve (algorithm 10) of `update`; velocity conditions last (eq. 7.28).
    pub(super) fn solve_grid(&mut self, update: NodalUpdate) {
        let accelerate = update == NodalUpdate::Accelerate;
        let (time, dt, damping) = (self.time, self.dt, self.settings.damping);
        let solve = NodeSolve::new(
            &self.velocity_bcs,
            (time, dt),
            damping,
            self.mass_cutoff,
            update,
        );
        let meta = self.grid.clone_meta();
        let cut = parallel::light(self.particles.len()).per_item();
        let chunks = self.grid.nodes.par_chunks_mut(CHUNK).enumerate();
        let work = parallel::map(chunks, cut, |(chunk, nodes): (usize, &mut [Node<D>])| {
            let mut w = (0.0, 0.0, 0.0);
            for (j, n) in nodes.iter_mut().enumerate() {
                if n.mass <= 0.0 {
                    n.velocity = SVector::zeros();
                    n.acceleration = SVector::zeros();
                    continue;
                }
                let v_old = solve.solve(n, &mut w);
                if !solve.bcs.is_empty() {
                    let x = meta.node_position(chunk * CHUNK + j);
                    solve.constrain(n, &x, &meta.spacing, &v_old, &mut w);
                }
            }
            w
        });
        if accelerate {
            for (damping, boundary, boundary_abs) in work {
                self.energies.external += damping;
                self.energies.supplied += damping.abs();
                self.energies.boundary += boundary;
                self.energies.supplied += boundary_abs;
            }
        }
    }
}
