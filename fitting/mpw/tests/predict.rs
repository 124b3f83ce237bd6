//! `mpw predict`: a set evaluated with the parameters of a fit report reproduces the
//! fit's predictions exactly; the set's own material gives other numbers; a set without
//! free parameters is refused by `mpw fit` with a pointer to `mpw predict`. Also: the
//! fit's progress off a terminal is one line per stage and start.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn mpw(args: &[&str]) -> std::process::Output {
    let out = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .current_dir(root())
        .args(args)
        .output()
        .unwrap();
    out
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mpw-predict-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The `*_fitted_*` columns of every experiment CSV in `dir`, by file name.
fn fitted_columns(dir: &Path) -> Vec<(String, Vec<String>)> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "csv"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(f).unwrap();
            let mut lines = text.lines();
            let header: Vec<&str> = lines.next().unwrap().split(',').collect();
            let cols: Vec<usize> = (0..header.len())
                .filter(|&k| header[k].contains("_fitted_"))
                .collect();
            let values = lines
                .flat_map(|l| {
                    let fields: Vec<&str> = l.split(',').collect();
                    cols.iter()
                        .map(|&k| fields[k].to_string())
                        .collect::<Vec<_>>()
                })
                .collect();
            (
                f.file_name().unwrap().to_string_lossy().into_owned(),
                values,
            )
        })
        .collect()
}

#[test]
fn a_fit_report_predicts_what_the_fit_predicted() {
    let (fit, predicted, base) = (scratch("fit"), scratch("pred"), scratch("base"));
    let set = "data/experiments/default.toml";
    let out = mpw(&["fit", set, "--out", fit.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    // Off a terminal the progress is one line per stage and start, not carriage returns.
    assert!(!err.contains('\r'), "{err:?}");
    let lines = err
        .lines()
        .filter(|l| l.contains("stage 1/1 start 1/1:"))
        .count();
    assert_eq!(lines, 1, "{err}");
    let report = fit.join("report.toml");
    let out = mpw(&[
        "predict",
        set,
        "--params",
        report.to_str().unwrap(),
        "--out",
        predicted.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("(no optimizer)"), "{stdout}");
    let (a, b) = (fitted_columns(&fit), fitted_columns(&predicted));
    assert_eq!(a.len(), 3, "three experiments in the default set");
    assert_eq!(a, b, "the same numbers, digit for digit");
    // The set's own material (the truth of the synthetic set, noise-free) differs.
    let out = mpw(&["predict", set, "--out", base.to_str().unwrap()]);
    assert!(out.status.success());
    assert_ne!(fitted_columns(&base), a);
}

#[test]
fn a_set_without_parameters_is_predicted_not_fitted() {
    let dir = scratch("noparams");
    let text = std::fs::read_to_string(root().join("data/experiments/default.toml")).unwrap();
    let experiments = root().join("data/experiments");
    let kept: String = text
        .split("[[")
        .filter(|part| !part.starts_with("parameter]]"))
        .collect::<Vec<_>>()
        .join("[[")
        .replace("\"../", &format!("\"{}/../", experiments.display()))
        .replace("file = \"", &format!("file = \"{}/", experiments.display()));
    let set = dir.join("no_parameters.toml");
    std::fs::write(&set, kept).unwrap();
    let set_arg = set.to_str().unwrap();
    let fit = mpw(&["fit", set_arg, "--out", dir.to_str().unwrap()]);
    let predict = mpw(&["predict", set_arg, "--out", dir.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&fit.stderr);
    assert!(!fit.status.success());
    assert!(
        err.contains("no_parameters.toml: the set has no [[parameter]], nothing to fit; `mpw predict` evaluates it"),
        "{err}"
    );
    assert!(
        predict.status.success(),
        "{}",
        String::from_utf8_lossy(&predict.stderr)
    );
}

/// An MPM level whose specimen melts at the final parameters (42CrMo4 with θm = 330 K,
/// θ0 = 293.15 K) says so on standard error, in the report and in a card exported from
/// it; with the real θm = 1793 K it says nothing.
#[test]
fn an_mpm_level_with_molten_points_warns_in_the_report_and_the_card() {
    let dir = scratch("hot");
    let steel = std::fs::read_to_string(root().join("data/materials/42crmo4_qt660.toml")).unwrap();
    let experiment = root()
        .join("data/experiments/shpb_293K.toml")
        .canonicalize()
        .unwrap();
    std::fs::write(
        dir.join("set.toml"),
        format!(
            "name = \"molten\"\nmaterial = \"steel.toml\"\n[[experiment]]\nfile = \"{}\"\n\
             window = [1.5e-5, 1.15e-4]\nforces = \"f2\"\nlevel = \"mpm-axisymmetric\"\nlayers = 4\n",
            experiment.display()
        ),
    )
    .unwrap();
    let run = |theta_m: &str| {
        let material = steel.replace("theta_m = 1793.15", &format!("theta_m = {theta_m}"));
        std::fs::write(dir.join("steel.toml"), material).unwrap();
        let out = mpw(&[
            "predict",
            dir.join("set.toml").to_str().unwrap(),
            "--out",
            dir.join("out").to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "{err}");
        (
            err,
            std::fs::read_to_string(dir.join("out/report.toml")).unwrap(),
        )
    };
    let needle = "shpb_293K: specimen: points reached the melting temperature θm = 330 K";
    let (err, report) = run("330.0");
    assert!(err.contains(&format!("warning: {needle}")), "{err}");
    assert!(
        report.contains("warnings = [\"specimen: points reached the melting"),
        "{report}"
    );
    let card = mpw(&[
        "export",
        "--format",
        "abaqus",
        "--params",
        dir.join("out/report.toml").to_str().unwrap(),
    ]);
    let card_text = String::from_utf8_lossy(&card.stdout);
    let joined: String = card_text
        .lines()
        .filter_map(|l| l.strip_prefix("** "))
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        joined.contains("WARNING: shpb_293K: specimen: points reached"),
        "{card_text}"
    );
    let (err, report) = run("1793.15");
    assert!(
        !err.contains("melting temperature") && report.contains("warnings = []"),
        "{err}"
    );
}
