//! Several material points in lockstep. The principal return is written once
//! for a lane type `L`: `f64` for one point, `F64x4` for four (simba's `WideF64x4`, SIMD
//! arithmetic over `wide::f64x4`: one AVX instruction per operation in the workspace's
//! x86-64-v3 build, `.cargo/config.toml`; two SSE2 ones on the x86-64 baseline). Branches
//! become lane masks (`select`); exp, ln and pow are the library's for one point and one
//! vectorized routine for four (`elementary`, within 2 ulp of the library). Each lane is
//! computed on its own, so a point's result does not depend on what it is grouped with,
//! and equals its one-point result to round-off.

use crate::elementary::Elementary;
use crate::error::MaterialError;
use nalgebra::SMatrix;
use simba::simd::{SimdBool, SimdRealField, SimdValue};

/// Four points in lockstep.
pub type F64x4 = simba::simd::WideF64x4;

/// The most lanes a lane type has.
pub const MAX_LANES: usize = 4;

/// A lane type: `f64` or `F64x4`.
pub trait Lane: SimdRealField<Element = f64> + Elementary + Copy + Send + Sync {
    /// A slot per lane for what failed in it.
    type Failures: Default + AsRef<[Option<MaterialError>]> + AsMut<[Option<MaterialError>]>;
}

impl Lane for f64 {
    type Failures = [Option<MaterialError>; 1];
}

impl Lane for F64x4 {
    type Failures = [Option<MaterialError>; 4];
}

/// The lane mask of a lane type.
pub type Mask<L> = <L as SimdValue>::SimdBool;

/// A lane value from its per-lane values.
#[inline]
pub fn pack<L: Lane>(value: impl Fn(usize) -> f64) -> L {
    let mut out = L::splat(value(0));
    for i in 1..L::LANES {
        out.replace(i, value(i));
    }
    out
}

/// `a` where `mask`, else `b`.
#[inline]
pub fn select<L: Lane>(mask: Mask<L>, a: L, b: L) -> L {
    a.select(mask, b)
}

/// All lanes false.
#[inline]
pub fn none<L: Lane>() -> Mask<L> {
    L::splat(0.0).simd_ne(L::splat(0.0))
}

/// The lanes where `x` is a nonzero finite number (a divisor that gives a number).
#[inline]
pub fn regular<L: Lane>(x: L) -> Mask<L> {
    finite(x) & x.simd_ne(L::splat(0.0))
}

/// The lanes where `x` is a finite number: x − x is 0 there and NaN for ±∞ and NaN.
#[inline]
#[allow(clippy::eq_op)]
pub fn finite<L: Lane>(x: L) -> Mask<L> {
    (x - x).simd_eq(L::splat(0.0))
}

/// `a` in the lanes of `mask`, `b` in the rest, entry by entry.
#[inline]
pub fn select_matrix<L: Lane, const R: usize, const C: usize>(
    mask: Mask<L>,
    a: &SMatrix<L, R, C>,
    b: &SMatrix<L, R, C>,
) -> SMatrix<L, R, C> {
    a.zip_map(b, |a, b| select(mask, a, b))
}

/// Whether lane `i` of `mask` is set.
#[inline]
pub fn lane<L: Lane>(mask: Mask<L>, i: usize) -> bool {
    mask.bitmask() & (1 << i) != 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use simba::simd::SimdPartialOrd;

    #[test]
    fn masks_select_lane_by_lane() {
        let a: F64x4 = pack(|i| i as f64);
        let b = F64x4::splat(-1.0);
        let m = a.simd_gt(F64x4::splat(1.5));
        let s = select(m, a, b);
        assert_eq!([0, 1, 2, 3].map(|i| s.extract(i)), [-1.0, -1.0, 2.0, 3.0]);
        assert!(!lane::<F64x4>(m, 1) && lane::<F64x4>(m, 2));
        assert!(!none::<F64x4>().any() && !none::<f64>());
    }
}
