//! The three bar-strain signals the wave analysis reads, on the record's time base:
//! the incident gauge read for the incident pulse and for the reflected pulse, and the
//! transmitted gauge; baselines removed, compression positive, Savitzky-Golay filtered if
//! asked (`shpb::filter`; the filter uses sample counts, so it assumes even sampling).
//!
//! With `dispersion`, each is corrected for the Pochhammer-Chree dispersion over its
//! gauge distance (`shpb::dispersion`): +d_i for the incident pulse (it travels on to the
//! specimen face), −d_i for the reflected and −d_t for the transmitted pulse (they
//! travelled from the faces to the gauges). The non-dispersive travel time stays with
//! the reads (`GaugeSignals::read`).

use super::analysis::Processing;
use super::dispersion::{correct, PhaseVelocity};
use super::error::ShpbError;
use super::pulses::PulseWindows;
use super::signal::interpolate;
use crate::experiment::ShpbExperiment;

/// Largest relative deviation of a sampling interval from the mean one that the
/// frequency-domain correction accepts.
const UNIFORM_SAMPLING: f64 = 0.01;

/// Which pulse a read is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pulse {
    Incident,
    Reflected,
    Transmitted,
}

pub struct GaugeSignals<'a> {
    time: &'a [f64],
    incident: Vec<f64>,
    reflected: Vec<f64>,
    transmitted: Vec<f64>,
    delay_incident_s: f64,
    delay_transmitted_s: f64,
}

impl<'a> GaugeSignals<'a> {
    /// The signals of `exp` with the baselines of `pulses`, filtered and corrected for
    /// dispersion as `processing` asks (the correction needs the bar's Poisson ratio and
    /// uniform sampling).
    pub fn new(
        exp: &'a ShpbExperiment,
        pulses: &PulseWindows,
        processing: Processing,
    ) -> Result<GaugeSignals<'a>, ShpbError> {
        let compression = |values: &[f64], baseline: f64| -> Vec<f64> {
            let v: Vec<f64> = values.iter().map(|v| -(v - baseline)).collect();
            match processing.filter {
                Some(sg) => sg.apply(&v),
                None => v,
            }
        };
        let on_incident = compression(&exp.incident, pulses.baseline_incident);
        let transmitted = compression(&exp.transmitted, pulses.baseline_transmitted);
        let bar = &exp.bar;
        let (incident, reflected, transmitted) = if processing.dispersion {
            let nu = bar.poisson_ratio.ok_or_else(|| ShpbError::NoPoissonRatio {
                name: exp.name.clone(),
            })?;
            let dt = uniform_interval(exp)?;
            let phase = PhaseVelocity::new(bar.wave_speed_m_per_s(), 0.5 * bar.diameter_m, nu);
            let d_i = bar.incident_gauge_to_specimen_m;
            let d_t = bar.transmitted_gauge_to_specimen_m;
            (
                correct(&on_incident, dt, d_i, &phase),
                correct(&on_incident, dt, -d_i, &phase),
                correct(&transmitted, dt, -d_t, &phase),
            )
        } else {
            (on_incident.clone(), on_incident, transmitted)
        };
        Ok(GaugeSignals {
            time: &exp.time_s,
            incident,
            reflected,
            transmitted,
            delay_incident_s: pulses.delay_incident_s,
            delay_transmitted_s: pulses.delay_transmitted_s,
        })
    }

    /// `pulse` at the specimen faces at the face times `at` [s], read `shift` [s] later
    /// than its gauge travel time places it; compression positive.
    pub fn read(&self, pulse: Pulse, at: &[f64], shift: f64) -> Vec<f64> {
        let (values, delay) = match pulse {
            Pulse::Incident => (&self.incident, -self.delay_incident_s),
            Pulse::Reflected => (&self.reflected, self.delay_incident_s),
            Pulse::Transmitted => (&self.transmitted, self.delay_transmitted_s),
        };
        at.iter()
            .map(|&tf| interpolate(self.time, values, tf + delay + shift))
            .collect()
    }
}

/// The record's sampling interval [s], if every interval is within `UNIFORM_SAMPLING`
/// of the mean.
fn uniform_interval(exp: &ShpbExperiment) -> Result<f64, ShpbError> {
    let t = &exp.time_s;
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    match t
        .windows(2)
        .position(|w| ((w[1] - w[0]) / dt - 1.0).abs() > UNIFORM_SAMPLING)
    {
        None => Ok(dt),
        Some(k) => Err(ShpbError::NonUniformSampling {
            name: exp.name.clone(),
            sample: k,
            interval_s: t[k + 1] - t[k],
            mean_s: dt,
        }),
    }
}
