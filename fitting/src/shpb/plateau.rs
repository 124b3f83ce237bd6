//! The strain-rate plateau of an SHPB test and the means over it.
//!
//! On the 1 µs moving average of the 3-wave strain rate, the loading phase is where it
//! exceeds half its maximum; its median there is the plateau rate m. The plateau runs
//! from the first to the last sample of the loading phase within ±15 % of m.

use super::error::ShpbError;
use super::pulses::SMOOTHING_S;
use super::signal::moving_average;
use std::ops::Range;

/// Relative band around the median rate that counts as plateau.
const TOLERANCE: f64 = 0.15;

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
        let smooth = moving_average(rate_3wave, ((SMOOTHING_S / dt).round() as usize).max(1));
        let max = smooth.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let mut loading: Vec<f64> = smooth.iter().cloned().filter(|&r| r >= 0.5 * max).collect();
        if max.is_nan() || max <= 0.0 || loading.len() < 2 {
            return Err(no_plateau());
        }
        loading.sort_by(f64::total_cmp);
        let median = loading[loading.len() / 2];
        let on =
            |k: usize| smooth[k] >= 0.5 * max && (smooth[k] - median).abs() <= TOLERANCE * median;
        let first = (0..n).find(|&k| on(k)).ok_or_else(no_plateau)?;
        let last = (0..n).rev().find(|&k| on(k)).ok_or_else(no_plateau)?;
        if last <= first {
            return Err(no_plateau());
        }
        let range = first..last + 1;
        let mean = |v: &[f64]| v[range.clone()].iter().sum::<f64>() / range.len() as f64;
        Ok(Plateau {
            strain_rate_3wave_per_s: mean(rate_3wave),
            strain_rate_1wave_per_s: mean(rate_1wave),
            stress_3wave_pa: mean(stress_3wave),
            equilibrium_ratio: mean(ratio),
            range,
        })
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
    }
}
