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

/// Real part of every entry.
pub fn re<D: Scalar>(a: &M3<D>) -> M3<f64> {
    a.map(|x| x.re())
}

/// Lift a real matrix to constant scalars.
pub fn lift<D: Scalar>(a: &M3<f64>) -> M3<D> {
    a.map(|x| c::<D>(x))
}
