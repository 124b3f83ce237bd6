//! Shared helpers for the workspace-level verification tests in `tests/`.

use std::path::PathBuf;

/// Repository root (the workspace directory).
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `data/` shipped with the project.
pub fn data_dir() -> PathBuf {
    repo_root().join("data")
}
