//! `mpw drive` refuses temperatures the model cannot take and says when `--adiabatic`
//! cannot heat; a held temperature stays held in the printed result.

use std::path::Path;
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Runs of this process, so that each writes its own output folder.
static RUNS: AtomicUsize = AtomicUsize::new(0);

fn drive(args: &[&str]) -> (bool, String, String) {
    let k = RUNS.fetch_add(1, Ordering::Relaxed);
    let out = std::env::temp_dir().join(format!("mpw-drive-{}-{k}", std::process::id()));
    let o = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .arg("drive")
        .args(args)
        .args(["--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    (o.status.success(), text(&o.stdout), text(&o.stderr))
}

#[test]
fn impossible_temperatures_are_refused_with_the_reason() {
    let (ok, _, err) = drive(&["--temperature=-10"]);
    assert!(!ok && err.contains("must be above 0 K"), "{err}");
    let (ok, _, err) = drive(&["--temperature", "2000"]);
    assert!(!ok, "{err}");
    assert!(
        err.contains("melting temperature θm = 1793.15 K") && err.contains("42crmo4_qt660.toml"),
        "{err}"
    );
}

#[test]
fn adiabatic_without_heating_warns_and_a_held_temperature_is_held() {
    let (ok, _, err) = drive(&["--material", "data/materials/aisi_4340.toml", "--adiabatic"]);
    assert!(
        ok && err.contains("warning: --adiabatic with gamma_tq = 0"),
        "{err}"
    );
    let (ok, out, _) = drive(&["--path", "shear", "--strain", "1", "--temperature", "400"]);
    assert!(ok && out.contains("θ = 400.0 K"), "{out}");
}
