//! The MPM model of one processed SHPB record: bars, specimen cylinder and face signals
//! from the experiment file and its analysis (`crate::shpb::analyze`, time from the start
//! of its window at the faces), the material starting at the test temperature.

use super::{Bars, Cylinder, FaceSignals, ModelSettings, ShpbModel};
use crate::experiment::ShpbExperiment;
use crate::shpb::ShpbAnalysis;
use materials::plasticity::ElastoPlastic;
use materials::preheated::Preheated;
use std::sync::Arc;

/// The measured histories at the faces, from the processed record.
pub fn signals(analysis: &ShpbAnalysis) -> FaceSignals {
    FaceSignals {
        time_s: analysis.time_s.clone(),
        incident: analysis.incident.clone(),
        relative_velocity_m_per_s: analysis.relative_velocity_m_per_s.clone(),
    }
}

/// `material` starting at the temperature `theta_start` [K].
pub fn preheated(material: &ElastoPlastic, theta_start: f64) -> Arc<dyn materials::Material> {
    Arc::new(Preheated {
        inner: *material,
        theta_start,
    })
}

/// The model of the record with `settings`; `material` fixes the contact frequency.
pub fn model(
    experiment: &ShpbExperiment,
    analysis: &ShpbAnalysis,
    settings: ModelSettings,
    material: &ElastoPlastic,
) -> anyhow::Result<ShpbModel> {
    let bar = &experiment.bar;
    let bars = Bars {
        axial_stiffness: bar.elastic_modulus_pa * bar.area_m2(),
        wave_speed: bar.wave_speed_m_per_s(),
    };
    let specimen = &experiment.specimen;
    let cylinder = Cylinder {
        diameter: specimen.diameter_m,
        length: specimen.length_m,
    };
    ShpbModel::new(
        cylinder,
        bars,
        signals(analysis),
        settings,
        preheated(material, experiment.temperature_k),
    )
}
