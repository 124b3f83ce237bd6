//! `mpw export --params report.toml` alone writes a card of the fit's material with the
//! fit's covered ranges and warnings as comment lines of at most 80 characters; a material
//! file that does not match the report is refused.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn mpw(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mpw"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .output()
        .unwrap()
}

/// The shipped default set, fitted into `dir`.
fn fitted_report(dir: &Path) -> PathBuf {
    let experiments = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/experiments")
        .canonicalize()
        .unwrap();
    let set = std::fs::read_to_string(experiments.join("default.toml")).unwrap();
    let set = set
        .replace("file = \"", &format!("file = \"{}/", experiments.display()))
        .replace(
            "material = \"",
            &format!("material = \"{}/", experiments.display()),
        );
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("set.toml"), set).unwrap();
    let out = mpw(&[
        "fit",
        dir.join("set.toml").to_str().unwrap(),
        "--out",
        dir.join("fit").to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    dir.join("fit/report.toml")
}

#[test]
fn a_card_from_a_report_alone_carries_the_fit_s_ranges() {
    let dir = std::env::temp_dir().join(format!("mpw-export-{}", std::process::id()));
    let report = fitted_report(&dir);
    let out = mpw(&[
        "export",
        "--params",
        report.to_str().unwrap(),
        "--format",
        "lsdyna",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let card = String::from_utf8_lossy(&out.stdout);
    assert!(card.contains("*MAT_JOHNSON_COOK"), "{card}");
    let comments: String = card
        .lines()
        .filter(|l| l.starts_with('$'))
        .collect::<Vec<_>>()
        .join(" ");
    for said in [
        "fitted (A, B, C, M, N) to 3 experiment(s)",
        "strain rates 5.6e-5 to",
        "temperatures 293.1 to 573.1 K",
        "extrapolation",
    ] {
        assert!(
            comments.replace("$  ", "").contains(said),
            "no `{said}` in\n{card}"
        );
    }
    assert!(err.contains("note: fitted (A, B, C, M, N)"), "{err}");
    for line in card.lines() {
        assert!(
            line.chars().count() <= 80,
            "{} characters: {line}",
            line.chars().count()
        );
    }
    let abaqus = mpw(&["export", "--params", report.to_str().unwrap()]);
    let card = String::from_utf8_lossy(&abaqus.stdout);
    assert!(card.contains("*MATERIAL, NAME=42CRMO4_QT660"), "{card}");
    assert!(card.contains("ADIABATIC"), "{card}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_material_that_is_not_the_report_s_is_refused() {
    let dir = std::env::temp_dir().join(format!("mpw-export-other-{}", std::process::id()));
    let report = fitted_report(&dir);
    let out = mpw(&[
        "export",
        "data/materials/ss304l.toml",
        "--params",
        report.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("data/materials/ss304l.toml: not the material of the fit")
            && err.contains("`E` = 1.93e11 in the file"),
        "{err}"
    );
    let same = mpw(&[
        "export",
        "data/materials/42crmo4_qt660.toml",
        "--params",
        report.to_str().unwrap(),
    ]);
    assert!(
        same.status.success(),
        "{}",
        String::from_utf8_lossy(&same.stderr)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A law a Johnson-Cook card cannot carry is refused with the file and the law, not
/// written as the JC card of its JC-named parameters (a Huh-Kang law has A, B, N, C too).
#[test]
fn a_law_that_is_not_johnson_cook_gets_no_johnson_cook_card() {
    let out = mpw(&["export", "data/materials/ss304l_huh_kang.toml"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("data/materials/ss304l_huh_kang.toml: the flow-stress law is power × huh-kang × johnson-cook"),
        "{err}"
    );
    assert!(
        out.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
}
