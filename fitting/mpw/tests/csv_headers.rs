//! Every CSV the commands write names its columns one way: words joined by underscores,
//! ending in the SI unit (`time_s`, `force_front_compression_n`, `kinetic_j_per_m`,
//! `true_stress_at_0.05_pa`), no spaces, brackets or slashes (the old `t [s]`, `kinetic
//! [J/m]` fail here); stresses in Pa in every file, the folder summary of `mpw shpb`
//! included (no `_mpa` column).

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn mpw(args: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .current_dir(root())
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Every `.csv` under `dir`.
fn csv_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(csv_files(&p));
        } else if p.extension().is_some_and(|x| x == "csv") {
            out.push(p);
        }
    }
    out
}

#[test]
fn every_csv_header_is_snake_case_with_its_unit() {
    let dir = std::env::temp_dir().join(format!("mpw-csv-headers-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = |name: &str| dir.join(name).to_str().unwrap().to_string();
    mpw(&[
        "simulate",
        "data/scenes/colliding_disks.toml",
        "--out",
        &out("disks"),
    ]);
    mpw(&[
        "simulate",
        "data/scenes/taylor_bar_axisymmetric.toml",
        "--out",
        &out("taylor"),
    ]);
    mpw(&[
        "shpb",
        "data/experiments/shpb_293K.toml",
        "--out",
        &out("shpb"),
    ]);
    mpw(&["fit", "data/experiments/default.toml", "--out", &out("fit")]);
    mpw(&["drive", "--out", &out("drive")]);
    let files = csv_files(&dir);
    assert!(files.len() >= 8, "{files:?}");
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        let header = text.lines().next().unwrap();
        for column in header.split(',') {
            // words joined by underscores; upper case only where a scene names its own
            // bodies and control points (`A_x_m`)
            let fine = !column.is_empty()
                && column
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_.".contains(c));
            assert!(fine, "{}: column `{column}`", f.display());
        }
        assert!(!header.contains("_mpa"), "{}: {header}", f.display());
    }
}

/// The folder summary of `mpw shpb` holds the true stress in Pa, the value of the record's
/// own `shpb.csv` at that true strain.
#[test]
fn the_shpb_summary_is_in_pa_like_the_record() {
    let dir = std::env::temp_dir().join(format!("mpw-csv-summary-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let folder = dir.join("records");
    std::fs::create_dir_all(&folder).unwrap();
    let experiments = root().join("data/experiments").canonicalize().unwrap();
    let record = std::fs::read_to_string(experiments.join("shpb_293K.toml"))
        .unwrap()
        .replace("data = \"", &format!("data = \"{}/", experiments.display()));
    std::fs::write(folder.join("r.toml"), record).unwrap();
    mpw(&[
        "shpb",
        folder.to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    let summary = std::fs::read_to_string(dir.join("out/summary.csv")).unwrap();
    let header: Vec<&str> = summary.lines().next().unwrap().split(',').collect();
    let row: Vec<&str> = summary.lines().nth(1).unwrap().split(',').collect();
    let column = header
        .iter()
        .position(|h| *h == "true_stress_at_0.05_pa")
        .unwrap();
    let stress: f64 = row[column].parse().unwrap();
    // the record's own curve at true strain 0.05, on loading
    let record = std::fs::read_to_string(dir.join("out/r/shpb.csv")).unwrap();
    let names: Vec<&str> = record.lines().next().unwrap().split(',').collect();
    let col = |n: &str| names.iter().position(|h| *h == n).unwrap();
    let (e, s) = (
        col("true_strain_compression"),
        col("true_stress_3wave_compression_pa"),
    );
    let rows: Vec<Vec<f64>> = record
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let k = rows.iter().position(|r| r[e] >= 0.05).unwrap();
    let (a, b) = (&rows[k - 1], &rows[k]);
    let expected = a[s] + (0.05 - a[e]) / (b[e] - a[e]) * (b[s] - a[s]);
    assert!(
        (stress / expected - 1.0).abs() < 1e-9,
        "{stress} vs {expected}"
    );
    assert!(stress > 1e8, "{stress} is not in Pa");
}
