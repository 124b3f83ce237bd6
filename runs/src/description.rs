//! A run description: what to run (`kind` and its `input` file, with changes `set` by
//! field path), with which seed and threads, and which named results to return. It is
//! written as TOML, one file per task:
//!
//! ```toml
//! kind = "scene"                    # what the program runs (mpw: an MPM scene file)
//! input = "/shared/scenes/taylor_bar_axisymmetric.toml"   # relative: to this file's folder
//! seed = 3                          # optional: the input's random choices (mpw scenes: grid.seed)
//! threads = 1                       # at most this many of the executor's threads (0: all)
//! returns = ["bar.z_max"]           # named results to keep; empty: all
//! [set]                             # changes to the input, by field path
//! "grid.spacing" = 5e-4
//! ```
//!
//! The description's hash (`hash`, FNV-1a 64 of its TOML text) names it in the manifest, so
//! that a result can be traced to exactly the description that produced it.

use anyhow::Result;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunDescription {
    pub kind: String,
    pub input: PathBuf,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    #[serde(default)]
    pub threads: usize,
    #[serde(default)]
    pub returns: Vec<String>,
    #[serde(default)]
    pub set: toml::Table,
}

impl RunDescription {
    /// A description of `kind` on `input`, no changes, seed or thread request, all results.
    pub fn new(kind: &str, input: &Path) -> Self {
        RunDescription {
            kind: kind.to_string(),
            input: input.to_path_buf(),
            seed: None,
            threads: 0,
            returns: Vec::new(),
            set: toml::Table::new(),
        }
    }

    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("a description is plain TOML")
    }

    /// FNV-1a 64 of the description's TOML text, 16 hex digits.
    pub fn hash(&self) -> String {
        format!("{:016x}", fnv1a64(self.to_toml().as_bytes()))
    }

    /// Read a description file; a relative `input` is made relative to the file's folder.
    pub fn read(path: &Path) -> Result<Self> {
        let mut description: RunDescription =
            crate::atomic::read_toml(path, "the run description")?;
        if description.input.is_relative() {
            let folder = path.parent().unwrap_or(Path::new("."));
            description.input = folder.join(&description.input);
        }
        Ok(description)
    }

    /// Write the description to `path` (atomically).
    pub fn write(&self, path: &Path) -> Result<()> {
        crate::atomic::write(path, &self.to_toml())
    }
}

/// The 64-bit FNV-1a hash (Fowler, Noll, Vo): stable across machines and Rust versions,
/// unlike `std`'s hasher; not cryptographic (it names descriptions, it does not guard them).
fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_description_reads_back_as_written_and_its_hash_follows_its_content() {
        let mut d = RunDescription::new("scene", Path::new("/data/scene.toml"));
        d.seed = Some(7);
        d.threads = 1;
        d.returns = vec!["bar.z_max".into()];
        d.set
            .insert("grid.spacing".into(), toml::Value::Float(5e-4));
        let dir = std::env::temp_dir().join(format!("runs-description-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("description.toml");
        d.write(&path).unwrap();
        let back = RunDescription::read(&path).unwrap();
        assert_eq!(back, d);
        assert_eq!(back.hash(), d.hash());
        let mut other = d.clone();
        other.seed = Some(8);
        assert_ne!(other.hash(), d.hash());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// The published FNV-1a 64 test vectors (Fowler, Noll, Vo; IETF draft-eastlake-fnv).
    #[test]
    fn the_hash_is_fnv1a_64() {
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn an_unknown_key_is_refused_with_the_file_named() {
        let dir = std::env::temp_dir().join(format!("runs-description-bad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("d.toml");
        std::fs::write(&path, "kind = \"scene\"\ninput = \"s.toml\"\nsed = 3\n").unwrap();
        let e = RunDescription::read(&path).unwrap_err().to_string();
        assert!(e.contains("d.toml") && e.contains("sed"), "{e}");
        std::fs::write(&path, "kind = \"scene\"\ninput = \"s.toml\"\n").unwrap();
        assert_eq!(
            RunDescription::read(&path).unwrap().input,
            dir.join("s.toml")
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
