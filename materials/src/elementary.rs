//! e^x, ln x and x^y for a lane type (`lanes`): one vectorized routine for one point and
//! for four, so that each lane of a batch gives the one-point result to the bit.
//!
//! The routines are `wide`'s for `f64x4` (exp: range reduction by ln 2 in two parts and a
//! degree-13 polynomial; ln: the Cephes rational form on the mantissa; x^y: Agner Fog's
//! vector-class pow with an extended-precision logarithm). One point (`f64`) runs the same
//! instructions in lane 0 of a splat. Against `f64::exp`, `f64::ln` and `f64::powf` they
//! are within 1 ulp (exp, ln) and 2 ulp (x^y) over the arguments a return meets (tested); four lanes cost about one
//! library call (`simba` takes the library functions lane by lane).
//!
//! They replace the library calls in the hot path of the return (flow stress along ln Δα,
//! the first guess, the onset of flow); `f64::exp` and friends stay everywhere else.

use simba::simd::WideF64x4 as F64x4;
use wide::f64x4;

/// The vectorized elementary functions of a lane type (every `Lane` has them).
pub trait Elementary: Copy {
    /// e^x in every lane.
    fn exp_v(self) -> Self;
    /// ln x in every lane (x > 0; NaN below 0, −∞ at 0).
    fn ln_v(self) -> Self;
    /// x^y in every lane (x ≥ 0).
    fn powf_v(self, y: Self) -> Self;
}

impl Elementary for f64 {
    #[inline]
    fn exp_v(self) -> Self {
        f64x4::splat(self).exp().as_array()[0]
    }

    #[inline]
    fn ln_v(self) -> Self {
        f64x4::splat(self).ln().as_array()[0]
    }

    #[inline]
    fn powf_v(self, y: Self) -> Self {
        f64x4::splat(self).powf_simd(f64x4::splat(y)).as_array()[0]
    }
}

impl Elementary for F64x4 {
    #[inline]
    fn exp_v(self) -> Self {
        F64x4(self.0.exp())
    }

    #[inline]
    fn ln_v(self) -> Self {
        F64x4(self.0.ln())
    }

    #[inline]
    fn powf_v(self, y: Self) -> Self {
        F64x4(self.0.powf_simd(y.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use simba::simd::SimdValue;

    /// Distance in units in the last place.
    fn ulps(a: f64, b: f64) -> u64 {
        if a == b {
            return 0;
        }
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    /// Log-spaced samples of [lo, hi] (both > 0), with a jitter that hits every mantissa.
    fn log_spaced(lo: f64, hi: f64, count: usize) -> impl Iterator<Item = f64> {
        let (a, b) = (lo.ln(), hi.ln());
        (0..count).map(move |k| {
            let t = (k as f64 + 0.5 * ((k * 7919) % 1000) as f64 / 1000.0) / count as f64;
            (a + (b - a) * t).exp()
        })
    }

    fn worst(pairs: impl Iterator<Item = (f64, f64)>) -> u64 {
        pairs.map(|(a, b)| ulps(a, b)).max().unwrap()
    }

    #[test]
    fn exp_is_within_one_ulp_of_the_library() {
        let x = (0..200_000).map(|k| -60.0 + 65.0 * k as f64 / 200_000.0 + 1e-7 * (k % 13) as f64);
        let w = worst(x.map(|x| (x.exp_v(), x.exp())));
        assert!(w <= 1, "{w} ulp");
    }

    #[test]
    fn ln_is_within_one_ulp_of_the_library() {
        let w = worst(log_spaced(1e-300, 1e300, 200_000).map(|x| (x.ln_v(), x.ln())));
        assert!(w <= 1, "{w} ulp");
        let near_one = log_spaced(0.5, 2.0, 200_000).map(|x| (x.ln_v(), x.ln()));
        assert!(worst(near_one) <= 1);
    }

    /// Over what a flow stress raises: α in [1e-10, 10] to N in [0.05, 1.5], and θ* in
    /// (0, 1) to M in [0.3, 3].
    #[test]
    fn powf_is_within_two_ulp_of_the_library() {
        for y in [0.05, 0.1, 0.31, 0.5, 0.83, 1.09, 1.5, 2.3, 3.0] {
            let w = worst(log_spaced(1e-10, 10.0, 50_000).map(|x| (x.powf_v(y), x.powf(y))));
            assert!(w <= 2, "x^{y}: {w} ulp");
        }
        assert_eq!(0f64.powf_v(0.31), 0.0);
        assert_eq!(1f64.powf_v(0.31), 1.0);
    }

    /// Each lane of four is the one-point result to the bit, whatever its neighbours.
    #[test]
    fn a_lane_gives_the_one_point_result_to_the_bit() {
        let x: Vec<f64> = log_spaced(1e-6, 40.0, 400).collect();
        for chunk in x.chunks(4) {
            let lanes = F64x4(f64x4::from([0, 1, 2, 3].map(|i| chunk[i % chunk.len()])));
            let (e, l, p) = (
                lanes.exp_v(),
                lanes.ln_v(),
                lanes.powf_v(F64x4::splat(0.31)),
            );
            for (i, &xi) in chunk.iter().enumerate() {
                assert_eq!(e.extract(i).to_bits(), xi.exp_v().to_bits());
                assert_eq!(l.extract(i).to_bits(), xi.ln_v().to_bits());
                assert_eq!(p.extract(i).to_bits(), xi.powf_v(0.31).to_bits());
            }
        }
    }
}
