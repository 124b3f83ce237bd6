//! `mpw simulate` warns at the start when Δt is above the CFL limit and names that setting
//! as the likely cause when the run then fails; SHPB scenes name their parameters and write
//! exact derivatives.

use std::path::Path;
use std::process::Command;

#[test]
fn a_safety_factor_above_one_is_warned_about_and_named_when_the_run_fails() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let scene = std::fs::read_to_string(root.join("data/scenes/colliding_disks.toml")).unwrap();
    let risky = scene.replace("safety = 0.2", "safety = 1.5");
    assert_ne!(risky, scene);
    let dir = std::env::temp_dir().join(format!("mpw-simulate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("disks.toml"), risky).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .args([
            "simulate",
            dir.join("disks.toml").to_str().unwrap(),
            "--out",
        ])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{err}");
    assert!(
        err.contains("warning: time.safety = 1.5: dt = ") && err.contains("exceeds the CFL limit"),
        "{err}"
    );
    assert!(err.contains("simulation failed at step"), "{err}");
    assert!(err.contains("likely cause: time.safety = 1.5"), "{err}");
    assert!(
        dir.join("out/history.csv").is_file(),
        "the failed run keeps its output"
    );
}

/// An SHPB scene says which parameters it runs with and where they come from: the material
/// file's start values unless `--params` names a fit (or another material file).
#[test]
fn an_shpb_run_names_the_source_of_its_parameters() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap();
    let data = root.join("data");
    let scene = format!(
        "kind = \"shpb\"\nexperiment = \"{}\"\nmaterial = \"{}\"\nlevel = \"mpm-axisymmetric\"\n\
         drive = \"measured-velocity\"\nlayers = 4\n",
        data.join("experiments/shpb_293K.toml").display(),
        data.join("materials/42crmo4_qt660.toml").display()
    );
    let dir = std::env::temp_dir().join(format!("mpw-simulate-shpb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("shpb.toml"), scene).unwrap();
    let run = |extra: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_mpw"))
            .args(["simulate", dir.join("shpb.toml").to_str().unwrap(), "--out"])
            .arg(dir.join("out"))
            .args(extra)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "{err}");
        err
    };
    let err = run(&[]);
    assert!(
        err.contains("parameters: A = 801.00 MPa, B = 1531.00 MPa")
            && err.contains("from the material file")
            && err
                .contains("the file's own values, not a fit's: pass a fit's report with --params"),
        "{err}"
    );
    let other = data.join("materials/aisi_4340.toml");
    let err = run(&["--params", other.to_str().unwrap()]);
    assert!(
        err.contains("A = 792.00 MPa") && err.contains(&format!("from {}", other.display())),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A Taylor bar whose copper melts at 330 K (θ0 = 293.15 K) warns how many points reached
/// the melting temperature, when and where; with the real θm = 1356 K it does not.
#[test]
fn points_that_reach_the_melting_temperature_are_warned_about() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = std::env::temp_dir().join(format!("mpw-simulate-melt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let copper = std::fs::read_to_string(root.join("data/materials/ofhc_copper.toml")).unwrap();
    let scene = std::fs::read_to_string(root.join("data/scenes/taylor_bar_axisymmetric.toml"))
        .unwrap()
        .replace("../materials/ofhc_copper.toml", "copper.toml")
        .replace(
            "spacing = 0.00036285714285714286",
            "spacing = 0.0007257142857142857",
        )
        .replace("end = 80e-6", "end = 20e-6");
    std::fs::write(dir.join("taylor.toml"), scene).unwrap();
    let run = |theta_m: &str| {
        let material = copper.replace("theta_m = 1356.0", &format!("theta_m = {theta_m}"));
        std::fs::write(dir.join("copper.toml"), material).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_mpw"))
            .args([
                "simulate",
                dir.join("taylor.toml").to_str().unwrap(),
                "--out",
            ])
            .arg(dir.join("out"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "{err}");
        err
    };
    let err = run("330.0");
    let warning = err
        .lines()
        .find(|l| l.starts_with("warning: bar: points reached the melting temperature θm = 330 K"))
        .unwrap_or_else(|| panic!("{err}"));
    let number_after = |key: &str| -> f64 {
        let rest = &warning[warning
            .find(key)
            .unwrap_or_else(|| panic!("{key}: {warning}"))
            + key.len()..];
        let end = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
            .unwrap();
        rest[..end].parse().unwrap()
    };
    // The wall layer heats first: molten points exist, the first of them before the end.
    assert!(number_after("first at step ") > 0.0, "{warning}");
    assert!(number_after("(t = ") < 20e-6, "{warning}");
    assert!(number_after("; ") >= 1.0, "{warning}");
    // The hottest point is at the wall (y within two cells of it).
    let at = &warning[warning.find(" at (").unwrap() + 5..];
    let y: f64 = at[at.find(", ").unwrap() + 2..at.find(") mm").unwrap()]
        .parse()
        .unwrap();
    assert!(y < 2.0 * 0.7257, "{warning}");
    assert!(
        !run("1356.0").contains("melting"),
        "real copper does not melt here"
    );
}

/// `--derivatives` on an SHPB scene writes each face force's sensitivity p ∂F/∂p per
/// parameter (the material file's values as the scale), nonzero once the specimen yields,
/// with either drive (faces of prescribed motion, or on elastic bars).
#[test]
fn an_shpb_scene_writes_the_face_forces_derivatives() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap();
    let data = root.join("data");
    let scene = |drive: &str| {
        format!(
            "kind = \"shpb\"\nexperiment = \"{}\"\nmaterial = \"{}\"\nlevel = \"mpm-axisymmetric\"\n\
             drive = \"{drive}\"\nlayers = 4\n",
            data.join("experiments/shpb_293K.toml").display(),
            data.join("materials/42crmo4_qt660.toml").display()
        )
    };
    let dir = std::env::temp_dir().join(format!("mpw-simulate-shpb-d-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |drive: &str| {
        std::fs::write(dir.join("shpb.toml"), scene(drive)).unwrap();
        Command::new(env!("CARGO_BIN_EXE_mpw"))
            .args(["simulate", dir.join("shpb.toml").to_str().unwrap(), "--out"])
            .arg(dir.join("out"))
            .args(["--derivatives", "A,C"])
            .output()
            .unwrap()
    };
    let out = run("measured-velocity");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let csv = std::fs::read_to_string(dir.join("out/derivatives.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("time_s,F1_A_n,F2_A_n,F1_C_n,F2_C_n"));
    let last: Vec<f64> = (lines.last().unwrap().split(','))
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(
        last[2] > 0.0 && last[4] > 0.0,
        "F2 rises with A and C: {last:?}"
    );
    assert!(dir.join("out/derivatives.png").is_file());
    let out = run("incident-pulse");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    // the pulse ends before the record: the specimen has left the faces at its end
    let csv = std::fs::read_to_string(dir.join("out/derivatives.csv")).unwrap();
    let largest = |column: usize| {
        (csv.lines().skip(1))
            .map(|l| l.split(',').nth(column).unwrap().parse::<f64>().unwrap())
            .fold(f64::NEG_INFINITY, f64::max)
    };
    assert!(
        largest(2) > 1.0 && largest(4) > 1.0,
        "through the elastic bars too, F2 rises with A and C: {} and {} N",
        largest(2),
        largest(4)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
