//! One-dimensional wave analysis of an SHPB record (DESIGN 7.1), compression positive.
//!
//! With ε_i, ε_r, ε_t the incident, reflected and transmitted bar strains shifted to the
//! specimen faces (compression positive), bar modulus E_b, area A_b, wave speed c0,
//! specimen area A_s and length L_s:
//! - face velocities v1 = c0 (ε_i − ε_r), v2 = c0 ε_t; relative velocity v1 − v2 [m/s]
//! - face forces F1 = E_b A_b (ε_i + ε_r), F2 = E_b A_b ε_t [N]
//! - stresses: 2-wave (front) F1/A_s, 1-wave (back) F2/A_s, 3-wave (F1 + F2)/(2 A_s) [Pa]
//! - strain rate 3-wave ε̇ = c0 (ε_i − ε_r − ε_t)/L_s, 1-wave ε̇ = −2 c0 ε_r/L_s [1/s]
//! - engineering strain ε = ∫ ε̇ dt (3-wave), specimen length L = L_s (1 − ε) [m]
//! - true strain ln(L_s/L) = −ln(1 − ε), true stress σ (1 − ε) (constant volume)
//! - equilibrium ratio R = 2 |F1 − F2| / |F1 + F2| [-]
//!
//! Time runs from the start of the analysis window at the faces (ε = 0 there). The
//! reflected and transmitted pulses are placed by the record's `Processing`: its
//! alignment (`shpb::alignment`) and, if chosen, the dispersion correction
//! (`shpb::gauges`).

use super::alignment::{self, Shifts};
use super::error::ShpbError;
use super::filter::polynomial_trend;
use super::gauges::{GaugeSignals, Pulse};
use super::plateau::Plateau;
use super::pulses::{detect_pulses, smoothing_width, PulseWindows};
use super::signal::{cumulative_integral, mean_std, moving_average};
use crate::experiment::limits::SIGNAL_SAMPLES;
pub use crate::experiment::processing::Processing;
use crate::experiment::ShpbExperiment;
use std::path::Path;

/// Histories at the specimen faces, sampled at the record's mean sampling interval.
#[derive(Debug, Clone)]
pub struct ShpbAnalysis {
    pub name: String,
    /// Time since the start of the analysis window at the specimen faces [s].
    pub time_s: Vec<f64>,
    /// Bar strains at the faces, compression positive [-].
    pub incident: Vec<f64>,
    pub reflected: Vec<f64>,
    pub transmitted: Vec<f64>,
    /// Incident-face velocity v1 and transmitted-face velocity v2 [m/s].
    pub velocity_front_m_per_s: Vec<f64>,
    pub velocity_back_m_per_s: Vec<f64>,
    /// Relative face velocity v1 − v2 = c0 (ε_i − ε_r − ε_t) [m/s].
    pub relative_velocity_m_per_s: Vec<f64>,
    /// Face forces F1 (incident side) and F2 (transmitted side), compression positive [N].
    pub force_front_n: Vec<f64>,
    pub force_back_n: Vec<f64>,
    /// Engineering stresses, compression positive [Pa].
    pub stress_1wave_pa: Vec<f64>,
    pub stress_2wave_pa: Vec<f64>,
    pub stress_3wave_pa: Vec<f64>,
    /// Strain rates, compression positive [1/s].
    pub strain_rate_3wave_per_s: Vec<f64>,
    pub strain_rate_1wave_per_s: Vec<f64>,
    /// Engineering strain from the 3-wave rate, compression positive [-].
    pub strain: Vec<f64>,
    /// True (logarithmic) strain and true 3-wave stress, compression positive.
    pub true_strain: Vec<f64>,
    pub true_stress_pa: Vec<f64>,
    /// Specimen length L(t) [m].
    pub specimen_length_m: Vec<f64>,
    /// R = 2 |F1 − F2| / |F1 + F2| [-].
    pub equilibrium_ratio: Vec<f64>,
    pub pulses: PulseWindows,
    /// How the reflected and transmitted pulses were placed, and the shifts it added.
    pub processing: Processing,
    pub shifts: Shifts,
    pub plateau: Plateau,
}

/// Process the raw record as its TOML asks (`ShpbExperiment::processing`).
pub fn analyze(exp: &ShpbExperiment) -> Result<ShpbAnalysis, ShpbError> {
    analyze_with(exp, exp.processing)
}

/// Process the raw record: baselines, pulses, gauge signals at the faces
/// (`processing`), wave analysis, plateau.
pub fn analyze_with(
    exp: &ShpbExperiment,
    processing: Processing,
) -> Result<ShpbAnalysis, ShpbError> {
    let pulses = detect_pulses(exp)?;
    let t = &exp.time_s;
    let n = t.len();
    let dt = (t[n - 1] - t[0]) / (n - 1) as f64;
    let (start, end) = pulses.window_at_faces_s;
    let samples = SIGNAL_SAMPLES
        .check(((end - start) / dt).floor() + 1.0, || {
            format!("the window at the faces {start:e} .. {end:e} s at the record's mean sampling interval {dt:e} s")
        })
        .map_err(|source| ShpbError::TooLarge {
            name: exp.name.clone(),
            source,
        })?;
    let face_times: Vec<f64> = (0..samples).map(|k| start + k as f64 * dt).collect();
    let gauges = GaugeSignals::new(exp, &pulses, processing)?;
    let shifts = alignment::shifts(processing.alignment, &gauges, &pulses, &face_times);
    let incident = gauges.read(Pulse::Incident, &face_times, 0.0);
    let reflected = gauges.read(Pulse::Reflected, &face_times, shifts.reflected_s);
    let transmitted = gauges.read(Pulse::Transmitted, &face_times, shifts.transmitted_s);

    let bar = &exp.bar;
    let c0 = bar.wave_speed_m_per_s();
    let stiffness = bar.elastic_modulus_pa * bar.area_m2();
    let (area, length) = (exp.specimen.area_m2(), exp.specimen.length_m);
    let zip = |f: &dyn Fn(usize) -> f64| (0..samples).map(f).collect::<Vec<f64>>();
    let velocity_front_m_per_s = zip(&|k| c0 * (incident[k] - reflected[k]));
    let velocity_back_m_per_s = zip(&|k| c0 * transmitted[k]);
    let relative_velocity_m_per_s = zip(&|k| velocity_front_m_per_s[k] - velocity_back_m_per_s[k]);
    let force_front_n = zip(&|k| stiffness * (incident[k] + reflected[k]));
    let force_back_n = zip(&|k| stiffness * transmitted[k]);
    let stress_1wave_pa = zip(&|k| force_back_n[k] / area);
    let stress_2wave_pa = zip(&|k| force_front_n[k] / area);
    let stress_3wave_pa = zip(&|k| 0.5 * (force_front_n[k] + force_back_n[k]) / area);
    let strain_rate_3wave_per_s = zip(&|k| relative_velocity_m_per_s[k] / length);
    let strain_rate_1wave_per_s = zip(&|k| -2.0 * c0 * reflected[k] / length);
    let time_s: Vec<f64> = face_times.iter().map(|tf| tf - start).collect();
    let strain = cumulative_integral(&time_s, &strain_rate_3wave_per_s);
    let true_strain = zip(&|k| -(1.0 - strain[k]).ln());
    let true_stress_pa = zip(&|k| stress_3wave_pa[k] * (1.0 - strain[k]));
    let specimen_length_m = zip(&|k| length * (1.0 - strain[k]));
    let equilibrium_ratio = zip(&|k| {
        2.0 * (force_front_n[k] - force_back_n[k]).abs()
            / (force_front_n[k] + force_back_n[k]).abs()
    });
    let plateau = Plateau::find(
        &exp.name,
        &time_s,
        &strain_rate_3wave_per_s,
        &strain_rate_1wave_per_s,
        &stress_3wave_pa,
        &equilibrium_ratio,
    )?;
    check_stress(&exp.name, plateau.stress_3wave_pa)?;
    Ok(ShpbAnalysis {
        name: exp.name.clone(),
        time_s,
        incident,
        reflected,
        transmitted,
        velocity_front_m_per_s,
        velocity_back_m_per_s,
        relative_velocity_m_per_s,
        force_front_n,
        force_back_n,
        stress_1wave_pa,
        stress_2wave_pa,
        stress_3wave_pa,
        strain_rate_3wave_per_s,
        strain_rate_1wave_per_s,
        strain,
        true_strain,
        true_stress_pa,
        specimen_length_m,
        equilibrium_ratio,
        pulses,
        processing,
        shifts,
        plateau,
    })
}

/// Plateau stresses of real specimens, from soft polymers to hardened steel with margin
/// [Pa]. The stress is F/A_s with F = E_b A_b ε, so a diameter in the wrong unit moves it by
/// the square of the unit's factor.
pub const PLAUSIBLE_STRESS: (f64, f64) = (1e6, 1e10);

fn check_stress(name: &str, stress_pa: f64) -> Result<(), ShpbError> {
    let (low, high) = PLAUSIBLE_STRESS;
    let likely = match stress_pa.abs() {
        s if s > high => "bar.diameter too large or specimen.diameter too small (a length in m written for mm?), or a gauge column in a unit too large",
        s if s < low => "specimen.diameter too large or bar.diameter too small (a length in mm written for m?), or a gauge column in microstrain declared as strain",
        _ => return Ok(()),
    };
    Err(ShpbError::ImplausibleStress {
        name: name.to_string(),
        stress_pa: stress_pa.abs(),
        low,
        high,
        likely,
    })
}

impl ShpbAnalysis {
    /// Median of the equilibrium ratio R over the plateau [-].
    pub fn median_equilibrium_ratio(&self) -> f64 {
        let mut r = self.equilibrium_ratio[self.plateau.range.clone()].to_vec();
        r.sort_by(f64::total_cmp);
        r[r.len() / 2]
    }

    /// Oscillation of the front force F1 over the plateau: half the peak-to-peak of F1
    /// (1 µs moving average, against electrical noise) about its least-squares quadratic
    /// trend, relative to the plateau mean of F1 [-]. Pochhammer-Chree ringing of the
    /// incident and reflected pulses shows here, the smooth hardening does not.
    pub fn force_front_oscillation(&self) -> f64 {
        let dt = self.time_s[1] - self.time_s[0];
        let width = smoothing_width(dt);
        let f1 = &moving_average(&self.force_front_n, width)[self.plateau.range.clone()];
        let trend = polynomial_trend(f1, 2);
        let deviation = f1.iter().zip(&trend).map(|(f, t)| f - t);
        let high = deviation.clone().fold(f64::NEG_INFINITY, f64::max);
        let low = deviation.fold(f64::INFINITY, f64::min);
        0.5 * (high - low) / mean_std(f1).0
    }

    /// Every history with a column name that states quantity, sign and unit.
    pub fn columns(&self) -> Vec<(&'static str, &[f64])> {
        vec![
            ("time_s", &self.time_s),
            ("incident_strain_compression", &self.incident),
            ("reflected_strain_compression", &self.reflected),
            ("transmitted_strain_compression", &self.transmitted),
            ("velocity_front_m_per_s", &self.velocity_front_m_per_s),
            ("velocity_back_m_per_s", &self.velocity_back_m_per_s),
            (
                "relative_velocity_compression_m_per_s",
                &self.relative_velocity_m_per_s,
            ),
            ("force_front_compression_n", &self.force_front_n),
            ("force_back_compression_n", &self.force_back_n),
            ("stress_1wave_back_compression_pa", &self.stress_1wave_pa),
            ("stress_2wave_front_compression_pa", &self.stress_2wave_pa),
            ("stress_3wave_compression_pa", &self.stress_3wave_pa),
            (
                "strain_rate_3wave_compression_per_s",
                &self.strain_rate_3wave_per_s,
            ),
            (
                "strain_rate_1wave_compression_per_s",
                &self.strain_rate_1wave_per_s,
            ),
            ("eng_strain_compression", &self.strain),
            ("true_strain_compression", &self.true_strain),
            ("true_stress_3wave_compression_pa", &self.true_stress_pa),
            ("specimen_length_m", &self.specimen_length_m),
            ("equilibrium_ratio", &self.equilibrium_ratio),
        ]
    }

    /// Write [`columns`](Self::columns) as CSV, plus a 0/1 `on_plateau` column.
    pub fn write_csv(&self, path: &Path) -> anyhow::Result<()> {
        let columns = self.columns();
        let mut w = csv::Writer::from_path(path)?;
        let mut header: Vec<&str> = columns.iter().map(|(name, _)| *name).collect();
        header.push("on_plateau");
        w.write_record(&header)?;
        for k in 0..self.time_s.len() {
            let mut row: Vec<String> = columns.iter().map(|(_, v)| format!("{:e}", v[k])).collect();
            row.push(u8::from(self.plateau.range.contains(&k)).to_string());
            w.write_record(&row)?;
        }
        w.flush()?;
        Ok(())
    }
}
