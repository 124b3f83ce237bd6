//! The commit `mpw --version` names: `git rev-parse --short HEAD` of the checkout it was
//! built from (with `-dirty` for uncommitted changes), or "unknown commit" outside one.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    let text = String::from_utf8(out.stdout).ok()?;
    out.status.success().then(|| text.trim().to_owned())
}

fn main() {
    let commit = match git(&["rev-parse", "--short", "HEAD"]) {
        Some(hash) => {
            let dirty = git(&["status", "--porcelain", "--untracked-files=no"]);
            let mark = if dirty.is_some_and(|d| !d.is_empty()) {
                "-dirty"
            } else {
                ""
            };
            format!("commit {hash}{mark}")
        }
        None => "unknown commit".to_owned(),
    };
    println!("cargo:rustc-env=MPW_COMMIT={commit}");
    // a new commit or a change of the work tree's state rebuilds the version string
    for path in ["../../.git/HEAD", "../../.git/index"] {
        println!("cargo:rerun-if-changed={path}");
    }
}
