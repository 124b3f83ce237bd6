//! The SHPB processing checked against a synthetic record whose specimen history is
//! known exactly (`synthetic`): the processed stress, strain and strain rate against the
//! exact ones. The library's tests and the verification table use it.

use super::alignment::Shifts;
use super::analysis::{analyze_with, Processing, ShpbAnalysis};
use super::synthetic::{SyntheticSetup, SyntheticShpb};
use super::ShpbError;
use crate::experiment::ShpbExperiment;

/// Errors of the processed record against the exact synthetic specimen history.
#[derive(Debug, Clone)]
pub struct RoundTrip {
    pub analysis: ShpbAnalysis,
    /// Max over the plastic loading phase of |σ − σ_exact(ε)| / σ_exact(ε), for the
    /// 3-wave, 1-wave (back) and 2-wave (front) stress at the processed strain ε.
    pub stress_error_3wave: f64,
    pub stress_error_1wave: f64,
    pub stress_error_2wave: f64,
    /// Max |ε − ε_exact| over the loading phase, relative to the maximum exact strain.
    pub strain_error: f64,
    /// Mean exact strain rate over the processed plateau [1/s].
    pub exact_plateau_rate_per_s: f64,
}

/// Process a synthetic record (default processing) and compare it with the exact history.
pub fn synthetic_round_trip(setup: &SyntheticSetup) -> Result<RoundTrip, ShpbError> {
    synthetic_round_trip_with(setup, Processing::default())
}

/// Process a synthetic record with `processing` and compare it with the exact history.
pub fn synthetic_round_trip_with(
    setup: &SyntheticSetup,
    processing: Processing,
) -> Result<RoundTrip, ShpbError> {
    let synthetic = SyntheticShpb::generate(setup);
    let analysis = analyze_with(&synthetic.experiment, processing)?;
    let window_start = analysis.pulses.window_at_faces_s.0;
    let exact_time = &synthetic.time_s;
    let (peak, max_strain) =
        synthetic.strain.iter().enumerate().fold(
            (0, 0.0),
            |best, (k, &e)| if e > best.1 { (k, e) } else { best },
        );
    let loading_end = exact_time[peak];
    let exact_strain = |t: f64| {
        super::signal::interpolate(exact_time, &synthetic.strain, t.clamp(0.0, loading_end))
    };
    let curve = setup.curve;
    let plastic_from = 2.0 * curve.yield_stress_pa / curve.elastic_modulus_pa;

    let (mut e3, mut e1, mut e2, mut strain_error) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for (k, &t) in analysis.time_s.iter().enumerate() {
        let tau = window_start + t - synthetic.load_start_s;
        if tau > loading_end {
            break;
        }
        let strain = analysis.strain[k];
        strain_error = strain_error.max((strain - exact_strain(tau)).abs() / max_strain);
        if strain >= plastic_from {
            let exact = curve.loading_stress(strain);
            e3 = e3.max((analysis.stress_3wave_pa[k] / exact - 1.0).abs());
            e1 = e1.max((analysis.stress_1wave_pa[k] / exact - 1.0).abs());
            e2 = e2.max((analysis.stress_2wave_pa[k] / exact - 1.0).abs());
        }
    }
    let dt = analysis.time_s[1] - analysis.time_s[0];
    let range = analysis.plateau.range.clone();
    let strain_at = |k: usize| exact_strain(window_start + k as f64 * dt - synthetic.load_start_s);
    let exact_plateau_rate_per_s =
        (strain_at(range.end - 1) - strain_at(range.start)) / ((range.len() - 1) as f64 * dt);
    Ok(RoundTrip {
        analysis,
        stress_error_3wave: e3,
        stress_error_1wave: e1,
        stress_error_2wave: e2,
        strain_error,
        exact_plateau_rate_per_s,
    })
}

/// A synthetic record whose gauges sit 2 % further in time than d/c0, with the delays
/// forgotten (read with d/c0), and the shifts its reads need: the reflected one the
/// extra round trip 2 Δ_i, the transmitted one Δ_i + Δ_t.
pub fn record_with_late_gauges(seed: u64) -> (ShpbExperiment, Shifts) {
    let mut setup = SyntheticSetup::steel_945_like(seed);
    let (di, dt) = (
        setup.bar.incident_delay_s(),
        setup.bar.transmitted_delay_s(),
    );
    setup.bar.incident_delay_calibrated_s = Some(1.02 * di);
    setup.bar.transmitted_delay_calibrated_s = Some(1.02 * dt);
    let mut exp = SyntheticShpb::generate(&setup).experiment;
    exp.bar.incident_delay_calibrated_s = None;
    exp.bar.transmitted_delay_calibrated_s = None;
    let needed = Shifts {
        reflected_s: 2.0 * 0.02 * di,
        transmitted_s: 0.02 * (di + dt),
    };
    (exp, needed)
}
