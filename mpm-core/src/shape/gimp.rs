//! GIMP shape functions (Bardenhagen & Kober 2004; thesis eq. 10.1-10.3): the hat function
//! S of the grid averaged over the point's box-shaped domain, a tensor product of 1-D
//! factors. With Φ the antiderivative of the hat (h = 1: Φ(s) = (1 + s)²/2 on [−1, 0],
//! 1 − (1 − s)²/2 on [0, 1], 0 below, 1 above) and r = ξ − m the distance of the point
//! from node m in cells, a domain of half-width l cells gives, for any l > 0
//! (reading §1.4),
//!
//!   S̄(r) = [Φ(r + l) − Φ(r − l)] / (2l),   dS̄/dξ = [S(r + l) − S(r − l)] / (2l),
//!
//! which for l ≤ 1/2 is the familiar piecewise form. l = 0 is the hat itself, so classic
//! MPM is the point-GIMP case.
//!
//! - uGIMP: l_k = a_k / h_k, the reference domain, kept through the run.
//! - cpGIMP, analytic (Wallstedt & Guilkey 2008, the cpGIMP Sadeghirad et al. 2011 compare
//!   with): l_k = a_k |F_kk| / h_k, the domain stretched by the diagonal of F (shear
//!   neglected); l may exceed 1/2, the truss stretches 800 %. The thesis's cpGIMP is the
//!   vertex form of module `cpdi` instead; on the truss the two differ (`mpw verify`).

use super::domain::{Fixed, Follow, Stretched};
use super::{box_indices, Kernel, Point, Reach, Weights, MAX_SUPPORT};
use crate::grid::floor_i64;
use materials::scalar::{c, Scalar};
use nalgebra::SVector;
use std::marker::PhantomData;

/// Half-widths below this [cells] are points: the hat weights (the averaged form would
/// lose digits to cancellation, and differs from the hat by O(l)).
const POINT_WIDTH: f64 = 1e-9;

/// GIMP with the box domain of rule `M`: its half-widths l_k = |R_kk| / h_k.
pub struct Gimp<M>(PhantomData<M>);

/// Uniform GIMP: the reference domain.
pub type UGimp = Gimp<Fixed>;

/// Convected-particle GIMP, analytic: the hat averaged over the domain stretched by the
/// diagonal of F.
pub type CpGimpAnalytic = Gimp<Stretched>;

impl<M: Follow, const D: usize> Kernel<D> for Gimp<M> {
    const DOMAIN: bool = true;

    fn extent(p: &Point<'_, D>) -> SVector<f64, D> {
        M::edges(p.half, p.f)
            .diagonal()
            .abs()
            .component_mul(p.inv_h)
    }

    /// The box of nodes the domain meets; beyond `MAX_SUPPORT` nodes along one axis the
    /// factors do not fit, and the count is `usize::MAX` (more than a point may reach).
    fn nodes(e: &SVector<f64, D>) -> usize {
        match e.iter().all(|&e| Reach::of(e).support <= MAX_SUPPORT) {
            true => Reach::box_nodes(e),
            false => usize::MAX,
        }
    }

    #[inline]
    fn evaluate(p: &Point<'_, D>, out: &mut impl Weights<D>) {
        tensor_product(p, &Self::extent(p), out)
    }
}

/// S̄(r) = [Φ(r + l) − Φ(r − l)]/(2l) and dS̄/dξ = [S(r + l) − S(r − l)]/(2l) for a node
/// r cells from a point with half-width l > 0 (cells). Written for any scalar: the
/// derivative pass (`solver::tangent`) runs it with dual r.
#[inline]
pub(crate) fn averaged_hat<T: Scalar>(r: T, l: f64) -> (T, T) {
    let w = 0.5 / l;
    (
        (hat_integral(r + l) - hat_integral(r - l)) * w,
        (hat(r + l) - hat(r - l)) * w,
    )
}

/// Antiderivative Φ of the hat function (cells).
#[inline]
fn hat_integral<T: Scalar>(s: T) -> T {
    let one = T::one();
    if s.re() <= -1.0 {
        T::zero()
    } else if s.re() <= 0.0 {
        c::<T>(0.5) * (one + s) * (one + s)
    } else if s.re() < 1.0 {
        one - c::<T>(0.5) * (one - s) * (one - s)
    } else {
        one
    }
}

/// The hat function S(s) = max(1 − |s|, 0).
#[inline]
fn hat<T: Scalar>(s: T) -> T {
    if s.re().abs() < 1.0 {
        T::one() - s.abs()
    } else {
        T::zero()
    }
}

/// 1-D factors S̄ and dS̄/dξ [per cell] of the `support` nodes from ⌊ξ − l⌋ (the
/// returned first node, in cells from the cell's lower corner) for a point at ξ with
/// half-width l (cells).
#[inline]
fn axis(xi: f64, l: f64, support: usize) -> (i64, [f64; MAX_SUPPORT], [f64; MAX_SUPPORT]) {
    let first = floor_i64(xi - l);
    let (mut s, mut ds) = ([0.0; MAX_SUPPORT], [0.0; MAX_SUPPORT]);
    for m in 0..support {
        let r = xi - (first + m as i64) as f64;
        (s[m], ds[m]) = if l < POINT_WIDTH {
            let inside = r.abs() < 1.0;
            (hat(r), if inside { -r.signum() } else { 0.0 })
        } else {
            averaged_hat(r, l)
        };
    }
    (first, s, ds)
}

/// N_I = Π_k S̄_k and ∂N_I/∂x_j = dS̄_j/dξ_j / h_j Π_{k≠j} S̄_k over the box of nodes the
/// domain meets (those with N_I = 0 and ∇N_I = 0 left out).
#[inline]
fn tensor_product<const D: usize>(
    p: &Point<'_, D>,
    l: &SVector<f64, D>,
    out: &mut impl Weights<D>,
) {
    let support: [usize; D] = std::array::from_fn(|k| Reach::of(l[k]).support);
    let axes: [(i64, [f64; MAX_SUPPORT], [f64; MAX_SUPPORT]); D] =
        std::array::from_fn(|k| axis(p.xi[k], l[k], support[k]));
    for index in box_indices(support) {
        let s: [f64; D] = std::array::from_fn(|k| axes[k].1[index[k]]);
        let n: f64 = s.iter().product();
        let grad = SVector::<f64, D>::from_fn(|j, _| {
            let others: f64 = (0..D).filter(|&k| k != j).map(|k| s[k]).product();
            p.inv_h[j] * axes[j].2[index[j]] * others
        });
        if n != 0.0 || grad != SVector::<f64, D>::zeros() {
            out.push(
                std::array::from_fn(|k| axes[k].0 + index[k] as i64),
                n,
                grad,
            );
        }
    }
}
