//! The MPM model of an SHPB record (`fitting::shpb_model`) on the 945 test 01 record of
//! the shared data: the measured-velocity drive reproduces the record's specimen length,
//! the incident-pulse drive the record's force level; a run cut short is the start of the
//! whole run; scene and set files with bad fields are refused with the field named.

mod common;

use fitting::shpb_model::scene::ShpbScene;
use fitting::shpb_model::Drive;
use std::path::{Path, PathBuf};

fn scene_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/scenes/shpb/945_test01.toml")
}

fn scene(drive: Drive) -> Option<ShpbScene> {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/shpb/steel_945");
    if !shared.is_dir() {
        common::skip("../shared/data/shpb/steel_945");
        return None;
    }
    let mut s = ShpbScene::load(&scene_file()).unwrap();
    s.settings.layers = 10;
    s.settings.drive = drive;
    Some(s)
}

/// The faces act on the points' domains, so the gap between them is the specimen length:
/// with the measured drive it must follow the record's L(t) = L0 − ∫ (v1 − v2) dt. The
/// two integrations differ only by the trapezoid rule against the analysis's sum over
/// the same samples: 1e-4 of L0.
#[test]
fn the_measured_drive_reproduces_the_specimen_length_of_the_record() {
    let Some(s) = scene(Drive::MeasuredVelocity) else {
        return;
    };
    let material = materials::load_elasto_plastic(&s.material_file).unwrap();
    let run = s
        .model(&material)
        .unwrap()
        .run(s.material(&material))
        .unwrap();
    let h = &run.history;
    let l0 = s.experiment.specimen.length_m;
    assert_eq!(h.length_m[0], l0);
    let end = *h.time_s.last().unwrap();
    let k = s.analysis.time_s.partition_point(|&t| t <= end) - 1;
    let measured = s.analysis.specimen_length_m[k];
    let model = h.length_m[h.length_m.len() - 1];
    assert!(
        (model - measured).abs() < 1e-4 * l0,
        "final length: model {model} m, record {measured} m"
    );
}

#[test]
fn a_scene_with_a_bad_field_names_it() {
    let text = std::fs::read_to_string(scene_file()).unwrap();
    let dir = std::env::temp_dir().join(format!("mpw-shpb-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (from, to, expect) in [
        (
            "drive = \"incident-pulse\"",
            "drive = \"pulse\"",
            "`drive`: ",
        ),
        (
            "level = \"mpm-axisymmetric\"",
            "level = \"mpm-2d\"",
            "`level`: ",
        ),
        ("friction = 0.1", "friction = 1.5", "`friction`: "),
        ("layers = 20", "layers = 1", "`layers`: "),
    ] {
        let file = dir.join("scene.toml");
        std::fs::write(&file, text.replace(from, to)).unwrap();
        let e = ShpbScene::load(&file).err().expect(to).to_string();
        assert!(e.contains(expect) && e.contains("scene.toml"), "{to}: {e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Friction at the faces restrains the barrelling: the force must rise with μ, and a
/// halved or doubled penalty must move it less than the friction does. For scale:
/// Siebel's slab estimate 1 + μ d / 3h gives −3.1 % and +6.2 % for μ = 0.05 and 0.2
/// against 0.1 on this 8 × 4 mm specimen; measured at 10 points along, −3.9 % and +8.3 %.
#[test]
fn the_force_rises_with_friction_and_hardly_depends_on_the_penalty() {
    let Some(s) = scene(Drive::MeasuredVelocity) else {
        return;
    };
    let material = materials::load_elasto_plastic(&s.material_file).unwrap();
    let v = fitting::shpb_model::study::contact_sensitivity(&s, &material).unwrap();
    for x in &v {
        println!(
            "{}: mean {:+.3e}, RMS {:.3e}",
            x.label, x.mean_change, x.rms_change
        );
    }
    let (kappa_half, kappa_double, mu_half, mu_double) = (&v[0], &v[1], &v[2], &v[3]);
    assert!(mu_half.mean_change < 0.0 && mu_double.mean_change > 0.0);
    let kappa = kappa_half
        .mean_change
        .abs()
        .max(kappa_double.mean_change.abs());
    assert!(kappa < mu_half.mean_change.abs().min(mu_double.mean_change.abs()));
}

/// The fit's contact changes act on a copy of the discretized model
/// (`ShpbModel::with_contact`); rebuilding the model from changed settings must give the
/// same run. Not to the bit: √2² ≠ 2 in floating point, so the penalty differs by an ulp.
#[test]
fn contact_changes_on_the_template_equal_a_rebuilt_model() {
    let Some(s) = scene(Drive::MeasuredVelocity) else {
        return;
    };
    let material = materials::load_elasto_plastic(&s.material_file).unwrap();
    let model = s.model(&material).unwrap();
    for change in &fitting::shpb_model::CONTACT_CHANGES {
        let changed = model
            .with_contact(change)
            .unwrap()
            .run(s.material(&material))
            .unwrap()
            .history;
        let rebuilt = ShpbScene {
            settings: s.settings.with_contact(change),
            ..s.clone()
        };
        let expected = rebuilt
            .model(&material)
            .unwrap()
            .run(s.material(&material))
            .unwrap()
            .history;
        let peak = expected
            .force_transmitted_n
            .iter()
            .fold(0.0f64, |m, f| m.max(f.abs()));
        assert_eq!(
            changed.time_s.len(),
            expected.time_s.len(),
            "{}",
            change.label
        );
        for (a, b) in changed
            .force_transmitted_n
            .iter()
            .zip(&expected.force_transmitted_n)
        {
            assert!(
                (a - b).abs() <= 1e-9 * peak,
                "{}: {a} vs {b} N",
                change.label
            );
        }
    }
}

/// The shipped MPM-level set file with its paths made absolute, to be written anywhere.
fn mpm_set_text() -> String {
    let experiments = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/experiments");
    let absolute = |folder: &str| format!("\"{}/{folder}", experiments.display());
    std::fs::read_to_string(experiments.join("fit_945_mpm.toml"))
        .unwrap()
        .replace("\"../materials/", &absolute("../materials/"))
        .replace("\"shpb_steel_945/", &absolute("shpb_steel_945/"))
}

/// A set file's MPM fields: `drive` names a drive of the model and belongs to the MPM
/// level; `jacobian = "exact"` needs a kernel the derivative pass carries; the
/// error names the field (`{:#}` prints the set file and experiment).
#[test]
fn a_set_file_with_a_bad_drive_names_it() {
    if scene(Drive::MeasuredVelocity).is_none() {
        return;
    }
    let text = mpm_set_text();
    let first = "level = \"mpm-axisymmetric\"";
    assert!(text.contains(first));
    for (to, expect) in [
        (
            "level = \"mpm-axisymmetric\"\ndrive = \"pulse\"",
            "`experiment.drive`: \"pulse\", expected \"measured-velocity\" or \"incident-pulse\"",
        ),
        (
            "level = \"single-point\"\ndrive = \"incident-pulse\"",
            "belong to the MPM levels",
        ),
        (
            "level = \"mpm-axisymmetric\"\njacobian = \"analytic\"",
            "`experiment.jacobian`: \"analytic\", expected \"finite-difference\" or \"exact\"",
        ),
        (
            "level = \"mpm-axisymmetric\"\njacobian = \"exact\"\nshape_function = \"cpdi-hex\"",
            "needs shape_function",
        ),
    ] {
        let file = std::env::temp_dir().join(format!("mpw-drive-{}.toml", std::process::id()));
        std::fs::write(&file, text.replacen(first, to, 1)).unwrap();
        let result = fitting::fit::sets::fit_set::FitSet::load(&file);
        std::fs::remove_file(&file).unwrap();
        let e = format!("{:#}", result.err().expect(to));
        assert!(e.contains(expect) && e.contains("test_01"), "{to}: {e}");
    }
}

/// A fit's run ends a window after its last sample: the run is explicit, so the shorter
/// run's history must be the whole run's to the bit.
#[test]
fn a_run_cut_short_is_the_start_of_the_whole_run() {
    let Some(s) = scene(Drive::IncidentPulse) else {
        return;
    };
    let material = materials::load_elasto_plastic(&s.material_file).unwrap();
    let model = s.model(&material).unwrap();
    let whole = model.run(s.material(&material)).unwrap().history;
    let end = 0.5 * model.end_s();
    let cut = model.run_until(s.material(&material), end).unwrap().history;
    let n = cut.time_s.len();
    assert!(n < whole.time_s.len() && cut.time_s[n - 1] >= end - 1e-9);
    assert_eq!(cut.force_incident_n[..], whole.force_incident_n[..n]);
    assert_eq!(cut.force_transmitted_n[..], whole.force_transmitted_n[..n]);
}

/// The shipped MPM-level set files load: six records each, compared on F2; with
/// `level = "mpm-3d-quarter"` the same set loads the 3D quarter's models.
#[test]
fn the_shipped_mpm_sets_load() {
    if scene(Drive::MeasuredVelocity).is_none() {
        return;
    }
    let experiments = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/experiments");
    for file in ["fit_945_mpm.toml", "fit_945_mpm_pulse.toml"] {
        let set = fitting::fit::sets::fit_set::FitSet::load(&experiments.join(file))
            .unwrap_or_else(|e| panic!("{file}: {e:#}"));
        assert_eq!(set.blocks.len(), 6, "{file}");
        for block in &set.blocks {
            assert_eq!(block.channels, ["F2"], "{file}: {}", block.name);
            assert_eq!(block.model.level(), "axisymmetric MPM SHPB specimen");
        }
    }
    // a 3D level in a set file: the same records, the quarter's model
    let text = mpm_set_text().replace("level = \"mpm-axisymmetric\"", "level = \"mpm-3d-quarter\"");
    let file = std::env::temp_dir().join(format!("mpw-quarter-{}.toml", std::process::id()));
    std::fs::write(&file, text).unwrap();
    let set = fitting::fit::sets::fit_set::FitSet::load(&file);
    std::fs::remove_file(&file).unwrap();
    let set = set.unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(set.blocks.len(), 6);
    for block in &set.blocks {
        assert_eq!(block.model.level(), "3D quarter MPM SHPB specimen");
    }
}
