//! Which continuum the 2D or 3D grid represents, and everything that depends on it: how a
//! point's in-plane velocity gradient becomes the 3×3 L and F the materials see, the hoop
//! term of the internal force, and a point's volume. Solver stages and the discretization
//! ask this module; none of them branches on the kinematics itself.
//!
//! - `PlaneStrain` (D = 2): F = [[F_2D, 0], [0, 1]], so F33 = 1 and L33 = 0; volumes are
//!   per metre of thickness [m³/m].
//! - `Axisymmetric` (D = 2, coordinates (r, z)): the hoop stretch F_θθ = r/R of a point at
//!   radius r that started at R; the hoop strain rate v_r/r enters the stress power and
//!   the internal force gains the hoop term σ_θθ N_I V / r in the radial direction (Sulsky
//!   & Schreyer 1996); a point of cross-section A at radius r is the ring 2π r A (Pappus).
//! - `Solid` (D = 3): full 3D.

use materials::scalar::Scalar;
use materials::tensor::mul;
use nalgebra::{Matrix3, SMatrix, SVector};
use std::f64::consts::PI;

/// (I + L Δt) F for an in-plane L (D = 2): the rows below D are F's own and each sum runs
/// over the D in-plane terms. The full product adds L's zeros times F as well, which
/// changes no finite number but the sign of a zero.
#[inline]
fn in_plane_update<T: Scalar, const D: usize>(
    l: &SMatrix<T, D, D>,
    f: &Matrix3<T>,
    dt: f64,
) -> Matrix3<T> {
    let step = |i: usize, k: usize| match i == k {
        true => T::one() + l[(i, k)] * dt,
        false => l[(i, k)] * dt,
    };
    Matrix3::from_fn(|i, j| match i < D {
        true => (1..D).fold(step(i, 0) * f[(0, j)], |sum, k| {
            sum + step(i, k) * f[(k, j)]
        }),
        false => f[(i, j)],
    })
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kinematics {
    PlaneStrain,
    Axisymmetric,
    Solid,
}

impl Kinematics {
    /// Grid dimension this kinematics needs.
    pub fn dimension(self) -> usize {
        match self {
            Kinematics::PlaneStrain | Kinematics::Axisymmetric => 2,
            Kinematics::Solid => 3,
        }
    }

    /// The 3×3 velocity gradient L [1/s] and the updated F_{n+1} = (I + L Δt) F_n of a
    /// point at `x` (reference position `x_ref`) from its in-plane gradient `l` and grid
    /// velocity `vg`. Axisymmetric: L_θθ = v_r / r and F_θθ = (r + v_r Δt) / R. Always
    /// inlined: called out of line with five dual directions, its matrices went through
    /// memcpy.
    #[inline(always)]
    pub fn deformation<T: Scalar, const D: usize>(
        self,
        l: &SMatrix<T, D, D>,
        vg: &SVector<T, D>,
        (x, x_ref): (&SVector<T, D>, &SVector<f64, D>),
        f: &Matrix3<T>,
        dt: f64,
    ) -> (Matrix3<T>, Matrix3<T>) {
        let mut l3 = Matrix3::zeros();
        l3.fixed_view_mut::<D, D>(0, 0).copy_from(l);
        let mut f_new = match D {
            3 => mul(&(Matrix3::identity() + l3.map(|l| l * dt)), f),
            _ => in_plane_update(l, f, dt),
        };
        if self == Kinematics::Axisymmetric {
            l3[(2, 2)] = vg[0] / x[0];
            f_new[(2, 2)] = (x[0] + vg[0] * dt) / x_ref[0];
        }
        (l3, f_new)
    }

    /// The hoop force density σ_θθ V / r [N] that a point at `x` adds, times N_I, to the
    /// radial internal force of node I (zero unless axisymmetric).
    #[inline]
    pub fn hoop_force<T: Scalar, const D: usize>(
        self,
        sigma: &Matrix3<T>,
        volume: T,
        x: &SVector<T, D>,
    ) -> T {
        match self {
            Kinematics::Axisymmetric => sigma[(2, 2)] * volume / x[0],
            _ => T::zero(),
        }
    }

    /// Volume [m³] (plane strain: per metre) of a point at `x` whose piece of the grid's
    /// space has size `size` (area in 2D, volume in 3D).
    pub fn volume<const D: usize>(self, x: &SVector<f64, D>, size: f64) -> f64 {
        match self {
            Kinematics::Axisymmetric => 2.0 * PI * x[0] * size,
            _ => size,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix2, Vector2};

    #[test]
    fn axisymmetric_hoop_terms_follow_the_radius() {
        let l = Matrix2::new(0.1, 0.0, 0.0, -0.2);
        let (x, x_ref, vg) = (
            Vector2::new(2.0, 1.0),
            Vector2::new(1.6, 1.0),
            Vector2::new(0.4, 0.0),
        );
        let f = Matrix3::from_diagonal(&nalgebra::Vector3::new(1.0, 1.0, 1.25));
        let (l3, f_new) = Kinematics::Axisymmetric.deformation(&l, &vg, (&x, &x_ref), &f, 0.5);
        assert_eq!(l3[(2, 2)], 0.2); // v_r / r
        assert_eq!(f_new[(2, 2)], 2.2 / 1.6); // (r + v_r Δt) / R
        assert_eq!(f_new[(0, 0)], 1.05);
        let (l3, f_new) = Kinematics::PlaneStrain.deformation(&l, &vg, (&x, &x_ref), &f, 0.5);
        assert_eq!((l3[(2, 2)], f_new[(2, 2)]), (0.0, 1.25));
        let sigma = Matrix3::from_diagonal(&nalgebra::Vector3::new(0.0, 0.0, 3.0));
        assert_eq!(Kinematics::Axisymmetric.hoop_force(&sigma, 4.0, &x), 6.0);
        assert_eq!(Kinematics::PlaneStrain.hoop_force(&sigma, 4.0, &x), 0.0);
        assert_eq!(Kinematics::Axisymmetric.volume(&x, 1.0), 4.0 * PI);
    }
}
