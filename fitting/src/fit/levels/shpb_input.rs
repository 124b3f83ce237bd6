//! Face signals of an SHPB record for the fit, from the signal processing of
//! `crate::shpb::analyze` (baselines, pulse detection, time shift, wave analysis):
//! relative face velocity v1 − v2 [m/s] and face forces F1, F2 [N], compression positive.
//!
//! Time here is measured from the start of the incident pulse at the specimen faces
//! (incident-pulse start at the gauge plus d_i/c0), so that a fit window means the same
//! thing for every record; the analysis window starts a margin earlier (negative times),
//! where v ≈ 0, and the specimen length is integrated from there.
//!
//! The strain-rate plateau of the analysis (3-wave rate within ±15 % of its median over
//! the loading phase, see `crate::shpb`) and its mean equilibrium ratio
//! R = 2 |F1 − F2| / |F1 + F2| come along, so that a fit can compare the model only where
//! the specimen deforms at constant rate.

use crate::shpb::ShpbAnalysis;
use std::ops::Range;

/// Specimen-face signals from the analysis.
#[derive(Debug, Clone)]
pub struct FaceSignals {
    /// Time since the incident pulse start at the faces [s] (negative in the margin).
    pub time_s: Vec<f64>,
    /// Relative face velocity v1 − v2 [m/s], compression positive.
    pub velocity_m_per_s: Vec<f64>,
    /// Incident-face force F1 [N], compression positive.
    pub f1_n: Vec<f64>,
    /// Transmitted-face force F2 [N], compression positive.
    pub f2_n: Vec<f64>,
    /// Samples on the strain-rate plateau.
    pub plateau: Range<usize>,
    /// Mean equilibrium ratio R on the plateau [-].
    pub plateau_equilibrium_ratio: f64,
}

pub fn face_signals(a: &ShpbAnalysis) -> FaceSignals {
    let p = &a.pulses;
    let offset = p.incident_at_gauge_s.0 + p.delay_incident_s - p.window_at_faces_s.0;
    FaceSignals {
        time_s: a.time_s.iter().map(|t| t - offset).collect(),
        velocity_m_per_s: a.relative_velocity_m_per_s.clone(),
        f1_n: a.force_front_n.clone(),
        f2_n: a.force_back_n.clone(),
        plateau: a.plateau.range.clone(),
        plateau_equilibrium_ratio: a.plateau.equilibrium_ratio,
    }
}
