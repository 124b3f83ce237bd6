//! Particle-to-grid transfer (algorithm 9), in parallel without locks and the same on any
//! number of threads (module `slabs`).

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

impl<const D: usize> Solver<D> {
    /// Particle-to-grid transfer of the chosen quantities (algorithm 9), lock-free and
    /// deterministic (module `slabs`).
    pub(super) fn scatter(&mut self, t: Transfer) {
        self.clear_nodes(t);
        self.bucket_by_slab();
        let stride = self.grid.strides[D - 1];
        for colour in 0..2 {
            let s = &self.scratch;
            let parts = s.slabs.parts(&mut self.grid.nodes, colour, stride);
            let sources = Sources {
                p: &self.particles,
                force: &s.force,
                weights: &s.weights,
                body_force: self.settings.body_force,
                kinematics: self.settings.kinematics,
            };
            let cut = parallel::light(self.particles.len()).per_item();
            parallel::for_each(parts.into_par_iter(), cut, |(k, start, nodes)| {
                for &i in s.slabs.points(k) {
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

    /// The particles in slabs by their lowest node (module `slabs`).
    fn bucket_by_slab(&mut self) {
        let last = D - 1;
        let s = &mut self.scratch;
        let stride = self.grid.strides[last];
        let weights = &s.weights;
        let rows = (self.grid.dims[last], weights.support());
        s.slabs
            .bucket(self.particles.len(), rows, |i| weights.lowest(i) / stride);
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
    pub(super) mass: f64,
    pub(super) momentum: SVector<T, D>,
    pub(super) external: SVector<T, D>,
    pub(super) stress_volume: SMatrix<T, D, D>,
    pub(super) hoop: T,
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

    /// The share of a transfer without forces (`Transfer::MOMENTUM`): mass and momentum,
    /// the force terms zero.
    #[inline]
    pub(super) fn without_forces(mass: f64, velocity: &SVector<T, D>) -> Self {
        PointShare {
            mass,
            momentum: velocity * c::<T>(mass),
            external: SVector::zeros(),
            stress_volume: SMatrix::zeros(),
            hoop: T::zero(),
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
