//! `mpw fit` stopped by SIGTERM (as by Ctrl-C) writes a partial report marked interrupted,
//! exits non-zero naming where the report is, and a card exported from that report warns
//! that its values are not an optimum.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};

#[test]
fn a_terminated_fit_leaves_a_partial_report() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = std::env::temp_dir().join(format!("mpw-fit-interrupt-{}", std::process::id()));
    let mut child = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .args(["fit", "data/experiments/fit_304l.toml", "--out"])
        .arg(&out)
        .current_dir(&root)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut first = String::new();
    stderr.read_line(&mut first).unwrap();
    assert!(first.starts_with("fitting"), "{first}");
    // The handler is installed before that line and the fit's first start takes a good
    // fraction of a second: stop it now, whichever start the signal lands in.
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut rest).unwrap();
    let status = child.wait().unwrap();
    assert!(!status.success(), "an interrupted fit must not exit 0");
    assert!(
        rest.contains("the fit was interrupted; the partial report")
            && rest.contains(out.to_str().unwrap()),
        "{rest}"
    );
    let report = std::fs::read_to_string(out.join("report.toml")).unwrap();
    assert!(report.contains("\ninterrupted = true"), "{report}");
    assert!(report.contains("termination = \"interrupted"), "{report}");
    assert!(report.contains("converged = false"), "{report}");
    let card = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .args(["export", "--format", "lsdyna", "--params"])
        .arg(out.join("report.toml"))
        .current_dir(&root)
        .output()
        .unwrap();
    assert!(
        card.status.success(),
        "{}",
        String::from_utf8_lossy(&card.stderr)
    );
    let text = String::from_utf8_lossy(&card.stdout);
    assert!(text.contains("interrupted"), "{text}");
    assert!(String::from_utf8_lossy(&card.stderr).contains("interrupted"));
    std::fs::remove_dir_all(&out).unwrap();
}
