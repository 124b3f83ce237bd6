//! Accuracy against cost of the SHPB model: one scene at several model levels and
//! resolutions. Each run's face forces are compared with the reference's (the last run,
//! e.g. the finest 3D model) over the record's plateau (RMS of the difference over the
//! reference's mean force there), beside its wall time and size: the numbers a user reads
//! to pick a level and resolution to fit with.

use super::scene::ShpbScene;
use super::{Discretization, ShpbRun, CONTACT_CHANGES};
use crate::shpb::signal::interpolate;
use anyhow::Result;
use materials::plasticity::ElastoPlastic;

/// One resolution of the study.
#[derive(Debug, Clone)]
pub struct Resolution {
    pub discretization: Discretization,
    pub particles: usize,
    pub steps: usize,
    pub wall_s: f64,
    /// RMS force difference against the reference over the plateau, relative to the
    /// reference's mean force there, at the incident (F1) and transmitter (F2) face.
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

/// Run `scene` with `material` at each of `discretizations` (the last is the reference)
/// and report each against the reference. `progress` is told each run.
pub fn refinement(
    scene: &ShpbScene,
    material: &ElastoPlastic,
    discretizations: &[Discretization],
    progress: &dyn Fn(&Discretization, &ShpbRun),
) -> Result<Vec<Resolution>> {
    anyhow::ensure!(
        discretizations.len() >= 2,
        "a refinement study needs at least two resolutions"
    );
    let mut runs = Vec::new();
    for d in discretizations {
        let mut s = scene.settings;
        s.layers = d.layers;
        s.level = d.level;
        let with = ShpbScene {
            settings: s,
            ..scene.clone()
        };
        let run = with.model(material)?.run(with.material(material))?;
        progress(d, &run);
        runs.push(run);
    }
    let times = scene.plateau_times();
    let reference = &runs[runs.len() - 1].history;
    Ok(runs
        .iter()
        .zip(discretizations)
        .map(|(r, &discretization)| {
            let h = &r.history;
            let error = |model: &[f64], of_reference: &[f64]| {
                relative_rms(
                    &times,
                    (&h.time_s, model),
                    (&reference.time_s, of_reference),
                )
            };
            Resolution {
                discretization,
                particles: r.particles,
                steps: r.steps,
                wall_s: r.wall_s,
                error_incident: error(&h.force_incident_n, &reference.force_incident_n),
                error_transmitted: error(&h.force_transmitted_n, &reference.force_transmitted_n),
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
