//! A fit that no parameter set can make good (here: a strain column of fractions declared
//! as "%", so every strain is 100× too small) exits non-zero with the likely causes, after
//! writing its report; `--allow-poor-fit` exits 0. Its parameters end on their bounds with
//! undefined correlations: the summary says so and never "converged".

use std::path::Path;
use std::process::Command;

#[test]
fn a_strain_in_percent_declared_on_fractions_is_a_poor_fit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = std::env::temp_dir().join(format!("mpw-poor-fit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let experiments = root.join("data/experiments");
    std::fs::copy(
        experiments.join("qs_tension.csv"),
        dir.join("qs_tension.csv"),
    )
    .unwrap();
    let toml = std::fs::read_to_string(experiments.join("qs_tension.toml")).unwrap();
    let wrong = toml.replace(
        "strain = { name = \"engineering_strain\", unit = \"1\" }",
        "strain = { name = \"engineering_strain\", unit = \"%\" }",
    );
    assert_ne!(wrong, toml);
    std::fs::write(dir.join("qs_tension.toml"), wrong).unwrap();
    let material = root.join("data/materials/42crmo4_qt660.toml");
    let mut set = format!(
        "name = \"percent mistake\"\nmaterial = \"{}\"\n",
        material.display()
    );
    for (p, lo, hi, start) in [
        ("A", 2e8, 2e9, 6e8),
        ("B", 1e8, 4e9, 1e9),
        ("N", 0.05, 1.5, 0.5),
    ] {
        set += &format!(
            "[[parameter]]\nname = \"{p}\"\nlower = {lo:e}\nupper = {hi:e}\nstart = {start:e}\n"
        );
    }
    set += "[[experiment]]\nfile = \"qs_tension.toml\"\n";
    std::fs::write(dir.join("set.toml"), set).unwrap();
    let fit = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_mpw"))
            .args(["fit", dir.join("set.toml").to_str().unwrap(), "--out"])
            .arg(dir.join("out"))
            .args(extra)
            .output()
            .unwrap()
    };
    let out = fit(&[]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("set.toml: poor fit") && err.contains("(67 %)"),
        "{err}"
    );
    assert!(
        err.contains("a strain in % declared as \"1\" or the reverse"),
        "{err}"
    );
    let table = String::from_utf8_lossy(&out.stdout);
    let summary = table.lines().find(|l| l.starts_with("Summary:")).unwrap();
    assert!(
        summary.starts_with("Summary: stopped at the bounds: B at its upper bound 4000.00 MPa"),
        "{summary}"
    );
    assert!(!table.contains("(converged)"), "{table}");
    assert_eq!(summary.matches("WARNING").count(), 1, "{summary}");
    assert!(summary.contains("correlations are undefined"), "{summary}");
    assert!(
        dir.join("out/report.toml").is_file(),
        "the report is written"
    );
    assert!(fit(&["--allow-poor-fit"]).status.success());
}
