//! Exact derivatives of the MPM SHPB model's face forces (`jacobian = "exact"`,
//! `ShpbModel::run_with_derivatives`) against central differences of whole runs, on the
//! 945 test 01 record of the shared data.

mod common;

use fitting::fit::levels::jacobian_check::against_central_differences;
use fitting::fit::levels::model::ExperimentModel;
use fitting::fit::levels::mpm_shpb::{FaceForces, Jacobian, MpmShpb};
use fitting::shpb_model::scene::ShpbScene;
use fitting::shpb_model::Drive;
use materials::plasticity::ElastoPlastic;
use std::path::Path;

const FREE: [&str; 4] = ["A", "B", "N", "C"];

/// The scene of the record (incident-pulse drive) and its material; `None` without the
/// shared data.
fn scene() -> Option<(ShpbScene, ElastoPlastic)> {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/shpb/steel_945");
    if !shared.is_dir() {
        common::skip("../shared/data/shpb/steel_945");
        return None;
    }
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/scenes/shpb/945_test01.toml");
    let s = ShpbScene::load(&file).unwrap();
    let material = materials::load_elasto_plastic(&s.material_file).unwrap();
    Some((s, material))
}

/// The record's model at `layers` points along (CPDI, μ = 0.1) with `drive`, compared on
/// F1 and F2 at every `thin`-th plateau sample.
fn model(drive: Drive, layers: usize, thin: usize) -> Option<(MpmShpb, ElastoPlastic)> {
    let (mut s, material) = scene()?;
    s.settings.layers = layers;
    s.settings.drive = drive;
    let times: Vec<f64> = s.plateau_times().into_iter().step_by(thin).collect();
    let m = MpmShpb::new(
        s.model(&material).unwrap(),
        times,
        FaceForces::Both,
        s.experiment.temperature_k,
    );
    Some((m.with_jacobian(Jacobian::Exact), material))
}

/// Every sample of F1 and F2 (394 on the plateau of test 01 at 10 points along) and its
/// derivative along A, B, N and C against the closer of the central differences at
/// h/p = 1e-5 and 1e-6, relative to the column's largest entry. Measured on the 2-core
/// VM: at most 2.4e-6 (A at 1e-6); the steps of 1e-3 and 1e-2 that a finite-difference
/// fit needs against the model's events are off by up to 0.46 and 0.22 at single samples.
#[test]
fn the_exact_jacobian_of_the_face_forces_matches_central_differences() {
    check(Drive::MeasuredVelocity);
}

/// The same with the incident-pulse drive: both faces move with elastic bars, driven by
/// the contact force, so the derivatives also pass through the faces' displacements.
/// Measured on the 2-core VM: at most 1.3e-7 of the column (A).
#[test]
fn the_pulse_drive_jacobian_through_the_elastic_bars_matches_central_differences() {
    check(Drive::IncidentPulse);
}

/// The exact Jacobian of F1 and F2 against the closer central difference, each column
/// relative to its largest entry.
fn check(drive: Drive) {
    let Some((m, material)) = model(drive, 10, 10) else {
        return;
    };
    let (y, _) = m.predict_with_jacobian(&material, &FREE).unwrap();
    assert_eq!(y, m.predict(&material).unwrap(), "the pass changed the run");
    for c in against_central_differences(&m, &material, &FREE, &[1e-5, 1e-6]).unwrap() {
        assert!(c.scale > 1e3, "F depends on {}: {} N", c.parameter, c.scale);
        // round-off amplified through the run is ~1e-6 of the column; a missing term of
        // the derivative is off by 1e-2 or more
        eprintln!("{drive:?} {}: {:.1e}", c.parameter, c.best());
        assert!(c.best() < 3e-5, "{c:?}");
    }
}
