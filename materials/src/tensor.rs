//! Small generic helpers on 3×3 tensors (`nalgebra::Matrix3<D>`), valid for real and dual
//! scalars alike. No Voigt orders: tensors stay 3×3.

use crate::scalar::{c, Scalar};
use nalgebra::Matrix3;
use num_traits::Zero;
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

/// `det` of a tensor with the structure `IN_PLANE` (see `sum_coupled`): the terms of `det`
/// that are not zero by it, in `det`'s order, so the same number.
#[inline]
pub fn det_in<const IN_PLANE: bool, T: Ring>(a: &M3<T>) -> T {
    match IN_PLANE {
        false => det(a),
        true => a[(0, 0)] * (a[(1, 1)] * a[(2, 2)]) - a[(0, 1)] * (a[(1, 0)] * a[(2, 2)]),
    }
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

/// Which entries of the 3×3 tensors of a computation may be nonzero: all of them, or
/// with `IN_PLANE` the x-y block and the zz entry only, as in plane strain and
/// axisymmetric models, where F, Fp⁻¹, b, their eigenvectors and σ keep the z axis (and
/// so do their derivatives). The `_in` products skip the terms that structure makes zero
/// and leave those entries zero: the same numbers as the full products, whose extra
/// terms are products with an exact zero (a sum x + 0 is x).
///
/// Σ_k term(k) over the k of the terms a_ik b_kj of entry (i, j) that can be nonzero,
/// summed in the order of k.
#[inline(always)]
fn sum_coupled<const IN_PLANE: bool, T: Ring + Zero>(
    i: usize,
    j: usize,
    term: impl Fn(usize) -> T,
) -> T {
    match (IN_PLANE, i < 2, j < 2) {
        (false, _, _) => term(0) + term(1) + term(2),
        (true, true, true) => term(0) + term(1),
        (true, false, false) => term(2),
        (true, _, _) => T::zero(),
    }
}

/// The product a b, written out: for dual scalars several times faster than nalgebra's
/// general product (which goes through its generic `gemm`), and the same numbers: each
/// entry sums a_i0 b_0j + a_i1 b_1j + a_i2 b_2j in that order, as `gemm` does.
#[inline]
pub fn mul<T: Ring + Zero>(a: &M3<T>, b: &M3<T>) -> M3<T> {
    mul_in::<false, T>(a, b)
}

/// `mul` of tensors with the structure `IN_PLANE` (see `sum_coupled`).
#[inline(always)]
pub fn mul_in<const IN_PLANE: bool, T: Ring + Zero>(a: &M3<T>, b: &M3<T>) -> M3<T> {
    M3::from_fn(|i, j| sum_coupled::<IN_PLANE, _>(i, j, |k| a[(i, k)] * b[(k, j)]))
}

/// a aᵀ, six entries formed and mirrored: the same numbers as `mul(a, &a.transpose())`
/// (each entry sums a_i0 a_j0 + a_i1 a_j1 + a_i2 a_j2 in that order).
#[inline]
pub fn mul_transpose_self<T: Ring + Zero>(a: &M3<T>) -> M3<T> {
    mul_transpose_self_in::<false, T>(a)
}

/// `mul_transpose_self` of a tensor with the structure `IN_PLANE`.
#[inline(always)]
pub fn mul_transpose_self_in<const IN_PLANE: bool, T: Ring + Zero>(a: &M3<T>) -> M3<T> {
    symmetric_in::<IN_PLANE, T>(|i, j| sum_coupled::<IN_PLANE, _>(i, j, |k| a[(i, k)] * a[(j, k)]))
}

/// The symmetric matrix with `entry(i, j)` on and above the diagonal (i ≤ j), mirrored
/// below it: six entries formed instead of nine.
#[inline(always)]
pub fn symmetric<T: Ring + Zero>(entry: impl Fn(usize, usize) -> T) -> M3<T> {
    symmetric_in::<false, T>(entry)
}

/// `symmetric` with the structure `IN_PLANE`: xz and yz zero, without calling `entry`.
#[inline(always)]
pub fn symmetric_in<const IN_PLANE: bool, T: Ring + Zero>(
    entry: impl Fn(usize, usize) -> T,
) -> M3<T> {
    let off_plane = |i: usize, j: usize| match IN_PLANE {
        true => T::zero(),
        false => entry(i, j),
    };
    let (e01, e02, e12) = (entry(0, 1), off_plane(0, 2), off_plane(1, 2));
    M3::new(
        entry(0, 0),
        e01,
        e02,
        e01,
        entry(1, 1),
        e12,
        e02,
        e12,
        entry(2, 2),
    )
}

/// a b for a real `a`, each product of a real entry and a scalar costing what a real
/// factor costs (for dual scalars half a dual product); entries summed in `mul`'s order.
pub fn mul_real_left<D: Scalar>(a: &M3<f64>, b: &M3<D>) -> M3<D> {
    mul_real_left_in::<false, D>(a, b)
}

/// `mul_real_left` of tensors with the structure `IN_PLANE`.
pub fn mul_real_left_in<const IN_PLANE: bool, D: Scalar>(a: &M3<f64>, b: &M3<D>) -> M3<D> {
    M3::from_fn(|i, j| sum_coupled::<IN_PLANE, _>(i, j, |k| b[(k, j)] * a[(i, k)]))
}

/// a b for a real `b`, as `mul_real_left`.
pub fn mul_real_right<D: Scalar>(a: &M3<D>, b: &M3<f64>) -> M3<D> {
    mul_real_right_in::<false, D>(a, b)
}

/// `mul_real_right` of tensors with the structure `IN_PLANE`.
pub fn mul_real_right_in<const IN_PLANE: bool, D: Scalar>(a: &M3<D>, b: &M3<f64>) -> M3<D> {
    M3::from_fn(|i, j| sum_coupled::<IN_PLANE, _>(i, j, |k| a[(i, k)] * b[(k, j)]))
}

/// Vᵀ a V for a real V and a symmetric `a` (`a` in the basis of V's columns): the entries
/// of `mul_real_left(Vᵀ, a V)` on and above the diagonal, mirrored.
pub fn rotate_into<D: Scalar>(v: &M3<f64>, a: &M3<D>) -> M3<D> {
    rotate_into_in::<false, D>(v, a)
}

/// `rotate_into` of tensors with the structure `IN_PLANE`.
pub fn rotate_into_in<const IN_PLANE: bool, D: Scalar>(v: &M3<f64>, a: &M3<D>) -> M3<D> {
    let av = mul_real_right_in::<IN_PLANE, D>(a, v);
    symmetric_in::<IN_PLANE, D>(|i, j| sum_coupled::<IN_PLANE, _>(i, j, |k| av[(k, j)] * v[(k, i)]))
}

/// V a Vᵀ for a real V and a symmetric `a` (`a` back from the basis of V's columns), as
/// `rotate_into`.
pub fn rotate_out<D: Scalar>(v: &M3<f64>, a: &M3<D>) -> M3<D> {
    rotate_out_in::<false, D>(v, a)
}

/// `rotate_out` of tensors with the structure `IN_PLANE`.
pub fn rotate_out_in<const IN_PLANE: bool, D: Scalar>(v: &M3<f64>, a: &M3<D>) -> M3<D> {
    let av = mul_real_right_in::<IN_PLANE, D>(a, &v.transpose());
    symmetric_in::<IN_PLANE, D>(|i, j| sum_coupled::<IN_PLANE, _>(i, j, |k| av[(k, j)] * v[(i, k)]))
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
#[inline]
pub fn dev<D: Scalar>(a: &M3<D>) -> M3<D> {
    a - identity::<D>() * (trace(a) / c::<D>(3.0))
}

/// Double contraction `a : b`, summed in storage order over the nine entries (an indexed
/// sum the compiler unrolls wherever it is inlined; a matrix iterator it sometimes leaves
/// as a loop).
#[inline]
pub fn ddot<D: Scalar>(a: &M3<D>, b: &M3<D>) -> D {
    let (a, b) = (a.as_slice(), b.as_slice());
    (0..9).fold(c::<D>(0.0), |s, k| s + a[k] * b[k])
}

/// Frobenius norm `‖a‖ = √(a : a)`.
#[inline]
pub fn norm<D: Scalar>(a: &M3<D>) -> D {
    ddot(a, a).sqrt()
}

/// von Mises equivalent `√(3/2) ‖dev a‖`.
#[inline]
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

    /// A product with a real factor is the dual product with that factor lifted, to the
    /// bit; a rotation of a symmetric matrix is the two products' upper triangle, mirrored,
    /// and the rotations undo each other to round-off.
    #[test]
    fn products_with_a_real_factor_are_the_dual_products() {
        type D2 = crate::dual::Dual<2>;
        let real = M3::<f64>::new(0.9, -0.2, 0.1, 0.3, 1.1, -0.4, 0.05, 0.2, 0.95);
        let dual = M3::<D2>::from_fn(|i, j| {
            let x = 1.0 + 0.1 * (3 * i + j) as f64;
            D2::new(
                x,
                nalgebra::SVector::from([0.3 * x - 0.2, (i as f64) - 0.7 * j as f64]),
            )
        });
        assert_eq!(mul_real_left(&real, &dual), mul(&lift(&real), &dual));
        assert_eq!(mul_real_right(&dual, &real), mul(&dual, &lift(&real)));
        let v = crate::sym_eigen::decompose(&(real * real.transpose())).vectors;
        let sym = dual + dual.transpose();
        let products = mul_real_left(&v.transpose(), &mul_real_right(&sym, &v));
        let rotated = rotate_into(&v, &sym);
        for i in 0..3 {
            for j in i..3 {
                assert_eq!(rotated[(i, j)], products[(i, j)]);
                assert_eq!(rotated[(j, i)], products[(i, j)]);
            }
        }
        let back = rotate_out(&v, &rotated);
        for (x, y) in back.iter().zip(sym.iter()) {
            assert!((x.re - y.re).abs() < 1e-14 && (x.eps - y.eps).norm() < 1e-14);
        }
    }

    /// Of tensors that keep the z axis, the in-plane products give the full products'
    /// numbers exactly (values and derivatives), and leave xz, yz, zx and zy zero.
    #[test]
    fn in_plane_products_are_the_full_products() {
        type D2 = crate::dual::Dual<2>;
        let in_plane = |i: usize, j: usize| (i < 2) == (j < 2);
        let real = M3::<f64>::from_fn(|i, j| match in_plane(i, j) {
            true => 0.9 + 0.13 * i as f64 - 0.31 * j as f64 + 0.07 * (i * j) as f64,
            false => 0.0,
        });
        let dual = M3::<D2>::from_fn(|i, j| match in_plane(i, j) {
            true => {
                let x = 1.0 + 0.1 * (3 * i + j) as f64;
                D2::new(x, nalgebra::SVector::from([0.3 * x - 0.2, i as f64 - 0.7]))
            }
            false => D2::from(0.0),
        });
        let other = M3::<D2>::from_fn(|i, j| match in_plane(i, j) {
            true => dual[(j, i)] * dual[(i, j)] + D2::from(0.25),
            false => D2::from(0.0),
        });
        let v = crate::sym_eigen::decompose(&(real * real.transpose())).vectors;
        let sym = dual + dual.transpose();
        let same = |what: &str, a: M3<D2>, b: M3<D2>| {
            for (k, (x, y)) in a.iter().zip(b.iter()).enumerate() {
                assert!(
                    x.re == y.re && x.eps == y.eps,
                    "{what}, entry {k}: {x:?} against {y:?}"
                );
            }
            for (i, j) in [(0, 2), (1, 2), (2, 0), (2, 1)] {
                assert!(
                    b[(i, j)].re == 0.0 && b[(i, j)].eps.norm() == 0.0,
                    "{what} ({i}, {j})"
                );
            }
        };
        same("mul", mul(&dual, &other), mul_in::<true, _>(&dual, &other));
        same(
            "a aᵀ",
            mul_transpose_self(&dual),
            mul_transpose_self_in::<true, _>(&dual),
        );
        same(
            "real a",
            mul_real_left(&real, &dual),
            mul_real_left_in::<true, _>(&real, &dual),
        );
        same(
            "a real",
            mul_real_right(&dual, &real),
            mul_real_right_in::<true, _>(&dual, &real),
        );
        same(
            "Vᵀ a V",
            rotate_into(&v, &sym),
            rotate_into_in::<true, _>(&v, &sym),
        );
        same(
            "V a Vᵀ",
            rotate_out(&v, &sym),
            rotate_out_in::<true, _>(&v, &sym),
        );
        let (d, d_in) = (det(&dual), det_in::<true, _>(&dual));
        assert!(
            d.re == d_in.re && d.eps == d_in.eps,
            "det: {d:?} against {d_in:?}"
        );
    }
}
