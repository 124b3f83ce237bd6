//! Matrix exponential by Taylor series with scaling and squaring.
//!
//! A polynomial in the matrix entries, so it is exact and differentiable at repeated
//! eigenvalues (the case Δα = 0 of eq. 4.48), unlike eigen-decomposition forms
//! (DESIGN section 11). The scaling is chosen from the real part, so dual parts follow
//! the same arithmetic.

use crate::scalar::{c, Scalar};
use crate::tensor::{identity, mul, M3};

/// Largest Taylor order after scaling ‖A‖₁ ≤ 1/2: truncation error ≤ 0.5¹³/13! ≈ 2e-14.
const ORDER: usize = 12;

pub fn expm<D: Scalar>(a: &M3<D>) -> M3<D> {
    let norm1 = (0..3)
        .map(|j| (0..3).map(|i| a[(i, j)].re().abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let squarings = if norm1 > 0.5 {
        (norm1 / 0.5).log2().ceil() as i32
    } else {
        0
    };
    let scale = 0.5f64.powi(squarings);
    let scaled = a * c::<D>(scale);
    // the series stops once a term is below 1e-17 of ‖A‖₁ (after scaling): the rest is
    // below that, and so is the rest of its derivative, k ‖A‖^(k−1)/k! ‖dA‖ (a small
    // plastic increment needs 6-8 terms instead of 12)
    let small = 1e-17 * norm1 * scale;
    let mut term = identity::<D>();
    let mut sum = identity::<D>();
    for k in 1..=ORDER {
        term = mul(&term, &scaled) * c::<D>(1.0 / k as f64);
        sum += term;
        if (0..3)
            .map(|j| (0..3).map(|i| term[(i, j)].re().abs()).sum::<f64>())
            .fold(0.0, f64::max)
            <= small
        {
            break;
        }
    }
    for _ in 0..squarings {
        sum = mul(&sum, &sum);
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    #[test]
    fn diagonal_matches_scalar_exp() {
        let a = Matrix3::from_diagonal(&nalgebra::Vector3::new(0.3, -1.7, 2.5));
        let e = expm(&a);
        for i in 0..3 {
            let x: f64 = a[(i, i)];
            assert!((e[(i, i)] / x.exp() - 1.0).abs() < 1e-13);
        }
    }

    #[test]
    fn determinant_is_exp_of_trace() {
        let a = Matrix3::new(0.1, 0.4, -0.3, 0.2, -0.5, 0.7, 0.9, 0.05, 0.2);
        let e = expm(&a);
        let t: f64 = a.trace();
        assert!((e.determinant() / t.exp() - 1.0).abs() < 1e-12);
    }
}
