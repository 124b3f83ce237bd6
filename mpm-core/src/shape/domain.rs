//! How a point's domain follows its deformation (thesis §10, the variant family of
//! reading §1.2): the half-edge vectors R [m] (columns) of the box of reference half-widths
//! a_k carried along by F (the in-plane block of the 3×3 F).

use materials::scalar::c;
use materials::Scalar;
use nalgebra::{Matrix3, SMatrix, SVector};

/// A rule for the domain's half-edge vectors, for real F and for F with derivatives
/// (`solver::Tangent`).
pub trait Follow {
    fn edges<T: Scalar, const D: usize>(half: &SVector<f64, D>, f: &Matrix3<T>)
        -> SMatrix<T, D, D>;
}

/// Not at all: R = diag(a) (uGIMP).
pub struct Fixed;

/// By the diagonal of F: R = diag(F_kk a_k), shear neglected (cpGIMP).
pub struct Stretched;

/// By the whole F: R = F diag(a) (CPDI1, eq. 10.4).
pub struct Deformed;

impl Follow for Fixed {
    fn edges<T: Scalar, const D: usize>(
        half: &SVector<f64, D>,
        _: &Matrix3<T>,
    ) -> SMatrix<T, D, D> {
        SMatrix::from_diagonal(&half.map(c))
    }
}

impl Follow for Stretched {
    fn edges<T: Scalar, const D: usize>(
        half: &SVector<f64, D>,
        f: &Matrix3<T>,
    ) -> SMatrix<T, D, D> {
        SMatrix::from_fn(|i, k| {
            if i == k {
                f[(k, k)] * c::<T>(half[k])
            } else {
                c(0.0)
            }
        })
    }
}

impl Follow for Deformed {
    fn edges<T: Scalar, const D: usize>(
        half: &SVector<f64, D>,
        f: &Matrix3<T>,
    ) -> SMatrix<T, D, D> {
        SMatrix::from_fn(|i, k| f[(i, k)] * c::<T>(half[k]))
    }
}
