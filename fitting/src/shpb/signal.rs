//! Sampled-signal helpers for the bar records: linear interpolation at any time, a
//! centred moving average, mean and standard deviation, cumulative trapezoidal integral.

/// Value of the piecewise-linear signal (`time`, `values`) at `t`; `time` increases
/// strictly and `t` lies within it.
pub fn interpolate(time: &[f64], values: &[f64], t: f64) -> f64 {
    let i = time.partition_point(|&s| s <= t).clamp(1, time.len() - 1);
    let (t0, t1) = (time[i - 1], time[i]);
    let w = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
    values[i - 1] + w * (values[i] - values[i - 1])
}

/// Centred moving average over `width` samples (shorter at the ends).
pub fn moving_average(values: &[f64], width: usize) -> Vec<f64> {
    let half = width / 2;
    let mut prefix = vec![0.0; values.len() + 1];
    for (i, v) in values.iter().enumerate() {
        prefix[i + 1] = prefix[i] + v;
    }
    (0..values.len())
        .map(|i| {
            let lo = i.saturating_sub(half);
            let hi = (i + half + 1).min(values.len());
            (prefix[hi] - prefix[lo]) / (hi - lo) as f64
        })
        .collect()
}

/// Mean and (population) standard deviation.
pub fn mean_std(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt())
}

/// ∫ y dt from the first sample, by the trapezoidal rule.
pub fn cumulative_integral(time: &[f64], y: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; y.len()];
    for k in 1..y.len() {
        out[k] = out[k - 1] + 0.5 * (y[k] + y[k - 1]) * (time[k] - time[k - 1]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn helpers_are_exact_on_linear_and_constant_data() {
        let t = [0.0, 1.0, 3.0];
        let y = [1.0, 3.0, 7.0]; // y = 1 + 2 t
        assert_eq!(interpolate(&t, &y, 2.0), 5.0);
        assert_eq!(interpolate(&t, &y, 3.0), 7.0);
        // ∫ (1 + 2t) dt from 0 to 3 = 3 + 9 = 12, exact for the trapezoidal rule.
        assert_eq!(cumulative_integral(&t, &y), vec![0.0, 2.0, 12.0]);
        assert_eq!(
            moving_average(&[1.0, 2.0, 3.0, 4.0], 3),
            vec![1.5, 2.0, 3.0, 3.5]
        );
        assert_eq!(mean_std(&[1.0, 3.0]), (2.0, 1.0));
    }
}
