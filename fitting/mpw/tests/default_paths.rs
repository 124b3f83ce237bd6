//! Run from a folder without `data/`, the commands whose defaults live there end with the
//! missing file named and a hint to run from the repository root or name the files.

use std::process::Command;

#[test]
fn defaults_outside_the_repository_end_with_a_hint() {
    let dir = std::env::temp_dir().join(format!("mpw-elsewhere-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for args in [vec!["fit"], vec!["verify"]] {
        let o = Command::new(env!("CARGO_BIN_EXE_mpw"))
            .current_dir(&dir)
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.contains(": data/"),
            "{args:?}: {err}"
        );
        assert!(
            err.contains("hint: the default files (data/...)"),
            "{args:?}: {err}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
