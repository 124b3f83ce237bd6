//! A task's manifest: which program ran which description (its hash), with which seed and
//! threads, on which host, for how long, and how it ended. It is written last, atomically:
//! its presence means the task has finished. `Failed` is a failure of the task itself (a
//! description the program refuses, a missing input, a result the run does not give); it
//! would fail again, so no executor runs it twice. A task that leaves no manifest was
//! stopped from outside (killed, out of memory, over its time limit, a node lost) and may
//! be tried again.

use anyhow::Result;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The program that runs tasks: its name, version and the commit it was built from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Program<'a> {
    pub name: &'a str,
    pub version: &'a str,
    pub commit: &'a str,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    Ok,
    Failed,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// Name and version, e.g. `mpw 0.1.0`.
    pub program: String,
    pub commit: String,
    pub description_hash: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// The threads the task ran on.
    pub threads: usize,
    pub host: String,
    pub wall_seconds: f64,
    pub status: Status,
    /// Why the task failed (status `failed`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub message: Option<String>,
}

impl Manifest {
    pub fn write(&self, path: &Path) -> Result<()> {
        crate::atomic::write_toml(path, self)
    }

    pub fn read(path: &Path) -> Result<Self> {
        crate::atomic::read_toml(path, "the manifest")
    }
}

/// This machine's host name (empty if the system does not say).
pub fn host_name() -> String {
    let mut buffer = [0u8; 256];
    // SAFETY: the buffer is writable for its whole length, which is what is passed.
    let rc = unsafe { libc::gethostname(buffer.as_mut_ptr().cast(), buffer.len()) };
    if rc != 0 {
        return String::new();
    }
    let end = buffer.iter().position(|&b| b == 0).unwrap_or(buffer.len());
    String::from_utf8_lossy(&buffer[..end]).into_owned()
}
