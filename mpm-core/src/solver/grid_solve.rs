//! Grid solve (algorithm 10): nodal acceleration and velocity from the mapped mass,
//! momentum and force, the node mass cutoff, damping work and the velocity conditions
//! (eq. 7.28, and one-sided walls), whose prescribed values are taken once per step at
//! t_{n+1/2}.

use super::Solver;
use crate::boundary::VelocityBc;
use crate::grid::Node;
use crate::parallel;
use nalgebra::SVector;
use rayon::prelude::*;

/// Nodes per parallel work item.
const CHUNK: usize = 2048;

/// Work of one chunk of nodes [J]: damping, prescribed velocities, and the absolute
/// value of the latter.
type ChunkWork = (f64, f64, f64);

/// What every node of one grid solve shares.
struct NodeSolve<'a, const D: usize> {
    dt: f64,
    alpha: f64,
    cutoff: f64,
    accelerate: bool,
    /// Velocity conditions and their prescribed components this step.
    bcs: Vec<(&'a VelocityBc<D>, [Option<f64>; D])>,
}

impl<const D: usize> NodeSolve<'_, D> {
    /// a = (f − α_d p)/m and v = p/m + a Δt for a node above the mass cutoff (damping work
    /// into `w.0`), else v = p/m and a = 0; returns p/m.
    #[inline]
    fn solve(&self, n: &mut Node<D>, w: &mut ChunkWork) -> SVector<f64, D> {
        let v_old = n.momentum / n.mass;
        if self.accelerate && n.mass > self.cutoff * n.heaviest {
            let damping = n.momentum * self.alpha;
            n.acceleration = (n.force - damping) / n.mass;
            n.velocity = v_old + n.acceleration * self.dt;
            w.0 -= damping.dot(&n.velocity) * self.dt;
        } else {
            n.acceleration = SVector::zeros();
            n.velocity = v_old;
        }
        v_old
    }

    /// Velocity conditions at a node at `x` (eq. 7.28; one-sided walls take the
    /// acceleration that brings p/m to v̄), with the work of the reaction impulse.
    #[inline]
    fn constrain(
        &self,
        n: &mut Node<D>,
        x: &SVector<f64, D>,
        h: &SVector<f64, D>,
        v_old: &SVector<f64, D>,
        w: &mut ChunkWork,
    ) {
        for (bc, velocity) in &self.bcs {
            if !bc.nodes.contains(x, h) {
                continue;
            }
            for (i, v) in velocity.iter().enumerate() {
                let Some(v) = v else { continue };
                if !bc.acts(n.velocity[i], *v) {
                    continue;
                }
                if self.accelerate {
                    // work of the reaction impulse m (v̄ − v) on v̄
                    let dw = n.mass * (v - n.velocity[i]) * v;
                    w.1 += dw;
                    w.2 += dw.abs();
                }
                n.velocity[i] = *v;
                n.acceleration[i] = if bc.one_sided {
                    // what takes p/m to v̄: the points feel the wall
                    (v - v_old[i]) / self.dt
                } else {
                    0.0
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
        let t_half = self.time + 0.5 * self.dt;
        let solve = NodeSolve {
            dt: self.dt,
            alpha: self.settings.damping,
            cutoff: self.mass_cutoff,
            accelerate,
            bcs: self
                .velocity_bcs
                .iter()
                .map(|bc| (bc, bc.velocity_at(t_half)))
                .collect(),
        };
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
