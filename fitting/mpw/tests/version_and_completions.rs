//! `mpw --version` names the commit it was built from; `mpw completions SHELL` prints a
//! completion script for bash, zsh and fish that knows the subcommands; `mpw --help`
//! lists every solver card format.

use std::process::Command;

fn mpw(args: &[&str]) -> (bool, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_mpw"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
    )
}

#[test]
fn the_version_names_the_commit() {
    let (ok, out) = mpw(&["--version"]);
    assert!(ok, "{out}");
    let version = env!("CARGO_PKG_VERSION");
    assert!(out.starts_with(&format!("mpw {version} (")), "{out}");
    assert!(
        out.contains("commit ") || out.contains("unknown commit"),
        "{out}"
    );
}

#[test]
fn completions_know_the_subcommands_in_every_shell() {
    for shell in ["bash", "zsh", "fish"] {
        let (ok, out) = mpw(&["completions", shell]);
        assert!(ok, "{shell}: {out}");
        for sub in ["simulate", "export", "bench-mpm"] {
            assert!(out.contains(sub), "{shell}: no {sub} in\n{out}");
        }
    }
    let (ok, _) = mpw(&["completions", "cmd.exe"]);
    assert!(!ok);
}

#[test]
fn the_help_lists_every_card_format() {
    let (ok, out) = mpw(&["--help"]);
    assert!(ok);
    assert!(
        out.contains("Abaqus") && out.contains("LS-DYNA") && out.contains("JSON"),
        "{out}"
    );
}
