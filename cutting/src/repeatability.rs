//! Repeatability of runs that differ only in the grid shift's seed (thesis §12.3,
//! fig. 12.19): per sample time, the mean and the sample standard deviation (n − 1) of a
//! force over the runs, and CV(t) = std/mean. The thesis judges CV below 0.3 acceptable.
//!
//! Runs at different discretizations (the sets of table 12.2) do not share their time
//! samples; they are compared on the mean force per bin of relative feed
//! (`binned_by_feed`), and two such curves by their distance: the RMS of their difference
//! over the RMS of the first (`curve_distance`; 0 for one curve, 1 for a curve and zero).

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

/// The mean of `force` per bin of relative feed: `bins` equal bins from `from` to `to`,
/// the feed of each sample `feed[k]`; `None` if a bin has no sample.
pub fn binned_by_feed(
    feed: &[f64],
    force: &[f64],
    from: f64,
    to: f64,
    bins: usize,
) -> Option<Vec<f64>> {
    let width = (to - from) / bins as f64;
    let mut sum = vec![0.0; bins];
    let mut count = vec![0usize; bins];
    for (f, v) in feed.iter().zip(force) {
        let bin = ((f - from) / width).floor();
        if bin >= 0.0 && (bin as usize) < bins {
            sum[bin as usize] += v;
            count[bin as usize] += 1;
        }
    }
    (count.iter().all(|&c| c > 0))
        .then(|| sum.iter().zip(&count).map(|(s, &c)| s / c as f64).collect())
}

/// RMS(b − a) / RMS(a) over two curves of equal length (module docs).
pub fn curve_distance(a: &[f64], b: &[f64]) -> Option<f64> {
    if a.len() != b.len() || a.is_empty() {
        return None;
    }
    let rms = |v: &mut dyn Iterator<Item = f64>| -> f64 {
        let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x * x, n + 1));
        (s / n as f64).sqrt()
    };
    let scale = rms(&mut a.iter().copied());
    (scale > 0.0).then(|| rms(&mut a.iter().zip(b).map(|(x, y)| y - x)) / scale)
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

    /// Samples at feeds 0.05 ... 0.95 with forces equal to their feed: two bins over
    /// [0, 1] hold the means 0.25 and 0.75; a bin without samples gives nothing.
    #[test]
    fn binned_force_is_the_mean_per_bin() {
        let feed: Vec<f64> = (0..10).map(|k| 0.05 + 0.1 * k as f64).collect();
        let b = binned_by_feed(&feed, &feed, 0.0, 1.0, 2).unwrap();
        assert!(
            (b[0] - 0.25).abs() < 1e-12 && (b[1] - 0.75).abs() < 1e-12,
            "{b:?}"
        );
        assert!(binned_by_feed(&feed, &feed, 0.0, 1.0, 20).is_none());
    }

    /// A curve against itself: 0; against zero: 1; against itself plus 10 % of it: 0.1.
    #[test]
    fn curve_distance_is_relative_rms() {
        let a = [1.0, -2.0, 3.0];
        assert_eq!(curve_distance(&a, &a), Some(0.0));
        assert_eq!(curve_distance(&a, &[0.0; 3]), Some(1.0));
        let b: Vec<f64> = a.iter().map(|x| 1.1 * x).collect();
        assert!((curve_distance(&a, &b).unwrap() - 0.1).abs() < 1e-12);
        assert!(curve_distance(&a, &[1.0]).is_none());
    }
}
