//! A data path that names many records: a folder (every `*.csv` in it) or a file-name
//! pattern with `*` (any run of characters) and `?` (one character) in its last
//! component, e.g. `304L/rate_1800__*.csv`. Matches are sorted by name, so a set of
//! records is read in the same order on every machine.

use std::path::{Path, PathBuf};

/// Whether `path` names many records (a pattern or a folder).
pub fn is_many(path: &Path) -> bool {
    path.is_dir() || file_pattern(path).is_some()
}

fn file_pattern(path: &Path) -> Option<&str> {
    let name = path.file_name()?.to_str()?;
    name.contains(['*', '?']).then_some(name)
}

/// The records `path` names, sorted by name; `path` itself when it names one file.
pub fn expand(path: &Path) -> std::io::Result<Vec<PathBuf>> {
    let (folder, pattern) = if path.is_dir() {
        (path, "*.csv")
    } else if let Some(pattern) = file_pattern(path) {
        (path.parent().unwrap_or(Path::new(".")), pattern)
    } else {
        return Ok(vec![path.to_path_buf()]);
    };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(folder)? {
        let entry = entry?;
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if entry.file_type()?.is_file() && matches(pattern.as_bytes(), name.as_bytes()) {
            files.push(folder.join(name));
        }
    }
    files.sort();
    Ok(files)
}

/// Whether `name` matches `pattern` (`*` any run, `?` one byte, otherwise equal bytes).
fn matches(pattern: &[u8], name: &[u8]) -> bool {
    match pattern.split_first() {
        None => name.is_empty(),
        Some((b'*', rest)) => (0..=name.len()).any(|k| matches(rest, &name[k..])),
        Some((&p, rest)) => match name.split_first() {
            Some((&c, tail)) if p == b'?' || p == c => matches(rest, tail),
            _ => false,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wildcards_match_runs_and_single_characters() {
        let m = |p: &str, n: &str| matches(p.as_bytes(), n.as_bytes());
        assert!(m(
            "rate_1800__*.csv",
            "rate_1800__SRI_1800s_17_Ring1_02.csv"
        ));
        assert!(!m("rate_1800__*.csv", "rate_3600__SRI_3600s_33.csv"));
        assert!(!m("rate_1800__*.csv", "rate_1800__x.csv.bak"));
        assert!(m("t?st_*.csv", "test_05.csv"));
        assert!(!m("t?st_*.csv", "tst_05.csv"));
        assert!(m("*", ""));
        assert!(m("a*b*c", "aXXbYc"));
        assert!(!m("a*b*c", "aXXcYb"));
    }

    #[test]
    fn folders_and_patterns_expand_sorted() {
        let dir = std::env::temp_dir().join(format!("mpw-pattern-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for f in ["b.csv", "a.csv", "a.txt", "c.csv"] {
            std::fs::write(dir.join(f), "").unwrap();
        }
        let names = |v: Vec<PathBuf>| -> Vec<String> {
            v.iter()
                .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
                .collect()
        };
        assert!(is_many(&dir) && is_many(&dir.join("*.csv")) && !is_many(&dir.join("a.csv")));
        assert_eq!(names(expand(&dir).unwrap()), ["a.csv", "b.csv", "c.csv"]);
        assert_eq!(names(expand(&dir.join("[ab]*")).unwrap()).len(), 0);
        assert_eq!(names(expand(&dir.join("a.*")).unwrap()), ["a.csv", "a.txt"]);
        assert_eq!(names(expand(&dir.join("c.csv")).unwrap()), ["c.csv"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
