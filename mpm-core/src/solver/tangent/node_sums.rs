//! The derivatives of the particle-to-grid sums (eq. 7.30-7.32) by the product rule: the
//! node sums' values are the run's (`scatter`; the grid solve's derivative joins them,
//! `Tangent::solve`), so a point adds only the derivative parts of its share,
//! d(N m) = m dN, d(N m v) = N d(m v) + dN m v and
//! d(f_ext N − σV ∇N − e_r σ_θθ V/r N), each term's derivative added to the node's by
//! `Dual`'s accumulations (the dual product's operations on the derivative parts).

use super::Dual;
use crate::grid::Node;
use crate::solver::scatter::{PointShare, Transfer};
use nalgebra::SVector;

impl<const D: usize, const P: usize> PointShare<D, Dual<P>> {
    /// Add the derivatives of the share of weight `n` and gradient `grad` to `node`'s,
    /// whose real parts are left as they are.
    #[inline]
    pub(super) fn add_derivatives_to(
        &self,
        node: &mut Node<D, Dual<P>>,
        t: Transfer,
        n: &Dual<P>,
        grad: &SVector<Dual<P>, D>,
    ) {
        if t.mass {
            node.mass.add_derivatives_scaled(n, self.mass);
        }
        if t.momentum {
            for k in 0..D {
                node.momentum[k].add_derivatives_of_product(&self.momentum[k], n);
            }
        }
        if t.force {
            for k in 0..D {
                let force = &mut node.force[k];
                force.add_derivatives_of_product(&self.external[k], n);
                for j in 0..D {
                    force.sub_derivatives_of_product(&self.stress_volume[(k, j)], &grad[j]);
                }
            }
            node.force[0].sub_derivatives_of_product(&self.hoop, n);
        }
    }
}
