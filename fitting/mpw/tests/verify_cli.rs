//! `mpw verify --part`: only the named parts of the table run, each saying on stderr when
//! it is done; a name that is no part ends with the list of parts.

use std::path::Path;
use std::process::{Command, Output};

fn verify(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mpw"))
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .arg("verify")
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn only_the_named_parts_run() {
    let o = verify(&["--part", "fit"]);
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert!(o.status.success(), "{err}");
    // the table: a header, the rows, and the summary `N cases, ...`
    let rows: Vec<&str> = (out.lines().skip(1))
        .take_while(|l| !l.contains(" cases, "))
        .collect();
    assert!(!rows.is_empty(), "{out}");
    assert!(rows.iter().all(|r| r.starts_with("fit/")), "{out}");
    assert!(err.contains("verify: part 1/1 `fit`:"), "{err}");
}

#[test]
fn an_unknown_part_is_refused_with_the_list() {
    let o = verify(&["--part", "fit,tayler"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("no verification part `tayler`"), "{err}");
    assert!(err.contains("materials, shpb, fit, fit-mpm"), "{err}");
}
