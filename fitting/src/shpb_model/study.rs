//! Accuracy against cost of the SHPB model: one scene at several resolutions. Each
//! level's face forces are compared with the finest level's over the record's plateau
//! (RMS of the difference over the finest level's mean force there), beside its wall
//! time and size: the numbers a user reads to pick a resolution to fit with.

use super::scene::ShpbScene;
use super::{ShpbRun, CONTACT_CHANGES};
use crate::shpb::signal::interpolate;
use anyhow::Result;
use materials::plasticity::ElastoPlastic;

/// One resolution of the study.
#[derive(Debug, Clone)]
pub struct Level {
    pub layers: usize,
    pub particles: usize,
    pub steps: usize,
    pub wall_s: f64,
    /// RMS force difference against the finest level over the plateau, relative to the
    /// finest level's mean force there, at the incident (F1) and transmitter (F2) face.
    pub error_incident: f64,
    pub error_transmitted: f64,
}

/// RMS of `a − b` over `times` relative to the mean of `b` (each on its own time base,
/// `t_a` and `t_b`).
pub fn relative_rms(times: &[f64], (t_a, a): (&[f64], &[f64]), (t_b, b): (&[f64], &[f64])) -> f64 {
    let (sum2, sum) = times.iter().fold((0.0, 0.0), |(s2, s), &t| {
        let (x, y) = (interpolate(t_a, a, t), interpolate(t_b, b, t));
        (s2 + (x - y).powi(2), s + y)
    });
    let n = times.len() as f64;
    (sum2 / n).sqrt() / (sum / n)
}

/// Run `scene` with `material` at each of `layers` (ascending; the last is the
/// reference) and report each level against the finest. `progress` is told each level.
pub fn refinement(
    scene: &ShpbScene,
    material: &ElastoPlastic,
    layers: &[usize],
    progress: &dyn Fn(usize, &ShpbRun),
) -> Result<Vec<Level>> {
    anyhow::ensure!(
        layers.len() >= 2,
        "a refinement study needs at least two levels"
    );
    let mut runs = Vec::new();
    for &n in layers {
        let mut s = scene.settings;
        s.layers = n;
        let with = ShpbScene {
            settings: s,
            ..scene.clone()
        };
        let run = with.model(material)?.run(with.material(material))?;
        progress(n, &run);
        runs.push(run);
    }
    let times = scene.plateau_times();
    let finest = &runs[runs.len() - 1].history;
    Ok(runs
        .iter()
        .zip(layers)
        .map(|(r, &n)| {
            let h = &r.history;
            let error = |model: &[f64], reference: &[f64]| {
                relative_rms(&times, (&h.time_s, model), (&finest.time_s, reference))
            };
            Level {
                layers: n,
                particles: r.particles,
                steps: r.steps,
                wall_s: r.wall_s,
                error_incident: error(&h.force_incident_n, &finest.force_incident_n),
                error_transmitted: error(&h.force_transmitted_n, &finest.force_transmitted_n),
            }
        })
        .collect())
}

/// One variant of the contact parameters and how far its forces move from the base run.
#[derive(Debug, Clone)]
pub struct Variant {
    pub label: String,
    /// Mean F2 over the plateau relative to the base run's, minus 1 [-].
    pub mean_change: f64,
    /// RMS of F2 − F2_base over the plateau relative to the base run's mean [-].
    pub rms_change: f64,
}

/// How much the face force moves when the penalty stiffness κ and the friction μ are each
/// halved and doubled (`CONTACT_CHANGES`).
pub fn contact_sensitivity(scene: &ShpbScene, material: &ElastoPlastic) -> Result<Vec<Variant>> {
    let run = |settings| -> Result<ShpbRun> {
        let with = ShpbScene {
            settings,
            ..scene.clone()
        };
        with.model(material)?.run(with.material(material))
    };
    let base = scene.settings;
    let reference = run(base)?;
    let times = scene.plateau_times();
    let r = &reference.history;
    let mean = |h: &super::FaceHistory| {
        times
            .iter()
            .map(|&t| interpolate(&h.time_s, &h.force_transmitted_n, t))
            .sum::<f64>()
            / times.len() as f64
    };
    let base_mean = mean(r);
    CONTACT_CHANGES
        .iter()
        .map(|change| {
            let s = base.with_contact(change);
            let h = run(s)?.history;
            Ok(Variant {
                label: format!(
                    "{} (contact factor {:.3}, μ = {:.3})",
                    change.label, s.contact_factor, s.friction
                ),
                mean_change: mean(&h) / base_mean - 1.0,
                rms_change: relative_rms(
                    &times,
                    (&h.time_s, &h.force_transmitted_n),
                    (&r.time_s, &r.force_transmitted_n),
                ),
            })
        })
        .collect()
}
