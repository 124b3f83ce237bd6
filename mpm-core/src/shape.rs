//! Grid shape functions behind one interface, `Kernel`, and the one used today, linear
//! (bi-/trilinear, appendix E, eq. E.4-E.7).
//!
//! A kernel states its support as part of its type: a point reaches `SUPPORT` nodes per
//! axis, starting `PAD` nodes below the lower corner of its cell. The grid padding and the
//! slab width of the lock-free parallel scatter are derived from these, so a wider kernel
//! (GIMP, CPDI) changes neither. Weights and gradients are evaluated once per particle and
//! step into a `WeightCache` and read by every transfer of that step.
//!
//! Linear: for a point at local cell coordinates ξ_i = (x_i − x_i^min)/h_i ∈ [0, 1) the
//! factors are a_0 = 1 − ξ, a_1 = ξ (eq. E.5) and their derivatives ∓1/h_i (eq. E.7).
//! Corner `k` of the cell takes factor a_{bit_i(k)} in direction i, so
//! N_k = Π_i a_{bit_i(k)} and ∂N_k/∂x_j = da_{bit_j(k)} Π_{i≠j} a_{bit_i(k)}. The corner
//! order is binary (x fastest), which differs from the right-hand order of figure E.3 only
//! in labelling.

use nalgebra::SVector;

/// Number of cell corners in `D` dimensions, 2^D.
pub const fn corners(d: usize) -> usize {
    1 << d
}

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

/// A shape function: which nodes a point reaches and with what weights.
pub trait Kernel<const D: usize> {
    /// Nodes a point reaches along each axis.
    const SUPPORT: usize;
    /// Nodes of the stencil below the lower corner of the point's cell, per axis.
    const PAD: usize;
    /// Nodes of the stencil, SUPPORTᴰ.
    const NODES: usize;
    /// Weights N and gradients ∇N [1/m] of the stencil nodes (x fastest) for a point at
    /// local cell coordinates `xi` ∈ [0, 1)ᴰ in cells of inverse size `inv_h` [1/m].
    fn evaluate(
        xi: &SVector<f64, D>,
        inv_h: &SVector<f64, D>,
        n: &mut [f64],
        grad: &mut [SVector<f64, D>],
    );
}

/// Bi-/trilinear shape functions (appendix E): the 2ᴰ corners of the point's cell.
pub struct Linear;

impl<const D: usize> Kernel<D> for Linear {
    const SUPPORT: usize = 2;
    const PAD: usize = 0;
    const NODES: usize = corners(D);
    #[inline]
    fn evaluate(
        xi: &SVector<f64, D>,
        inv_h: &SVector<f64, D>,
        n: &mut [f64],
        grad: &mut [SVector<f64, D>],
    ) {
        let w = linear(xi, inv_h);
        n.copy_from_slice(&w.n[..corners(D)]);
        grad.copy_from_slice(&w.grad[..corners(D)]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn partition_of_unity_and_linear_completeness_in_3d() {
        let xi = Vector3::new(0.3, 0.7, 0.11);
        let inv_h = Vector3::new(2.0, 4.0, 0.5);
        let w = linear(&xi, &inv_h);
        let sum: f64 = w.n[..8].iter().sum();
        let grad_sum: Vector3<f64> = w.grad[..8].iter().sum();
        assert!((sum - 1.0).abs() < 1e-15);
        assert!(grad_sum.norm() < 1e-14);
        // reproduces the linear field x (in cell units): Σ N_k x_k = x and Σ ∇N_k x_k = e_i
        for i in 0..3 {
            let x: f64 = (0..8).map(|k| w.n[k] * ((k >> i) & 1) as f64).sum();
            assert!((x - xi[i]).abs() < 1e-15);
            let g: Vector3<f64> = (0..8)
                .map(|k| w.grad[k] * ((k >> i) & 1) as f64 / inv_h[i])
                .sum();
            assert!((g - Vector3::ith(i, 1.0)).norm() < 1e-14);
        }
    }
}
