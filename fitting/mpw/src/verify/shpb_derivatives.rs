//! Exact derivatives of the MPM SHPB model's face forces (`jacobian = "exact"`) on the
//! 945 test 01 record, when the shared data folder is there: CPDI, μ = 0.1, 10 points
//! along, F1 and F2 at every 10th plateau sample, their derivatives along A, B, N and C
//! against central differences of whole runs (`fit::levels::jacobian_check`). A row
//! asserts the closer of the relative steps 1e-5 and 1e-6, on the plateau between
//! truncation and round-off. With the measured-velocity drive (faces of prescribed
//! motion) the steps from 1e-2 to 1e-7 are reported as well: the error curve a
//! finite-difference Jacobian lives on (the MPM fit level's forward differences use
//! 1e-2); with the incident-pulse drive (faces on elastic bars, which the contact force
//! moves) the asserted pair alone.

use crate::verify::row::Row;
use crate::verify::Inputs;
use anyhow::Result;
use fitting::fit::levels::jacobian_check::against_central_differences;
use fitting::fit::levels::model::ExperimentModel;
use fitting::fit::levels::mpm_shpb::{FaceForces, Jacobian, MpmShpb};
use fitting::shpb_model::scene::ShpbScene;
use fitting::shpb_model::Drive;
use std::path::Path;
use std::time::Instant;

const FREE: [&str; 4] = ["A", "B", "N", "C"];
/// The relative steps: the asserted pair first.
const STEPS: [f64; 6] = [1e-5, 1e-6, 1e-2, 1e-3, 1e-4, 1e-7];
/// Bound of the asserted rows: round-off amplified through the run is ~1e-6 of a column,
/// a missing term of the derivative 1e-2 or more.
const BOUND: f64 = 3e-5;

pub fn rows(inputs: &Inputs) -> Result<Vec<Row>> {
    let Some(scene_file) = inputs.data.steel_945_scene() else {
        eprintln!("note: the 945 records are not there; the SHPB derivative rows skipped");
        return Ok(Vec::new());
    };
    let mut rows = drive_rows(&scene_file, Drive::MeasuredVelocity, &STEPS)?;
    rows.extend(drive_rows(&scene_file, Drive::IncidentPulse, &STEPS[..2])?);
    Ok(rows)
}

/// The rows of the model of `scene_file` driven by `drive`, against central differences
/// at relative `steps` (the asserted pair first).
fn drive_rows(scene_file: &Path, drive: Drive, steps: &[f64]) -> Result<Vec<Row>> {
    let mut scene = ShpbScene::load(scene_file)?;
    scene.settings.layers = 10;
    scene.settings.drive = drive;
    let material = materials::load_elasto_plastic(&scene.material_file)?;
    let times = scene.plateau_times().into_iter().step_by(10).collect();
    let model = MpmShpb::new(
        scene.model(&material)?,
        times,
        FaceForces::Both,
        scene.experiment.temperature_k,
    )
    .with_jacobian(Jacobian::Exact);
    let start = Instant::now();
    model.predict(&material)?;
    let plain = start.elapsed().as_secs_f64();
    let start = Instant::now();
    model.predict_with_jacobian(&material, &FREE)?;
    let exact = start.elapsed().as_secs_f64();
    let prefix = match drive {
        Drive::MeasuredVelocity => "shpb-model/derivatives/945 test 01 n10",
        Drive::IncidentPulse => "shpb-model/derivatives/945 test 01 n10 incident-pulse drive",
    };
    let mut rows = Vec::new();
    for c in against_central_differences(&model, &material, &FREE, steps)? {
        let name = &c.parameter;
        rows.push(
            Row::at_most(
                format!("{prefix}: dF/d{name} exact vs central differences (closer of h/p 1e-5, 1e-6), of the column"),
                c.errors[0].min(c.errors[1]),
                BOUND,
            )
            .with_note(format!("largest p dF/dp {:.3} kN", c.scale * 1e-3)),
        );
        for (step, error) in steps.iter().zip(&c.errors).skip(2) {
            rows.push(Row::reported(
                format!("{prefix}: dF/d{name} central differences at h/p {step:.0e}, worst error of the column"),
                *error,
            ));
        }
    }
    rows.push(Row::reported(
        format!("{prefix}: cost of value and exact Jacobian (p = 4) over one run"),
        exact / plain,
    ));
    Ok(rows)
}
