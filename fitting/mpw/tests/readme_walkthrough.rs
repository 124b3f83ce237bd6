//! The README's walk-through, run exactly as printed: every ```` ```toml file=PATH ````
//! block is written to PATH and every ```` ```sh walk-through ```` block is run by `sh -e`,
//! in order, in a folder laid out like the repository (its `data/` and the shared data
//! folder beside it), with this build's `mpw` first on the PATH.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// One step of the walk-through, in README order.
#[derive(Debug)]
enum Step {
    /// Write `text` to the file at this path.
    Write(String, String),
    /// Run these shell lines.
    Run(String),
}

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The walk-through's steps: the fenced blocks of its section marked as files or commands.
fn steps(readme: &str) -> Vec<Step> {
    let section = readme
        .split("\n## ")
        .find(|s| s.starts_with("Walk-through"))
        .expect("a \"## Walk-through\" section in the README");
    let mut steps = Vec::new();
    let mut blocks = section.split("```").skip(1).step_by(2);
    for block in blocks.by_ref() {
        let (info, body) = block.split_once('\n').unwrap_or((block, ""));
        let mut words = info.split_whitespace();
        match (words.next(), words.next()) {
            (Some("sh"), Some("walk-through")) => steps.push(Step::Run(body.to_string())),
            (Some(_), Some(file)) if file.starts_with("file=") => steps.push(Step::Write(
                file["file=".len()..].to_string(),
                body.to_string(),
            )),
            _ => {}
        }
    }
    steps
}

#[test]
fn the_readme_finds_its_walk_through_blocks() {
    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    let steps = steps(&readme);
    let runs = steps.iter().filter(|s| matches!(s, Step::Run(_))).count();
    let files = steps.len() - runs;
    assert!(runs >= 5 && files >= 4, "{steps:?}");
    let commands: String = steps
        .iter()
        .filter_map(|s| match s {
            Step::Run(lines) => Some(lines.as_str()),
            Step::Write(..) => None,
        })
        .collect();
    for command in ["mpw fit", "mpw export", "mpw shpb"] {
        assert!(commands.contains(command), "no `{command}` in {commands}");
    }
}

#[test]
fn the_readme_walk_through_runs_as_printed() {
    let shared = repo_root().join("../shared");
    if !shared.join("data/tension/304L").is_dir() || !shared.join("data/shpb").is_dir() {
        common::skip("../shared/data (the walk-through's records)");
        return;
    }
    let base = std::env::temp_dir().join(format!("mpw-walkthrough-{}", std::process::id()));
    let root = base.join("repository");
    std::fs::create_dir_all(&root).unwrap();
    std::os::unix::fs::symlink(
        repo_root().join("data").canonicalize().unwrap(),
        root.join("data"),
    )
    .unwrap();
    std::os::unix::fs::symlink(shared.canonicalize().unwrap(), base.join("shared")).unwrap();
    let bin = Path::new(env!("CARGO_BIN_EXE_mpw"))
        .parent()
        .unwrap()
        .to_path_buf();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );

    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    for step in steps(&readme) {
        match step {
            Step::Write(file, text) => std::fs::write(root.join(&file), text)
                .unwrap_or_else(|e| panic!("writing {file} of the walk-through: {e}")),
            Step::Run(lines) => {
                let out = Command::new("sh")
                    .args(["-e", "-c", &lines])
                    .current_dir(&root)
                    .env("PATH", &path)
                    .output()
                    .unwrap();
                assert!(
                    out.status.success(),
                    "the README's commands\n{lines}failed:\n{}{}",
                    String::from_utf8_lossy(&out.stdout),
                    String::from_utf8_lossy(&out.stderr)
                );
            }
        }
    }
    for output in [
        "my/fit/report.toml",
        "my/304l.k",
        "my/fit_shpb/report.toml",
        "my/945.inp",
    ] {
        assert!(
            root.join(output).is_file(),
            "the walk-through wrote no {output}"
        );
    }
    let card = std::fs::read_to_string(root.join("my/304l.k")).unwrap();
    assert!(card.contains("*MAT_JOHNSON_COOK"), "{card}");
    std::fs::remove_dir_all(&base).unwrap();
}
