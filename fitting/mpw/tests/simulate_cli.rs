//! `mpw simulate` warns at the start when Δt is above the CFL limit and names that setting
//! as the likely cause when the run then fails.

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
        err.contains("warning: time.safety = 1.5 exceeds 1"),
        "{err}"
    );
    assert!(err.contains("simulation failed at step"), "{err}");
    assert!(err.contains("likely cause: time.safety = 1.5"), "{err}");
    assert!(
        dir.join("out/history.csv").is_file(),
        "the failed run keeps its output"
    );
}
