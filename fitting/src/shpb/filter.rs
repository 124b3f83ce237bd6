//! Polynomial least squares on sampled signals: the trend of a stretch of samples
//! (`polynomial_trend`) and the Savitzky-Golay filter (Savitzky & Golay 1964): each sample
//! replaced by the value at its position of the least-squares polynomial of order p over
//! the 2m + 1 samples centred on it (at the ends, the polynomial of the first or last full
//! window), which smooths noise while keeping peaks and edges that a moving average of
//! the same width flattens.

pub use crate::experiment::processing::SavitzkyGolay;
use nalgebra::DMatrix;

/// The Savitzky-Golay filter a record asks for (`experiment::processing`), applied here.
impl SavitzkyGolay {
    /// `values` filtered; a record shorter than the window is fitted as one window.
    pub fn apply(&self, values: &[f64]) -> Vec<f64> {
        let n = values.len();
        if n <= self.window {
            return polynomial_trend(values, self.order.min(n.saturating_sub(1)));
        }
        let m = self.window / 2;
        let projection = projection(self.window, self.order);
        // row s: the weights of the window's samples in its fitted value at sample s
        let table = DMatrix::from_fn(self.window, self.window, |s, j| {
            (0..=self.order)
                .map(|k| position(s, self.window).powi(k as i32) * projection[(k, j)])
                .sum::<f64>()
        });
        (0..n)
            .map(|i| {
                let start = i.saturating_sub(m).min(n - self.window);
                (0..self.window)
                    .map(|j| table[(i - start, j)] * values[start + j])
                    .sum()
            })
            .collect()
    }
}

/// The least-squares polynomial of `order` through `values` (equally spaced), at each
/// sample.
pub fn polynomial_trend(values: &[f64], order: usize) -> Vec<f64> {
    let n = values.len();
    let coefficients = projection(n, order) * nalgebra::DVector::from_column_slice(values);
    (0..n)
        .map(|s| {
            (0..=order)
                .map(|k| coefficients[k] * position(s, n).powi(k as i32))
                .sum()
        })
        .collect()
}

/// Positions of `n` equally spaced samples scaled to [−1, 1] (conditioning).
fn position(s: usize, n: usize) -> f64 {
    if n == 1 {
        0.0
    } else {
        2.0 * s as f64 / (n - 1) as f64 - 1.0
    }
}

/// (AᵀA)⁻¹Aᵀ with A_sk = x_s^k: row k gives coefficient k of the fit from the samples.
fn projection(n: usize, order: usize) -> DMatrix<f64> {
    let a = DMatrix::from_fn(n, order + 1, |s, k| position(s, n).powi(k as i32));
    let ata = a.transpose() * &a;
    ata.try_inverse()
        .expect("the normal matrix of distinct positions is regular")
        * a.transpose()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A polynomial of the filter's order passes unchanged, ends included.
    #[test]
    fn a_polynomial_of_the_order_passes_unchanged() {
        let cubic: Vec<f64> = (0..40)
            .map(|k| {
                let x = k as f64 * 0.1;
                1.0 - 2.0 * x + 0.5 * x * x - 0.3 * x * x * x
            })
            .collect();
        let out = SavitzkyGolay::new(9, 3).unwrap().apply(&cubic);
        for (a, b) in cubic.iter().zip(&out) {
            assert!((a - b).abs() < 1e-10, "{a} vs {b}");
        }
        let trend = polynomial_trend(&cubic, 3);
        for (a, b) in cubic.iter().zip(&trend) {
            assert!((a - b).abs() < 1e-10, "{a} vs {b}");
        }
    }

    /// The published 5-point quadratic smoothing weights (−3, 12, 17, 12, −3)/35.
    #[test]
    fn five_point_quadratic_weights_are_the_published_ones() {
        let mut impulse = vec![0.0; 11];
        impulse[5] = 1.0;
        let out = SavitzkyGolay::new(5, 2).unwrap().apply(&impulse);
        let published = [-3.0, 12.0, 17.0, 12.0, -3.0];
        for (k, w) in published.iter().enumerate() {
            assert!((out[3 + k] - w / 35.0).abs() < 1e-12, "{k}: {}", out[3 + k]);
        }
    }

    /// White noise through the m = 10 (21-point) quadratic filter: its standard
    /// deviation falls by √(Σ w²) = √(3(3m² + 3m − 1)/((2m − 1)(2m + 1)(2m + 3))) = 0.3280
    /// (the centre weight of the quadratic filter equals Σ w²), within 3 % on 20 000
    /// samples.
    #[test]
    fn noise_is_reduced_by_the_variance_factor() {
        let mut state = 12345u64;
        let noise: Vec<f64> = (0..20000)
            .map(|_| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect();
        let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
        let out = SavitzkyGolay::new(21, 2).unwrap().apply(&noise);
        let ratio = rms(&out[10..19990]) / rms(&noise);
        let m: f64 = 10.0;
        let expected = (3.0 * (3.0 * m * m + 3.0 * m - 1.0)
            / ((2.0 * m - 1.0) * (2.0 * m + 1.0) * (2.0 * m + 3.0)))
            .sqrt();
        assert!(
            (ratio / expected - 1.0).abs() < 0.03,
            "{ratio} vs {expected}"
        );
    }

    #[test]
    fn an_even_window_is_refused() {
        assert!(SavitzkyGolay::new(10, 2).is_err());
        assert!(SavitzkyGolay::new(3, 3).is_err());
    }
}
