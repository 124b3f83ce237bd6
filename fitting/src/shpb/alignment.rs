//! How the reflected and transmitted pulses are placed in time against the incident one.
//!
//! The geometric alignment reads them delayed by the gauge travel times alone
//! (`Bar::incident_delay_s`). Two corrections add a shift δ to each read (positive: the
//! pulse is read later):
//! - `arrival`: the measured minus the predicted half-amplitude arrival of each pulse
//!   (`PulseWindows`); for a hardening specimen the reflected pulse has no edge that
//!   matches the incident one's, so this is a diagnostic more than a method;
//! - `force-balance`: the (δ_r, δ_t) that minimize Σ (ε_i + ε_r(δ_r) − ε_t(δ_t))², i.e.
//!   Σ (F1 − F2)² / (E A)², over the incident pulse (where ε_i exceeds half its peak), on a
//!   0.25 µs grid within ±`MAX_SHIFT_S`, refined to 0.01 µs around the best point. The
//!   data's source tool aligns this way.

use super::gauges::{GaugeSignals, Pulse};
use super::pulses::PulseWindows;
pub use crate::experiment::processing::Alignment;

/// Largest shift searched by the force balance [s].
pub const MAX_SHIFT_S: f64 = 10e-6;
const COARSE_S: f64 = 0.25e-6;
const FINE_S: f64 = 0.01e-6;

/// Shifts added to the geometric reads of the reflected and transmitted pulses [s].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Shifts {
    pub reflected_s: f64,
    pub transmitted_s: f64,
}

/// The shifts of `alignment` for the gauge signals with their detected `pulses`, read
/// at the face times `face_times` [s].
pub fn shifts(
    alignment: Alignment,
    gauges: &GaugeSignals,
    pulses: &PulseWindows,
    face_times: &[f64],
) -> Shifts {
    match alignment {
        Alignment::Geometric => Shifts::default(),
        Alignment::Arrival => Shifts {
            reflected_s: pulses.reflected_arrival_offset_s,
            transmitted_s: pulses.transmitted_arrival_offset_s,
        },
        Alignment::ForceBalance => force_balance(gauges, face_times),
    }
}

fn force_balance(gauges: &GaugeSignals, face_times: &[f64]) -> Shifts {
    let all = gauges.read(Pulse::Incident, face_times, 0.0);
    let peak = all.iter().cloned().fold(0.0, f64::max);
    let (body, eps_i): (Vec<f64>, Vec<f64>) = face_times
        .iter()
        .zip(&all)
        .filter(|(_, e)| **e > 0.5 * peak)
        .unzip();
    let misfit = |r: &[f64], t: &[f64]| -> f64 {
        (0..eps_i.len())
            .map(|k| (eps_i[k] + r[k] - t[k]).powi(2))
            .sum()
    };
    let best = |centre: Shifts, step: f64, half: f64| -> Shifts {
        let n = (half / step).round() as i64;
        let grid = |c: f64| (-n..=n).map(move |k| c + k as f64 * step);
        let r: Vec<(f64, Vec<f64>)> = grid(centre.reflected_s)
            .map(|d| (d, gauges.read(Pulse::Reflected, &body, d)))
            .collect();
        let t: Vec<(f64, Vec<f64>)> = grid(centre.transmitted_s)
            .map(|d| (d, gauges.read(Pulse::Transmitted, &body, d)))
            .collect();
        let mut found = (f64::INFINITY, centre);
        for (dr, rv) in &r {
            for (dt, tv) in &t {
                let m = misfit(rv, tv);
                if m < found.0 {
                    found = (
                        m,
                        Shifts {
                            reflected_s: *dr,
                            transmitted_s: *dt,
                        },
                    );
                }
            }
        }
        found.1
    };
    let coarse = best(Shifts::default(), COARSE_S, MAX_SHIFT_S);
    best(coarse, FINE_S, COARSE_S)
}
