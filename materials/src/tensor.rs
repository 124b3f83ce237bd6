//! Small generic helpers on 3×3 tensors (`nalgebra::Matrix3<D>`), valid for real and dual
//! scalars alike. No Voigt orders: tensors stay 3×3.

use crate::scalar::{c, Scalar};
use nalgebra::Matrix3;
use std::ops::{Add, Mul, Sub};

pub type M3<D> = Matrix3<D>;

pub fn identity<D: Scalar>() -> M3<D> {
    M3::identity()
}

pub fn trace<D: Scalar>(a: &M3<D>) -> D {
    a[(0, 0)] + a[(1, 1)] + a[(2, 2)]
}

/// The entry arithmetic of `det` and `adjugate`: real, dual and SIMD-lane scalars alike.
pub trait Ring:
    nalgebra::Scalar + Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
}

impl<T> Ring for T where
    T: nalgebra::Scalar + Copy + Add<Output = T> + Sub<Output = T> + Mul<Output = T>
{
}

pub fn det<T: Ring>(a: &M3<T>) -> T {
    a[(0, 0)] * (a[(1, 1)] * a[(2, 2)] - a[(1, 2)] * a[(2, 1)])
        - a[(0, 1)] * (a[(1, 0)] * a[(2, 2)] - a[(1, 2)] * a[(2, 0)])
        + a[(0, 2)] * (a[(1, 0)] * a[(2, 1)] - a[(1, 1)] * a[(2, 0)])
}

/// The adjugate (transposed cofactor matrix): A adj(A) = det(A) I.
pub fn adjugate<T: Ring>(a: &M3<T>) -> M3<T> {
    let m = |i: usize, j: usize| a[(i, j)];
    M3::new(
        m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1),
        m(0, 2) * m(2, 1) - m(0, 1) * m(2, 2),
        m(0, 1) * m(1, 2) - m(0, 2) * m(1, 1),
        m(1, 2) * m(2, 0) - m(1, 0) * m(2, 2),
        m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0),
        m(0, 2) * m(1, 0) - m(0, 0) * m(1, 2),
        m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0),
        m(0, 1) * m(2, 0) - m(0, 0) * m(2, 1),
        m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0),
    )
}

/// The product a b, written out: for dual scalars several times faster than nalgebra's
/// general product (which goes through its generic `gemm`), and the same numbers: each
/// entry sums a_i0 b_0j + a_i1 b_1j + a_i2 b_2j in that order, as `gemm` does.
#[inline]
pub fn mul<T: Ring>(a: &M3<T>, b: &M3<T>) -> M3<T> {
    M3::from_fn(|i, j| a[(i, 0)] * b[(0, j)] + a[(i, 1)] * b[(1, j)] + a[(i, 2)] * b[(2, j)])
}

/// a aᵀ, six entries formed and mirrored: the same numbers as `mul(a, &a.transpose())`
/// (each entry sums a_i0 a_j0 + a_i1 a_j1 + a_i2 a_j2 in that order).
#[inline]
pub fn mul_transpose_self<T: Ring>(a: &M3<T>) -> M3<T> {
    let e =
        |i: usize, j: usize| a[(i, 0)] * a[(j, 0)] + a[(i, 1)] * a[(j, 1)] + a[(i, 2)] * a[(j, 2)];
    let (b01, b02, b12) = (e(0, 1), e(0, 2), e(1, 2));
    M3::new(e(0, 0), b01, b02, b01, e(1, 1), b12, b02, b12, e(2, 2))
}

/// Vᵀ a V for a real V (`a` in the basis of V's columns), each product of a real entry
/// and a scalar costing what a real factor costs (for dual scalars half a dual product).
pub fn rotate_into<D: Scalar>(v: &M3<f64>, a: &M3<D>) -> M3<D> {
    let av =
        M3::from_fn(|i, j| a[(i, 0)] * v[(0, j)] + a[(i, 1)] * v[(1, j)] + a[(i, 2)] * v[(2, j)]);
    M3::from_fn(|i, j| av[(0, j)] * v[(0, i)] + av[(1, j)] * v[(1, i)] + av[(2, j)] * v[(2, i)])
}

/// V a Vᵀ for a real V (`a` back from the basis of V's columns), as `rotate_into`.
pub fn rotate_out<D: Scalar>(v: &M3<f64>, a: &M3<D>) -> M3<D> {
    let av =
        M3::from_fn(|i, j| a[(i, 0)] * v[(j, 0)] + a[(i, 1)] * v[(j, 1)] + a[(i, 2)] * v[(j, 2)]);
    M3::from_fn(|i, j| av[(0, j)] * v[(i, 0)] + av[(1, j)] * v[(i, 1)] + av[(2, j)] * v[(i, 2)])
}

/// Inverse by the adjugate; `None` if the determinant's real part is zero.
pub fn inverse<D: Scalar>(a: &M3<D>) -> Option<M3<D>> {
    let d = det(a);
    if d.re() == 0.0 || !d.re().is_finite() {
        return None;
    }
    Some(adjugate(a) * d.recip())
}

/// Deviatoric part `a − tr(a)/3 I`.
pub fn dev<D: Scalar>(a: &M3<D>) -> M3<D> {
    a - identity::<D>() * (trace(a) / c::<D>(3.0))
}

/// Double contraction `a : b`.
pub fn ddot<D: Scalar>(a: &M3<D>, b: &M3<D>) -> D {
    a.component_mul(b).iter().fold(c::<D>(0.0), |s, &x| s + x)
}

/// Frobenius norm `‖a‖ = √(a : a)`.
pub fn norm<D: Scalar>(a: &M3<D>) -> D {
    ddot(a, a).sqrt()
}

/// von Mises equivalent `√(3/2) ‖dev a‖`.
pub fn von_mises<D: Scalar>(a: &M3<D>) -> D {
    norm(&dev(a)) * c::<D>(1.5f64.sqrt())
}

/// Whether every entry's real part is finite, without a branch per entry: Σ (x − x) is 0
/// when every x is finite and NaN otherwise (∞ − ∞ and NaN − NaN are NaN).
#[inline]
pub fn all_finite<D: Scalar>(a: &M3<D>) -> bool {
    a.as_slice()
        .iter()
        .fold(0.0, |sum, x| sum + (x.re() - x.re()))
        == 0.0
}

/// Real part of every entry.
pub fn re<D: Scalar>(a: &M3<D>) -> M3<f64> {
    a.map(|x| x.re())
}

/// Lift a real matrix to constant scalars.
pub fn lift<D: Scalar>(a: &M3<f64>) -> M3<D> {
    a.map(|x| c::<D>(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_finite_finds_any_infinite_or_nan_entry() {
        let a = M3::<f64>::from_fn(|i, j| 1e300 * (i as f64 - j as f64) + 0.5);
        assert!(all_finite(&a));
        for bad in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            for k in 0..9 {
                let mut b = a;
                b[k] = bad;
                assert!(!all_finite(&b), "{bad} at {k}");
            }
        }
    }
}
