//! Bi-/trilinear shape functions (appendix E, eq. E.4-E.7), classic MPM.
//!
//! For a point at local cell coordinates ξ_i = (x_i − x_i^min)/h_i ∈ [0, 1) the factors are
//! a_0 = 1 − ξ, a_1 = ξ (eq. E.5) and their derivatives ∓1/h_i (eq. E.7). Corner `k` of the
//! cell takes factor a_{bit_i(k)} in direction i, so N_k = Π_i a_{bit_i(k)} and
//! ∂N_k/∂x_j = da_{bit_j(k)} Π_{i≠j} a_{bit_i(k)}. The corner order is binary (x fastest),
//! which differs from the right-hand order of figure E.3 only in labelling.

use super::{corners, node_index, Kernel, Point, Reach};
use nalgebra::SVector;

/// Shape function values and gradients [1/m] at one point for the 2^D corners of its cell
/// (arrays sized for D ≤ 3; entries beyond 2^D are unused).
#[derive(Debug, Clone, Copy)]
pub struct CellWeights<const D: usize> {
    pub n: [f64; 8],
    pub grad: [SVector<f64, D>; 8],
}

/// Values and gradients for local coordinates `xi` ∈ [0, 1)^D in a cell of inverse
/// spacing `inv_h` [1/m].
#[inline]
pub fn linear<const D: usize>(xi: &SVector<f64, D>, inv_h: &SVector<f64, D>) -> CellWeights<D> {
    let mut w = CellWeights {
        n: [0.0; 8],
        grad: [SVector::zeros(); 8],
    };
    for k in 0..corners(D) {
        let mut n = 1.0;
        let mut g = SVector::<f64, D>::repeat(1.0);
        for i in 0..D {
            let upper = (k >> i) & 1 == 1;
            let a = if upper { xi[i] } else { 1.0 - xi[i] };
            let da = if upper { inv_h[i] } else { -inv_h[i] };
            n *= a;
            for j in 0..D {
                g[j] *= if i == j { da } else { a };
            }
        }
        w.n[k] = n;
        w.grad[k] = g;
    }
    w
}

/// Bi-/trilinear shape functions: the 2ᴰ corners of the point's cell.
pub struct Linear;

impl<const D: usize> Kernel<D> for Linear {
    const DOMAIN: bool = false;

    fn extent(_: &Point<'_, D>) -> SVector<f64, D> {
        SVector::zeros()
    }

    #[inline]
    fn evaluate(
        p: &Point<'_, D>,
        reach: Reach,
        n: &mut [f64],
        grad: &mut [SVector<f64, D>],
    ) -> [i64; D] {
        let w = linear(&p.xi, p.inv_h);
        if reach == Reach::CELL {
            n.copy_from_slice(&w.n[..corners(D)]);
            grad.copy_from_slice(&w.grad[..corners(D)]);
            return [0; D];
        }
        // a wider stencil (another body's domains, or a point without one): the cell's
        // corners are its first two nodes per axis
        n.fill(0.0);
        grad.fill(SVector::zeros());
        for (node, (n, g)) in n.iter_mut().zip(grad.iter_mut()).enumerate() {
            let index: [usize; D] = node_index(node, reach.support);
            if index.iter().all(|&i| i < 2) {
                let corner: usize = (0..D).map(|k| index[k] << k).sum();
                (*n, *g) = (w.n[corner], w.grad[corner]);
            }
        }
        [0; D]
    }
}
