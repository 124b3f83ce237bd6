//! e^x, ln x and x^y for a lane type (`lanes`): the C library for one point, one
//! vectorized routine for four.
//!
//! The four-lane routines are `wide`'s for `f64x4` (exp: range reduction by ln 2 in two
//! parts and a degree-13 polynomial; ln: the Cephes rational form on the mantissa; x^y:
//! Agner Fog's vector-class pow with an extended-precision logarithm). Against
//! `f64::exp`, `f64::ln` and `f64::powf` they are within 1 ulp (exp, ln) and 2 ulp (x^y)
//! over the arguments a return meets (tested), and four lanes cost about one library call
//! (`simba` would call the library lane by lane). Each lane is computed on its own, so a
//! point's result does not depend on the points it is grouped with; it may differ from the
//! one-point result by those ulps. For one point the library stays: a routine for four
//! run in one lane costs more than the library call.
//!
//! They replace the library calls in the batched hot path of the return (flow stress along
//! ln Δα, the first guess, the onset of flow); `f64::exp` and friends stay everywhere
//! else.

use simba::simd::WideF64x4 as F64x4;

/// The elementary functions of a lane type (every `Lane` has them).
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
        self.exp()
    }

    #[inline]
    fn ln_v(self) -> Self {
        self.ln()
    }

    #[inline]
    fn powf_v(self, y: Self) -> Self {
        self.powf(y)
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
    use wide::f64x4;

    /// Distance in units in the last place.
    fn ulps(a: f64, b: f64) -> u64 {
        if a == b {
            return 0;
        }
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    /// Log-spaced samples of [lo, hi] (both > 0), with a jitter that hits every mantissa.
    fn log_spaced(lo: f64, hi: f64, count: usize) -> Vec<f64> {
        let (a, b) = (lo.ln(), hi.ln());
        (0..count)
            .map(|k| {
                let t = (k as f64 + 0.5 * ((k * 7919) % 1000) as f64 / 1000.0) / count as f64;
                (a + (b - a) * t).exp()
            })
            .collect()
    }

    /// Four lanes of `x` from `first` on (the last repeated past the end).
    fn pack4(x: &[f64], first: usize) -> F64x4 {
        F64x4(f64x4::from(
            [0, 1, 2, 3].map(|i| x[(first + i).min(x.len() - 1)]),
        ))
    }

    /// The largest distance in ulp between `four` taken four lanes at a time and `one`.
    fn worst(x: &[f64], four: impl Fn(F64x4) -> F64x4, one: impl Fn(f64) -> f64) -> u64 {
        let mut worst = 0;
        for first in (0..x.len()).step_by(4) {
            let lanes = four(pack4(x, first));
            for (i, &xi) in x[first..].iter().take(4).enumerate() {
                worst = worst.max(ulps(lanes.extract(i), one(xi)));
            }
        }
        worst
    }

    #[test]
    fn exp_in_lanes_is_within_one_ulp_of_the_library() {
        let x: Vec<f64> = (0..200_000)
            .map(|k| -60.0 + 65.0 * k as f64 / 200_000.0 + 1e-7 * (k % 13) as f64)
            .collect();
        let w = worst(&x, F64x4::exp_v, f64::exp);
        assert!(w <= 1, "{w} ulp");
    }

    #[test]
    fn ln_in_lanes_is_within_one_ulp_of_the_library() {
        for (lo, hi) in [(1e-300, 1e300), (0.5, 2.0)] {
            let w = worst(&log_spaced(lo, hi, 200_000), F64x4::ln_v, f64::ln);
            assert!(w <= 1, "[{lo}, {hi}]: {w} ulp");
        }
    }

    /// Over what a flow stress raises: α in [1e-10, 10] to N in [0.05, 1.5], and θ* in
    /// (0, 1) to M in [0.3, 3].
    #[test]
    fn pow_in_lanes_is_within_two_ulp_of_the_library() {
        let x = log_spaced(1e-10, 10.0, 50_000);
        for y in [0.05, 0.1, 0.31, 0.5, 0.83, 1.09, 1.5, 2.3, 3.0] {
            let w = worst(&x, |x| x.powf_v(F64x4::splat(y)), |x| x.powf(y));
            assert!(w <= 2, "x^{y}: {w} ulp");
        }
        let ends = F64x4(f64x4::from([0.0, 1.0, 0.0, 1.0])).powf_v(F64x4::splat(0.31));
        assert_eq!([ends.extract(0), ends.extract(1)], [0.0, 1.0]);
    }

    /// A lane's result does not depend on its neighbours: each equals the same argument
    /// in all four lanes, to the bit.
    #[test]
    fn a_lane_does_not_depend_on_its_neighbours() {
        let x = log_spaced(1e-6, 40.0, 400);
        let alone = |f: &dyn Fn(F64x4) -> F64x4, xi: f64| f(F64x4::splat(xi)).extract(0);
        let functions: [&dyn Fn(F64x4) -> F64x4; 3] = [&F64x4::exp_v, &F64x4::ln_v, &|x: F64x4| {
            x.powf_v(F64x4::splat(0.31))
        }];
        for f in functions {
            for first in (0..x.len()).step_by(3) {
                let lanes = f(pack4(&x, first));
                for i in 0..4 {
                    let xi = x[(first + i).min(x.len() - 1)];
                    assert_eq!(lanes.extract(i).to_bits(), alone(f, xi).to_bits());
                }
            }
        }
    }
}
