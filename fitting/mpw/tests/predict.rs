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
        .filter(|l| l.contains("stage 1 start 1:"))
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
