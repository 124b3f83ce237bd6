//! Repeatability of runs that differ only in the grid shift's seed (thesis §12.3,
//! fig. 12.19): per sample time, the mean and the sample standard deviation (n − 1) of a
//! force over the runs, and CV(t) = std/mean. The thesis judges CV below 0.3 acceptable.

/// Per-sample statistics of several runs' force histories on the same time samples.
#[derive(Debug, Clone, PartialEq)]
pub struct Spread {
    pub mean: Vec<f64>,
    /// Sample standard deviation (n − 1 in the denominator).
    pub std: Vec<f64>,
    /// std / |mean| (NaN where the mean is zero).
    pub cv: Vec<f64>,
}

/// The spread of `runs` (each a force history) over their common length; at least two.
pub fn spread(runs: &[Vec<f64>]) -> Option<Spread> {
    if runs.len() < 2 {
        return None;
    }
    let n = runs.iter().map(Vec::len).min()?;
    let k = runs.len() as f64;
    let mut out = Spread {
        mean: Vec::with_capacity(n),
        std: Vec::with_capacity(n),
        cv: Vec::with_capacity(n),
    };
    for i in 0..n {
        let mean = runs.iter().map(|r| r[i]).sum::<f64>() / k;
        let var = runs.iter().map(|r| (r[i] - mean).powi(2)).sum::<f64>() / (k - 1.0);
        out.mean.push(mean);
        out.std.push(var.sqrt());
        out.cv.push(match mean == 0.0 {
            true => f64::NAN,
            false => var.sqrt() / mean.abs(),
        });
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three runs 1, 2, 3 at every sample: mean 2, sample std 1, CV 0.5; a zero mean gives
    /// NaN; one run gives no spread.
    #[test]
    fn spread_uses_the_sample_standard_deviation() {
        let s = spread(&[vec![1.0, 0.0], vec![2.0, 0.0], vec![3.0, 0.0, 9.0]]).unwrap();
        assert_eq!(s.mean, [2.0, 0.0]);
        assert_eq!(s.std, [1.0, 0.0]);
        assert_eq!(s.cv[0], 0.5);
        assert!(s.cv[1].is_nan());
        assert!(spread(&[vec![1.0]]).is_none());
    }
}
