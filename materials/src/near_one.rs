//! e^z and ln x near z = 0 and x = 1, for the principal return, whose arguments are
//! elastic: the log stretches 2ε_a and flow ratios −√(3/2) Δα n_a are ~1e-3..1e-2 and
//! the squared trial stretches λ_a² are within as much of 1.
//!
//! - e^z: the Taylor polynomial of degree 8 for |z| ≤ 1/16, whose remainder
//!   z⁹/9! e^|z| ≤ 4.3e-17 is below half an ulp of e^z.
//! - ln x = 2 atanh t with t = (x − 1)/(x + 1), by the series 2 Σ t^(2k+1)/(2k+1) to
//!   k = 5, for |x − 1| ≤ 1/16: |t| ≤ 1/31, and the first omitted term t¹²/13 ≤ 9e-20
//!   relative.
//!
//! `elementary`'s exp and ln elsewhere. Each is a third of the instructions of the library
//! call.

use crate::lanes::{select, Lane};
use simba::simd::SimdBool;

/// Largest |z| taken by the polynomials (|x − 1| for the logarithm).
const LIMIT: f64 = 1.0 / 16.0;

/// 1/k! for k = 1..=8.
const INV_FACTORIAL: [f64; 8] = [
    1.0,
    1.0 / 2.0,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5040.0,
    1.0 / 40320.0,
];

/// e^z, to within 2 ulp of `f64::exp` (tested), lane by lane.
#[inline]
pub fn exp_small<L: Lane>(z: L) -> L {
    let far = z.simd_abs().simd_gt(L::splat(LIMIT));
    if far.all() {
        return z.exp_v();
    }
    let tail = INV_FACTORIAL
        .iter()
        .rev()
        .fold(L::splat(0.0), |acc, &c| (acc + L::splat(c)) * z);
    let near = L::splat(1.0) + tail;
    if far.any() {
        select(far, z.exp_v(), near)
    } else {
        near
    }
}

/// 1/(2k + 1) for k = 1..=5.
const INV_ODD: [f64; 5] = [1.0 / 3.0, 1.0 / 5.0, 1.0 / 7.0, 1.0 / 9.0, 1.0 / 11.0];

/// ln x, to within 2 ulp of `f64::ln` (tested), lane by lane.
#[inline]
pub fn ln_near_one<L: Lane>(x: L) -> L {
    let one = L::splat(1.0);
    let far = (x - one).simd_abs().simd_gt(L::splat(LIMIT));
    if far.all() {
        return x.ln_v();
    }
    let t = (x - one) / (x + one);
    let t2 = t * t;
    let tail = INV_ODD
        .iter()
        .rev()
        .fold(L::splat(0.0), |acc, &c| (acc + L::splat(c)) * t2);
    let near = L::splat(2.0) * t * (one + tail);
    if far.any() {
        select(far, x.ln_v(), near)
    } else {
        near
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agrees_with_the_library_exp_to_two_ulp() {
        let mut worst: f64 = 0.0;
        for i in -4000..=4000 {
            let z = LIMIT * i as f64 / 4000.0 * 1.01;
            let err = (exp_small(z) / z.exp() - 1.0).abs() / f64::EPSILON;
            worst = worst.max(err);
        }
        assert!(worst <= 2.0, "worst error {worst} ulp");
        assert_eq!(exp_small(0.0), 1.0);
        assert_eq!(exp_small(0.5), 0.5f64.exp());
    }

    #[test]
    fn agrees_with_the_library_ln_to_two_ulp() {
        let mut worst: f64 = 0.0;
        for i in -4000..=4000 {
            let x = 1.0 + LIMIT * i as f64 / 4000.0 * 1.01;
            let (ours, theirs) = (ln_near_one(x), x.ln());
            let ulp = f64::EPSILON * theirs.abs().max(f64::MIN_POSITIVE);
            worst = worst.max((ours - theirs).abs() / ulp);
        }
        assert!(worst <= 2.0, "worst error {worst} ulp");
        assert_eq!(ln_near_one(1.0), 0.0);
        assert_eq!(ln_near_one(1.5), 1.5f64.ln());
    }

    /// Four lanes give the one-point values: to the bit in the polynomials' range, to an
    /// ulp beyond it (the lanes' exp and ln there: `elementary`).
    #[test]
    fn lanes_give_the_one_point_values() {
        use crate::lanes::{pack, F64x4};
        use simba::simd::SimdValue;
        let z = [0.01, -0.05, 0.3, -2.0];
        let e: F64x4 = exp_small(pack(|i| z[i]));
        let l: F64x4 = ln_near_one(pack(|i| 1.0 + z[i].abs()));
        let ulps = |a: f64, b: f64| (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs();
        for i in 0..4 {
            let allowed = u64::from(z[i].abs() > LIMIT);
            assert!(ulps(e.extract(i), exp_small(z[i])) <= allowed, "e^{}", z[i]);
            let x = 1.0 + z[i].abs();
            assert!(ulps(l.extract(i), ln_near_one(x)) <= allowed, "ln {x}");
        }
    }
}
