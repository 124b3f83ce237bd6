//! Bi-/trilinear shape functions (appendix E, eq. E.4-E.7), classic MPM.
//!
//! For a point at local cell coordinates ξ_i = (x_i − x_i^min)/h_i ∈ [0, 1) the factors are
//! a_0 = 1 − ξ, a_1 = ξ (eq. E.5) and their derivatives ∓1/h_i (eq. E.7). Corner `k` of the
//! cell takes factor a_{bit_i(k)} in direction i, so N_k = Π_i a_{bit_i(k)} and
//! ∂N_k/∂x_j = da_{bit_j(k)} Π_{i≠j} a_{bit_i(k)}. The corner order is binary (x fastest),
//! which differs from the right-hand order of figure E.3 only in labelling.

use super::{corners, Kernel, Point, Weights};
use materials::scalar::Scalar;
use nalgebra::SVector;

/// Shape function values and gradients [1/m] at one point for the 2^D corners of its cell
/// (arrays sized for D ≤ 3; entries beyond 2^D are unused), in any scalar: with dual
/// local coordinates the dual parts are dN = ∇N·dx and d∇N = (∂²N/∂x²) dx (module
/// `solver::tangent`).
#[derive(Debug, Clone, Copy)]
pub struct CellWeights<const D: usize, T = f64> {
    pub n: [T; 8],
    pub grad: [SVector<T, D>; 8],
}

/// Values and gradients for local coordinates `xi` ∈ [0, 1)^D in a cell of inverse
/// spacing `inv_h` [1/m].
#[inline]
pub fn linear<T: Scalar, const D: usize>(
    xi: &SVector<T, D>,
    inv_h: &SVector<f64, D>,
) -> CellWeights<D, T> {
    let mut w = CellWeights {
        n: [T::zero(); 8],
        grad: [SVector::zeros(); 8],
    };
    for k in 0..corners(D) {
        let mut n = T::one();
        let mut g = SVector::<T, D>::repeat(T::one());
        for i in 0..D {
            let upper = (k >> i) & 1 == 1;
            let a = if upper { xi[i] } else { T::one() - xi[i] };
            let da = if upper { inv_h[i] } else { -inv_h[i] };
            n *= a;
            for j in 0..D {
                match i == j {
                    true => g[j] *= da,
                    false => g[j] *= a,
                }
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

    fn nodes(_: &SVector<f64, D>) -> usize {
        corners(D)
    }

    #[inline]
    fn evaluate(p: &Point<'_, D>, out: &mut impl Weights<D>) {
        let w = linear(&p.xi, p.inv_h);
        for k in 0..corners(D) {
            out.push(
                std::array::from_fn(|i| ((k >> i) & 1) as i64),
                w.n[k],
                w.grad[k],
            );
        }
    }
}
