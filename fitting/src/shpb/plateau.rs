//! The strain-rate plateau of an SHPB test and the means over it.
//!
//! On the 1 µs moving average of the 3-wave strain rate, the loading phase is where it
//! exceeds half its maximum; its median there is the plateau rate m. The plateau runs
//! from the first to the last sample of the loading phase within ±15 % of m.
//!
//! Whether the rate is constant there is a result, not an assumption. The plateau holds
//! a constant rate when at least `MIN_IN_BAND` of the loading phase lies within the band
//! (`in_band_fraction`). A rate that falls linearly through the loading phase to half its
//! peak (a hardening specimen under a flat pulse) spends 45 % of it in the band, and a
//! mean rate or stress over the window then describes nothing: the report says so and
//! gives the histories.
//! The least-squares line through the averaged rate over the plateau gives its rate at
//! the start and the end (`rate_trend_per_s`), reported either way.

use super::error::ShpbError;
use super::filter::polynomial_trend;
use super::pulses::smoothing_width;
use super::signal::moving_average;
use std::ops::Range;

/// Relative band around the median rate that counts as plateau.
pub const TOLERANCE: f64 = 0.15;
/// Smallest fraction of the loading phase within the band for a constant-rate test:
/// above the 45 % of a linear fall to half the peak rate.
pub const MIN_IN_BAND: f64 = 0.5;

#[derive(Debug, Clone, PartialEq)]
pub struct Plateau {
    /// Samples on the plateau.
    pub range: Range<usize>,
    /// Mean 3-wave strain rate on the plateau [1/s].
    pub strain_rate_3wave_per_s: f64,
    /// Mean 1-wave (reflected-only) strain rate on the plateau [1/s].
    pub strain_rate_1wave_per_s: f64,
    /// Mean 3-wave engineering stress on the plateau [Pa].
    pub stress_3wave_pa: f64,
    /// Mean equilibrium ratio R on the plateau [-].
    pub equilibrium_ratio: f64,
    /// Least-squares line through the averaged 3-wave rate over the plateau, at its first
    /// and last sample [1/s].
    pub rate_trend_per_s: (f64, f64),
    /// Median m of the averaged 3-wave rate over the loading phase [1/s].
    pub median_rate_per_s: f64,
    /// Fraction of the loading phase (rate above half its maximum) within ±`TOLERANCE`
    /// of the plateau rate m [-].
    pub in_band_fraction: f64,
}

impl Plateau {
    pub fn find(
        name: &str,
        time_s: &[f64],
        rate_3wave: &[f64],
        rate_1wave: &[f64],
        stress_3wave: &[f64],
        ratio: &[f64],
    ) -> Result<Plateau, ShpbError> {
        let n = time_s.len();
        let no_plateau = || ShpbError::NoPlateau {
            name: name.to_string(),
        };
        if n < 2 {
            return Err(no_plateau());
        }
        let dt = (time_s[n - 1] - time_s[0]) / (n - 1) as f64;
        let smooth = moving_average(rate_3wave, smoothing_width(dt));
        let max = smooth.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let mut loading: Vec<f64> = smooth.iter().cloned().filter(|&r| r >= 0.5 * max).collect();
        if max.is_nan() || max <= 0.0 || loading.len() < 2 {
            return Err(no_plateau());
        }
        loading.sort_by(f64::total_cmp);
        let median = loading[loading.len() / 2];
        let on =
            |k: usize| smooth[k] >= 0.5 * max && (smooth[k] - median).abs() <= TOLERANCE * median;
        let in_band_fraction = (0..n).filter(|&k| on(k)).count() as f64 / loading.len() as f64;
        let first = (0..n).find(|&k| on(k)).ok_or_else(no_plateau)?;
        let last = (0..n).rev().find(|&k| on(k)).ok_or_else(no_plateau)?;
        if last <= first {
            return Err(no_plateau());
        }
        let range = first..last + 1;
        let mean = |v: &[f64]| v[range.clone()].iter().sum::<f64>() / range.len() as f64;
        let trend = polynomial_trend(&smooth[range.clone()], 1);
        Ok(Plateau {
            rate_trend_per_s: (trend[0], trend[trend.len() - 1]),
            in_band_fraction,
            median_rate_per_s: median,
            strain_rate_3wave_per_s: mean(rate_3wave),
            strain_rate_1wave_per_s: mean(rate_1wave),
            stress_3wave_pa: mean(stress_3wave),
            equilibrium_ratio: mean(ratio),
            range,
        })
    }
}

impl Plateau {
    /// Change of the trend rate across the plateau, relative to the mean rate [-].
    pub fn rate_change(&self) -> f64 {
        let (start, end) = self.rate_trend_per_s;
        (end - start) / self.strain_rate_3wave_per_s
    }

    /// Whether the test held a constant rate: at least `MIN_IN_BAND` of its loading phase
    /// within the band.
    pub fn is_constant_rate(&self) -> bool {
        self.in_band_fraction >= MIN_IN_BAND
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trapezoidal_rate_gives_its_flat_top() {
        // Rate 0 → 1000/s over 10 µs, flat 1000/s for 80 µs, back to 0 over 10 µs;
        // sampled every 0.1 µs. The flat top and the ramps above 850/s are the plateau.
        let dt = 1e-7;
        let time: Vec<f64> = (0..1001).map(|k| k as f64 * dt).collect();
        let rate: Vec<f64> = time
            .iter()
            .map(|&t| 1000.0 * (t / 10e-6).min(1.0).min((100e-6 - t) / 10e-6).max(0.0))
            .collect();
        let stress = vec![5e8; time.len()];
        let p = Plateau::find(
            "trapezoid",
            &time,
            &rate,
            &rate,
            &stress,
            &vec![0.0; time.len()],
        )
        .unwrap();
        // Edges at rate 850/s: t = 8.5 µs and 91.5 µs, within one sample.
        assert!(
            (p.range.start as f64 * dt - 8.5e-6).abs() <= 1.01 * dt,
            "{:?}",
            p.range
        );
        assert!(
            ((p.range.end - 1) as f64 * dt - 91.5e-6).abs() <= 1.01 * dt,
            "{:?}",
            p.range
        );
        // Mean rate over [8.5, 91.5] µs: (80·1000 + 2·1.5·925)/83 = 991.6/s.
        let expected = (80.0 * 1000.0 + 2.0 * 1.5 * 925.0) / 83.0;
        assert!(
            (p.strain_rate_3wave_per_s - expected).abs() < 0.005 * expected,
            "{}",
            p.strain_rate_3wave_per_s
        );
        assert_eq!(p.stress_3wave_pa, 5e8);
        // the flat top and the ramps above 850/s are in the band: 83 of the 90 µs above
        // half the maximum
        assert!(
            (p.in_band_fraction - 83.0 / 90.0).abs() < 0.01,
            "{}",
            p.in_band_fraction
        );
        assert!(p.is_constant_rate());
    }

    /// A rate that falls linearly from 5300 to 2000 1/s over 22 µs (a published copper
    /// record) has no constant-rate plateau: the loading phase runs 5300 → 2650 1/s
    /// around the median 3975, and the ±15 % band holds 1192/2650 = 45 % of it. The
    /// trend of a line is the line itself.
    #[test]
    fn a_falling_rate_has_no_plateau() {
        let dt = 1e-7;
        let time: Vec<f64> = (0..=220).map(|k| k as f64 * dt).collect();
        let rate: Vec<f64> = time.iter().map(|&t| 5300.0 - 3300.0 * t / 22e-6).collect();
        let zeros = vec![0.0; time.len()];
        let p = Plateau::find("ramp", &time, &rate, &rate, &zeros, &zeros).unwrap();
        let at = |k: usize| 5300.0 - 3300.0 * k as f64 * dt / 22e-6;
        // the band lies inside the record, where the 1 µs average of a line is the line
        let (start, end) = p.rate_trend_per_s;
        assert!((start - at(p.range.start)).abs() < 1e-6, "{start}");
        assert!((end - at(p.range.end - 1)).abs() < 1e-6, "{end}");
        assert!(
            (p.in_band_fraction - 0.45).abs() < 0.02,
            "{}",
            p.in_band_fraction
        );
        assert!(!p.is_constant_rate());
    }
}
