//! SHPB processing round trip: bar signals built from a known rate-independent specimen
//! curve and a trapezoidal incident pulse (1D wave relations, specimen equilibrium),
//! delayed to the gauges, with baseline offsets and seeded noise, must give back the
//! exact stress-strain curve within 1 %.

use fitting::shpb::synthetic::{SyntheticSetup, SyntheticShpb};
use fitting::shpb::{
    analyze, analyze_with, record_with_late_gauges, synthetic_round_trip,
    synthetic_round_trip_with, Alignment, Processing, ShpbError,
};

#[test]
fn stress_strain_curve_comes_back_within_one_percent() {
    for seed in [1, 2, 3] {
        let setup = SyntheticSetup::steel_945_like(seed);
        let r = synthetic_round_trip(&setup).unwrap();
        let p = &r.analysis.plateau;
        println!(
            "seed {seed}: stress error 3w {:.2e} 1w {:.2e} 2w {:.2e}, strain error {:.2e}, \
             plateau rate {:.1} (exact {:.1}) 1/s, R {:.2e}",
            r.stress_error_3wave,
            r.stress_error_1wave,
            r.stress_error_2wave,
            r.strain_error,
            p.strain_rate_3wave_per_s,
            r.exact_plateau_rate_per_s,
            p.equilibrium_ratio
        );
        assert!(
            r.stress_error_3wave <= 0.01,
            "3-wave stress error {}",
            r.stress_error_3wave
        );
        assert!(
            r.stress_error_1wave <= 0.01,
            "1-wave stress error {}",
            r.stress_error_1wave
        );
        assert!(
            r.stress_error_2wave <= 0.01,
            "2-wave stress error {}",
            r.stress_error_2wave
        );
        assert!(r.strain_error <= 0.01, "strain error {}", r.strain_error);
        let rate_error = p.strain_rate_3wave_per_s / r.exact_plateau_rate_per_s - 1.0;
        assert!(rate_error.abs() <= 0.01, "plateau rate error {rate_error}");
        // The synthetic specimen is in equilibrium: R is noise only (< 2 % on the plateau).
        assert!(p.equilibrium_ratio < 0.02, "R = {}", p.equilibrium_ratio);
        // 1-wave rate equals the 3-wave rate under equilibrium.
        let one_wave = p.strain_rate_1wave_per_s / p.strain_rate_3wave_per_s - 1.0;
        assert!(one_wave.abs() < 0.01, "1-wave vs 3-wave rate {one_wave}");
    }
}

#[test]
fn baselines_and_time_shifts_are_recovered() {
    let setup = SyntheticSetup::steel_945_like(7);
    let synthetic = SyntheticShpb::generate(&setup);
    let a = analyze(&synthetic.experiment).unwrap();
    let p = &a.pulses;
    // Baselines within the noise band ±2 µε / √N of their true values.
    assert!(
        (p.baseline_incident - setup.baseline_incident).abs() < 0.2e-6,
        "{}",
        p.baseline_incident
    );
    assert!((p.baseline_transmitted - setup.baseline_transmitted).abs() < 0.2e-6);
    // Uniform noise on ±2 µε has standard deviation 2/√3 µε.
    let sigma = 2e-6 / 3f64.sqrt();
    assert!(
        (p.noise_incident / sigma - 1.0).abs() < 0.1,
        "{}",
        p.noise_incident
    );
    // d_i/c0 with c0 = √(210e9/7800) = 5188.75 m/s.
    let c0 = (210e9_f64 / 7800.0).sqrt();
    assert!((p.delay_incident_s - 1.020 / c0).abs() < 1e-15);
    // The incident front reaches the gauge at 60 µs: half amplitude 7.5 µs later.
    assert!(
        (p.incident_arrival_s - 67.5e-6).abs() < 0.5e-6,
        "{}",
        p.incident_arrival_s
    );
    // The face window starts before the load reaches the face, and ends after the pulse.
    assert!(p.window_at_faces_s.0 < synthetic.load_start_s);
    assert!(p.window_at_faces_s.1 > synthetic.load_start_s + setup.pulse.duration_s());
}

#[test]
fn a_record_without_a_pulse_is_an_error() {
    let mut setup = SyntheticSetup::steel_945_like(3);
    setup.pulse.amplitude = 1e-6; // under the ±2 µε noise
    let synthetic = SyntheticShpb::generate(&setup);
    let e = analyze(&synthetic.experiment).unwrap_err();
    assert!(matches!(e, ShpbError::NoIncidentPulse { .. }), "{e}");
}

/// A record whose pulses contradict the compression-negative convention is refused with
/// what was seen, never processed with the reflected pulse taken for the incident one
/// (the inverted record gave exit 0 and an equilibrium ratio of 1.74); a
/// reversed transmitted gauge alone is refused too.
#[test]
fn a_record_of_the_wrong_polarity_is_refused() {
    let synthetic = SyntheticShpb::generate(&SyntheticSetup::steel_945_like(5));
    assert!(analyze(&synthetic.experiment).is_ok());
    let negate = |v: &mut Vec<f64>| v.iter_mut().for_each(|x| *x = -*x);
    let mut inverted = synthetic.experiment.clone();
    negate(&mut inverted.incident);
    negate(&mut inverted.transmitted);
    let e = analyze(&inverted).unwrap_err();
    assert!(matches!(e, ShpbError::TensileIncidentPulse { .. }), "{e}");
    assert!(e.to_string().contains("compression-positive"), "{e}");
    let mut reversed = synthetic.experiment.clone();
    negate(&mut reversed.transmitted);
    let e = analyze(&reversed).unwrap_err();
    assert!(
        matches!(e, ShpbError::TensileTransmittedPulse { .. }),
        "{e}"
    );
}

/// Calibrated delays that differ from distance / c0 (here 2 % longer, as a calibrated
/// reflected time against √(E/ρ) in a published record) are used for timing: a record generated
/// with them processes back to its curve within 1 %; read with d/c0 instead, its
/// reflected pulse arrives 2 · 0.02 · d_i/c0 = 7.9 µs later, relative to the predicted
/// time, than with the delays stated (the arrival diagnostic reports it).
#[test]
fn calibrated_delays_align_the_pulses() {
    let mut setup = SyntheticSetup::steel_945_like(6);
    let bar = setup.bar.clone();
    setup.bar.incident_delay_calibrated_s = Some(1.02 * bar.incident_delay_s());
    setup.bar.transmitted_delay_calibrated_s = Some(1.02 * bar.transmitted_delay_s());
    let calibrated = synthetic_round_trip(&setup).unwrap();
    assert!(
        calibrated.stress_error_3wave < 0.01,
        "{}",
        calibrated.stress_error_3wave
    );
    let synthetic = SyntheticShpb::generate(&setup);
    let stated = analyze(&synthetic.experiment).unwrap().pulses;
    let mut uncalibrated = synthetic.experiment.clone();
    uncalibrated.bar.incident_delay_calibrated_s = None;
    uncalibrated.bar.transmitted_delay_calibrated_s = None;
    let p = analyze(&uncalibrated).unwrap().pulses;
    // the reflected pulse arrives 2 · 0.02 · d_i/c0 = 7.9 µs later than d/c0 predicts
    let expected = 2.0 * 0.02 * bar.incident_delay_s();
    let late = p.reflected_arrival_offset_s - stated.reflected_arrival_offset_s;
    assert!((late - expected).abs() < 0.1e-6, "{late} vs {expected}");
}

/// Alignment on a synthetic record with known delays: gauges whose travel times are 2 %
/// longer than d/c0, processed with d/c0. Reading the reflected pulse needs the extra
/// round trip 2 Δ_i, the transmitted one Δ_i + Δ_t; the force balance finds both within
/// 0.05 µs, 1.6 samples (the record is in equilibrium by construction).
#[test]
fn force_balance_finds_known_delays() {
    let (exp, needed) = record_with_late_gauges(10);
    // the shifts the late gauges need, from the bar itself
    let bar = SyntheticSetup::steel_945_like(10).bar;
    let (di, dt) = (bar.incident_delay_s(), bar.transmitted_delay_s());
    let balanced = Processing {
        alignment: Alignment::ForceBalance,
        ..Processing::default()
    };
    let a = analyze_with(&exp, balanced).unwrap();
    let (want_r, want_t) = (2.0 * 0.02 * di, 0.02 * (di + dt));
    assert!((needed.reflected_s - want_r).abs() < 1e-15);
    assert!(
        (a.shifts.reflected_s - want_r).abs() < 0.05e-6,
        "{} vs {want_r}",
        a.shifts.reflected_s
    );
    assert!(
        (a.shifts.transmitted_s - want_t).abs() < 0.05e-6,
        "{} vs {want_t}",
        a.shifts.transmitted_s
    );
}

/// Pulses that disperse between the gauges and the faces (Pochhammer-Chree, ν 0.29 on the
/// 20 mm bars over 1.02 and 0.77 m): corrected, the 3- and 1-wave stresses come back
/// within the 1 % of the non-dispersed round trip; uncorrected, the 3-wave stress is off
/// by more than 5 % (16 % measured) and the median R is 8 times larger.
#[test]
fn dispersion_correction_recovers_a_dispersed_record() {
    let mut setup = SyntheticSetup::steel_945_like(3);
    setup.dispersed = true;
    let corrected = Processing {
        dispersion: true,
        ..Processing::default()
    };
    let c = synthetic_round_trip_with(&setup, corrected).unwrap();
    let u = synthetic_round_trip(&setup).unwrap();
    println!(
        "corrected: 3w {:.4} 1w {:.4} 2w {:.4}, R {:.4}; uncorrected: 3w {:.4} 1w {:.4} 2w {:.4}, R {:.4}",
        c.stress_error_3wave,
        c.stress_error_1wave,
        c.stress_error_2wave,
        c.analysis.median_equilibrium_ratio(),
        u.stress_error_3wave,
        u.stress_error_1wave,
        u.stress_error_2wave,
        u.analysis.median_equilibrium_ratio()
    );
    assert!(c.stress_error_3wave < 0.01, "{}", c.stress_error_3wave);
    assert!(c.stress_error_1wave < 0.01, "{}", c.stress_error_1wave);
    assert!(u.stress_error_3wave > 0.05, "{}", u.stress_error_3wave);
    assert!(u.analysis.median_equilibrium_ratio() > 5.0 * c.analysis.median_equilibrium_ratio());
}

/// Honest windows: the steel-like specimen under the flat pulse holds its rate (94 % of
/// the loading phase within ±15 % of the plateau rate); a stiffly hardening one
/// (σ = 200 MPa + 6 GPa ε_p) does not: its rate falls from about 3070 to 2040 1/s as the
/// stress rises, 43 % of the loading phase is in the band, and the processing says there
/// is no constant-rate plateau (under the 50 % that a constant rate needs).
#[test]
fn a_hardening_specimen_has_no_constant_rate_plateau() {
    let steel = synthetic_round_trip(&SyntheticSetup::steel_945_like(1)).unwrap();
    assert!(steel.analysis.plateau.is_constant_rate());
    let mut setup = SyntheticSetup::steel_945_like(1);
    setup.curve.yield_stress_pa = 200e6;
    setup.curve.hardening_pa = 6e9;
    setup.curve.exponent = 1.0;
    let hardening = synthetic_round_trip(&setup).unwrap();
    let p = &hardening.analysis.plateau;
    println!(
        "steel in band {:.3}; hardening in band {:.3}, trend {:?}",
        steel.analysis.plateau.in_band_fraction, p.in_band_fraction, p.rate_trend_per_s
    );
    assert!(!p.is_constant_rate(), "{}", p.in_band_fraction);
    assert!(p.rate_change() < -0.25, "{}", p.rate_change());
}

/// A bar diameter in m where mm was meant (`"2 m"` for 20 mm) gives a plateau stress of
/// 10⁷ MPa: refused with the keys to check, as is a stress below 1 MPa.
#[test]
fn an_implausible_plateau_stress_names_the_diameters() {
    let synthetic = SyntheticShpb::generate(&SyntheticSetup::steel_945_like(5));
    let mut wide = synthetic.experiment.clone();
    wide.bar.diameter_m *= 100.0;
    match analyze(&wide).unwrap_err() {
        ShpbError::ImplausibleStress {
            stress_pa, likely, ..
        } => {
            assert!(stress_pa > 1e13, "{stress_pa}");
            assert!(likely.starts_with("bar.diameter too large"), "{likely}");
        }
        other => panic!("{other}"),
    }
    let mut thin = synthetic.experiment.clone();
    thin.bar.diameter_m /= 40.0;
    match analyze(&thin).unwrap_err() {
        ShpbError::ImplausibleStress {
            stress_pa, likely, ..
        } => {
            assert!(stress_pa < 1e6, "{stress_pa}");
            assert!(
                likely.starts_with("specimen.diameter too large"),
                "{likely}"
            );
        }
        other => panic!("{other}"),
    }
}
