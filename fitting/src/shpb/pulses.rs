//! Baseline removal and pulse detection on the raw gauge records.
//!
//! The incident pulse is the first excursion of the incident gauge beyond half of the
//! record's largest one (on a 1 µs moving average); it must be compressive, and so must
//! the transmitted pulse: a record whose pulses contradict its declared polarity is an
//! error that says what was seen, never processed with the reflected pulse taken for the
//! incident one. Its start and end are where
//! it leaves and re-enters the band |ε − b| < max(5 s_n, 0.03 a) around the baseline b
//! (s_n: pre-trigger noise, a: pulse amplitude). The baseline of each gauge is the mean of
//! its samples before the incident pulse (less a margin); the noise is their standard
//! deviation.
//!
//! The analysis window at the specimen faces is the incident window (widened on both
//! sides by 10 % of the pulse duration) delayed by d_i/c0; the reflected and transmitted
//! pulses are read through the same window, delayed by −d_i/c0 and −d_t/c0 (or by the
//! bar's calibrated delays, `Bar::incident_delay_s`). The measured
//! half-amplitude arrival of each of them is compared with the arrival that the gauge
//! distances and c0 predict, as a diagnostic of the time shift.

use super::error::ShpbError;
use super::signal::{mean_std, moving_average};
use crate::experiment::ShpbExperiment;

/// Moving-average length used to find pulses [s].
pub const SMOOTHING_S: f64 = 1e-6;

/// `SMOOTHING_S` in samples of interval `dt` [s] (at least one).
pub fn smoothing_width(dt: f64) -> usize {
    ((SMOOTHING_S / dt).round() as usize).max(1)
}
/// Margin on each side of the incident window, as a fraction of the pulse duration.
const MARGIN_FRACTION: f64 = 0.1;
/// Samples needed before the incident pulse to estimate the baseline.
const MIN_PRE_TRIGGER: usize = 16;

/// Where the pulses are, in the record's time base [s], and the baselines removed.
#[derive(Debug, Clone, PartialEq)]
pub struct PulseWindows {
    /// Incident pulse on the incident gauge: (start, end) [s], without margins.
    pub incident_at_gauge_s: (f64, f64),
    /// Half-amplitude crossing of the incident pulse's rising edge at the gauge [s].
    pub incident_arrival_s: f64,
    /// Analysis window at the specimen faces: (start, end) [s], with margins.
    pub window_at_faces_s: (f64, f64),
    /// Travel times d_i/c0 and d_t/c0 from the gauges to the specimen faces [s].
    pub delay_incident_s: f64,
    pub delay_transmitted_s: f64,
    /// Baselines removed from the incident and transmitted gauges [strain].
    pub baseline_incident: f64,
    pub baseline_transmitted: f64,
    /// Pre-trigger noise (standard deviation) of both gauges [strain].
    pub noise_incident: f64,
    pub noise_transmitted: f64,
    /// Incident pulse amplitude (peak of the 1 µs average, above the baseline) [strain].
    pub incident_amplitude: f64,
    /// Measured minus predicted half-amplitude arrival of the reflected pulse at the
    /// incident gauge and of the transmitted pulse at its gauge [s].
    pub reflected_arrival_offset_s: f64,
    pub transmitted_arrival_offset_s: f64,
}

/// Find the pulses of `exp` and the baselines of both gauges.
pub fn detect_pulses(exp: &ShpbExperiment) -> Result<PulseWindows, ShpbError> {
    let name = || exp.name.clone();
    let t = &exp.time_s;
    let n = t.len();
    let dt = (t[n - 1] - t[0]) / (n - 1) as f64;
    let width = smoothing_width(dt);
    let delay_incident_s = exp.bar.incident_delay_s();
    let delay_transmitted_s = exp.bar.transmitted_delay_s();

    // First estimate of baseline and noise from the first 5 % of the record.
    let head = &exp.incident[..(n / 20).max(MIN_PRE_TRIGGER).min(n)];
    let (b0, noise0) = mean_std(head);
    let smooth: Vec<f64> = moving_average(&exp.incident, width)
        .iter()
        .map(|v| v - b0)
        .collect();
    let global = smooth.iter().cloned().fold(0.0, f64::min);
    let tensile = smooth.iter().cloned().fold(0.0, f64::max);
    let largest = tensile.max(-global);
    if let Some(first) = smooth.iter().position(|v| v.abs() > 0.5 * largest) {
        if smooth[first] > 0.0 && tensile > 10.0 * noise0 {
            return Err(ShpbError::TensileIncidentPulse {
                name: name(),
                time_s: t[first],
                peak: tensile,
                compressive_peak: -global,
            });
        }
    }
    if -global < 10.0 * noise0 {
        return Err(ShpbError::NoIncidentPulse {
            name: name(),
            amplitude: -global,
            noise: noise0,
        });
    }
    // The first excursion beyond half the largest one, and its own peak.
    let half_start = smooth.iter().position(|&v| v < 0.5 * global).unwrap_or(0);
    let half_end = (half_start..n)
        .find(|&i| smooth[i] > 0.5 * global)
        .unwrap_or(n);
    let amplitude = -smooth[half_start..half_end]
        .iter()
        .cloned()
        .fold(0.0, f64::min);
    let band = (5.0 * noise0).max(0.03 * amplitude);
    let start = (0..half_start)
        .rev()
        .find(|&i| smooth[i] > -band)
        .unwrap_or(0);
    let end = (half_end..n).find(|&i| smooth[i] > -band).unwrap_or(n - 1);
    let margin = MARGIN_FRACTION * (t[end] - t[start]);

    // Baselines and noise from the samples before the pulse and its margin.
    let pre = t.partition_point(|&s| s < t[start] - margin);
    if pre < MIN_PRE_TRIGGER {
        return Err(ShpbError::NoPreTrigger {
            name: name(),
            start,
            needed: MIN_PRE_TRIGGER,
        });
    }
    let (baseline_incident, noise_incident) = mean_std(&exp.incident[..pre]);
    let (baseline_transmitted, noise_transmitted) = mean_std(&exp.transmitted[..pre]);

    let gauge = (t[start] - margin, t[end] + margin);
    let round_trip = 2.0 * delay_incident_s;
    if gauge.1 - gauge.0 >= round_trip {
        return Err(ShpbError::PulsesOverlap {
            name: name(),
            duration_s: gauge.1 - gauge.0,
            round_trip_s: round_trip,
        });
    }
    let faces = (gauge.0 + delay_incident_s, gauge.1 + delay_incident_s);
    for (pulse, needed_s) in [
        ("reflected", faces.1 + delay_incident_s),
        ("transmitted", faces.1 + delay_transmitted_s),
    ] {
        if needed_s > t[n - 1] {
            return Err(ShpbError::RecordTooShort {
                name: name(),
                pulse,
                end_s: t[n - 1],
                needed_s,
            });
        }
    }

    check_transmitted_sign(
        exp,
        width,
        (
            gauge.0 + delay_incident_s + delay_transmitted_s,
            gauge.1 + delay_incident_s + delay_transmitted_s,
        ),
        baseline_transmitted,
        noise_transmitted,
    )?;
    let incident_arrival_s = crossing(t, &smooth, half_start, 0.5 * global);
    let arrival = |values: &[f64], baseline: f64, shift: f64, sign: f64| {
        let s: Vec<f64> = moving_average(values, width)
            .iter()
            .map(|v| sign * (v - baseline))
            .collect();
        let lo = t.partition_point(|&x| x < gauge.0 + shift);
        let hi = t.partition_point(|&x| x <= gauge.1 + shift);
        let peak = s[lo..hi].iter().cloned().fold(0.0, f64::max);
        let first = (lo..hi).find(|&i| s[i] > 0.5 * peak).unwrap_or(lo);
        crossing(t, &s, first, 0.5 * peak) - (incident_arrival_s + shift)
    };
    let reflected_arrival_offset_s = arrival(&exp.incident, baseline_incident, round_trip, 1.0);
    let transmitted_arrival_offset_s = arrival(
        &exp.transmitted,
        baseline_transmitted,
        delay_incident_s + delay_transmitted_s,
        -1.0,
    );
    Ok(PulseWindows {
        incident_at_gauge_s: (t[start], t[end]),
        incident_arrival_s,
        window_at_faces_s: faces,
        delay_incident_s,
        delay_transmitted_s,
        baseline_incident,
        baseline_transmitted,
        noise_incident,
        noise_transmitted,
        incident_amplitude: amplitude,
        reflected_arrival_offset_s,
        transmitted_arrival_offset_s,
    })
}

/// The transmitted pulse, in its `window` at the gauge [s], must be compressive: a larger
/// tensile than compressive excursion, beyond 10 times the noise, is a reversed gauge.
fn check_transmitted_sign(
    exp: &ShpbExperiment,
    width: usize,
    window: (f64, f64),
    baseline: f64,
    noise: f64,
) -> Result<(), ShpbError> {
    let t = &exp.time_s;
    let lo = t.partition_point(|&x| x < window.0);
    let hi = t.partition_point(|&x| x <= window.1);
    let smooth = moving_average(&exp.transmitted, width);
    let (low, high) = smooth[lo..hi].iter().fold((0.0_f64, 0.0_f64), |(a, b), v| {
        (a.min(v - baseline), b.max(v - baseline))
    });
    if high > -low && high > 10.0 * noise {
        return Err(ShpbError::TensileTransmittedPulse {
            name: exp.name.clone(),
            window_s: window,
            peak: high,
            compressive_peak: -low,
        });
    }
    Ok(())
}

/// Time at which `s` crosses `level` between samples `i − 1` and `i` (linear).
fn crossing(t: &[f64], s: &[f64], i: usize, level: f64) -> f64 {
    if i == 0 {
        return t[0];
    }
    let (a, b) = (s[i - 1], s[i]);
    let w = if b != a {
        ((level - a) / (b - a)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    t[i - 1] + w * (t[i] - t[i - 1])
}
