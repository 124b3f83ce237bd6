//! Particle-to-grid transfer (algorithm 9), in parallel without locks: particles are
//! bucketed into slabs of node rows along the last axis by their lowest node; slabs of one
//! colour (even or odd) touch disjoint node ranges (a slab is at least support − 1 rows
//! wide, so a point reaches at most into the next slab), and each slab adds its
//! particles in index order, so the sums do not depend on the number of threads.

use super::Solver;
use crate::grid::Node;
use crate::kinematics::Kinematics;
use crate::parallel;
use crate::particles::Particles;
use crate::weights::WeightCache;
use materials::scalar::{c, Scalar};
use nalgebra::{Matrix3, SMatrix, SVector};
use rayon::prelude::*;

/// Which nodal quantities a transfer maps.
#[derive(Debug, Clone, Copy)]
pub(super) struct Transfer {
    pub mass: bool,
    pub momentum: bool,
    pub force: bool,
}

impl Transfer {
    pub const ALL: Self = Transfer {
        mass: true,
        momentum: true,
        force: true,
    };
    pub const MASS_MOMENTUM: Self = Transfer {
        force: false,
        ..Self::ALL
    };
    pub const FORCE: Self = Transfer {
        mass: false,
        momentum: false,
        force: true,
    };
    pub const MOMENTUM: Self = Transfer {
        mass: false,
        momentum: true,
        force: false,
    };
}

/// Particles bucketed into slabs of `width` node rows along the last axis.
struct Slabs {
    width: usize,
    count: usize,
}

impl<const D: usize> Solver<D> {
    /// Particle-to-grid transfer of the chosen quantities (algorithm 9), lock-free and
    /// deterministic (see the module notes).
    pub(super) fn scatter(&mut self, t: Transfer) {
        self.clear_nodes(t);
        let slabs = self.bucket_by_slab();
        let last = D - 1;
        let stride = self.grid.strides[last];
        let support = self.scratch.weights.support();
        for colour in 0..2 {
            let mut parts: Vec<(usize, usize, &mut [Node<D>])> = Vec::new();
            let mut rest: &mut [Node<D>] = &mut self.grid.nodes;
            let mut consumed = 0;
            for k in (colour..slabs.count).step_by(2) {
                // node rows slab k's points reach: k w .. (k + 1) w + support − 2
                let start = k * slabs.width * stride;
                let end =
                    (((k + 1) * slabs.width + support - 1) * stride).min(consumed + rest.len());
                let tail = std::mem::take(&mut rest);
                let (_, tail) = tail.split_at_mut(start - consumed);
                let (mine, tail) = tail.split_at_mut(end - start);
                rest = tail;
                consumed = end;
                parts.push((k, start, mine));
            }
            let s = &self.scratch;
            let sources = Sources {
                p: &self.particles,
                force: &s.force,
                weights: &s.weights,
                body_force: self.settings.body_force,
                kinematics: self.settings.kinematics,
            };
            let cut = parallel::light(self.particles.len()).per_item();
            parallel::for_each(parts.into_par_iter(), cut, |(k, start, nodes)| {
                for &i in &s.order[s.slab_start[k]..s.slab_start[k + 1]] {
                    sources.add(i as usize, t, start, nodes);
                }
            });
        }
        if t.force {
            self.add_surface_loads();
        }
    }

    fn clear_nodes(&mut self, t: Transfer) {
        let cut = parallel::light(self.particles.len());
        parallel::for_each(self.grid.nodes.par_iter_mut(), cut, |n: &mut Node<D>| {
            if t.mass {
                n.mass = 0.0;
                n.heaviest = 0.0;
            }
            if t.momentum {
                n.momentum = SVector::zeros();
            }
            if t.force {
                n.force = SVector::zeros();
            }
        });
    }

    /// Stable counting sort of the particles by the slab of their lowest node.
    /// Same-colour slabs are a slab apart, so they touch disjoint nodes when the width is
    /// at least support − 1 node rows.
    fn bucket_by_slab(&mut self) -> Slabs {
        let last = D - 1;
        let s = &mut self.scratch;
        let support = s.weights.support();
        let rows = self.grid.dims[last] + 1 - support;
        let width = rows.div_ceil(32).max(support - 1).max(1);
        let count = rows.div_ceil(width);
        let stride = self.grid.strides[last];
        let weights = &s.weights;
        let slab_of = |i: usize| weights.lowest(i) / stride / width;
        let n = self.particles.len();
        s.slab_start.clear();
        s.slab_start.resize(count + 1, 0);
        for i in 0..n {
            s.slab_start[slab_of(i) + 1] += 1;
        }
        for k in 0..count {
            s.slab_start[k + 1] += s.slab_start[k];
        }
        s.order.resize(n, 0);
        let mut next = s.slab_start.clone();
        for i in 0..n {
            let k = slab_of(i);
            s.order[next[k]] = i as u32;
            next[k] += 1;
        }
        Slabs { width, count }
    }
}

/// What the particles contribute to the nodes.
struct Sources<'a, const D: usize> {
    p: &'a Particles<D>,
    /// Applied, spring and contact force on each particle [N].
    force: &'a [SVector<f64, D>],
    weights: &'a WeightCache<D>,
    body_force: SVector<f64, D>,
    kinematics: Kinematics,
}

impl<const D: usize> Sources<'_, D> {
    /// Add particle `i`'s share to `nodes`, the slab's node range starting at node `start`.
    #[inline]
    fn add(&self, i: usize, t: Transfer, start: usize, nodes: &mut [Node<D>]) {
        let p = self.p;
        let w = self.weights.stencil(i);
        let m = p.mass[i];
        let share = PointShare::new(
            m,
            &p.velocity[i],
            self.force[i] + self.body_force * m,
            (&p.stress[i], p.volume[i], &p.position[i]),
            self.kinematics,
        );
        for (c, &index) in w.node.iter().enumerate() {
            share.add_to(&mut nodes[index as usize - start], t, w.n[c], &w.grad[c]);
        }
    }
}

/// What one point brings to the nodes it reaches (eq. 7.30-7.32): its mass m, momentum
/// m v, external force f_ext + m b, σ V (in-plane block) and hoop force density
/// σ_θθ V / r; in any scalar (dual in the derivative pass, `tangent`).
pub(super) struct PointShare<const D: usize, T> {
    mass: f64,
    momentum: SVector<T, D>,
    external: SVector<T, D>,
    stress_volume: SMatrix<T, D, D>,
    hoop: T,
}

impl<const D: usize, T: Scalar> PointShare<D, T> {
    #[inline]
    pub(super) fn new(
        mass: f64,
        velocity: &SVector<T, D>,
        external: SVector<T, D>,
        (stress, volume, x): (&Matrix3<T>, T, &SVector<T, D>),
        kinematics: Kinematics,
    ) -> Self {
        PointShare {
            mass,
            momentum: velocity * c::<T>(mass),
            external,
            stress_volume: stress.fixed_view::<D, D>(0, 0).into_owned() * volume,
            hoop: kinematics.hoop_force(stress, volume, x),
        }
    }

    /// Add the share of weight `n` and gradient `grad` to `node`.
    #[inline]
    pub(super) fn add_to(&self, node: &mut Node<D, T>, t: Transfer, n: T, grad: &SVector<T, D>) {
        if t.mass {
            node.mass += n * c::<T>(self.mass);
            node.heaviest = node.heaviest.max(self.mass);
        }
        if t.momentum {
            node.momentum += self.momentum * n;
        }
        if t.force {
            // σ V ∇N written out (as nalgebra sums it, faster for dual scalars)
            let sv = &self.stress_volume;
            let internal = SVector::<T, D>::from_fn(|i, _| {
                (1..D).fold(sv[(i, 0)] * grad[0], |sum, j| sum + sv[(i, j)] * grad[j])
            });
            let mut f = self.external * n - internal;
            f[0] -= self.hoop * n;
            node.force += f;
        }
    }
}
