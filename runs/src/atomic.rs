//! Files that appear whole or not at all: written beside their final name, then renamed
//! (a rename within one folder is atomic on POSIX file systems, NFS and Lustre included),
//! so that a reader polling for a task's files never sees half of one; and the task files
//! as TOML (`write_toml`, `read_toml`).

use anyhow::{Context, Result};
use std::io::Write;
use std::path::Path;

/// Write `text` to `path` through a temporary file in the same folder and a rename.
pub fn write(path: &Path, text: &str) -> Result<()> {
    let name = path
        .file_name()
        .with_context(|| format!("{}: not a file name", path.display()))?;
    let mut temporary = name.to_os_string();
    temporary.push(format!(".{}.partial", std::process::id()));
    let temporary = path.with_file_name(temporary);
    let mut file = std::fs::File::create(&temporary)
        .with_context(|| format!("cannot create {}", temporary.display()))?;
    file.write_all(text.as_bytes())
        .and_then(|()| file.sync_all())
        .with_context(|| format!("cannot write {}", temporary.display()))?;
    std::fs::rename(&temporary, path).with_context(|| {
        format!(
            "cannot rename {} to {}",
            temporary.display(),
            path.display()
        )
    })
}

/// Write `value` as TOML to `path` (atomically).
pub fn write_toml<T: serde::Serialize>(path: &Path, value: &T) -> Result<()> {
    let text = toml::to_string(value).with_context(|| format!("{} as TOML", path.display()))?;
    write(path, &text)
}

/// Read the TOML file `path`, `what` it is naming it in errors (`the manifest`).
pub fn read_toml<T: serde::de::DeserializeOwned>(path: &Path, what: &str) -> Result<T> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read {what} {}", path.display()))?;
    toml::from_str(&text).map_err(|e| anyhow::anyhow!("{}: {}", path.display(), e.message()))
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_written_file_holds_the_text_and_no_partial_file_stays() {
        let dir = std::env::temp_dir().join(format!("runs-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("manifest.toml");
        super::write(&path, "a = 1\n").unwrap();
        super::write(&path, "a = 2\n").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "a = 2\n");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("manifest.toml")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
