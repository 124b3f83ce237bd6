//! Where in a TOML input file an error is, so that every input file (material, experiment,
//! fit set) reports errors one way: `file:line:column: `key`: what was expected`, then a
//! hint where one helps. Lines and columns are 1-based; a column counts characters.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// A place in a text file: `file:line:column`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    pub file: PathBuf,
    pub line: usize,
    pub column: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.display(), self.line, self.column)
    }
}

impl Location {
    /// The place of byte `offset` of `text`, the contents of `file`.
    pub fn in_text(file: &Path, text: &str, offset: usize) -> Location {
        let before = &text[..floor_char_boundary(text, offset)];
        Location {
            file: file.to_path_buf(),
            line: before.matches('\n').count() + 1,
            column: before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1,
        }
    }
}

fn floor_char_boundary(text: &str, offset: usize) -> usize {
    let mut k = offset.min(text.len());
    while !text.is_char_boundary(k) {
        k -= 1;
    }
    k
}

/// The table a line belongs to: the name of the last `[name]` or `[[name]]` header at or
/// before byte `offset`.
fn table_at(text: &str, offset: usize) -> Option<String> {
    let mut start = 0;
    let mut found = None;
    for line in text.split_inclusive('\n') {
        if start > offset {
            break;
        }
        found = header_name(line).or(found);
        start += line.len();
    }
    found
}

/// `name` of a `[name]` or `[[name]]` header line.
fn header_name(line: &str) -> Option<String> {
    let t = line.trim();
    let inner = t.strip_prefix("[[").and_then(|r| r.split("]]").next());
    let inner = inner.or_else(|| t.strip_prefix('[').and_then(|r| r.split(']').next()))?;
    Some(inner.trim().to_string())
}

/// The key of the line holding byte `offset`: `table.key` for `key = ...` inside a table
/// (`key` at the top level), the table's name on a header line.
pub fn key_at(text: &str, offset: usize) -> Option<String> {
    let offset = floor_char_boundary(text, offset);
    let line_start = text[..offset].rfind('\n').map_or(0, |k| k + 1);
    let line = text[line_start..].lines().next().unwrap_or("");
    if let Some(name) = header_name(line) {
        return Some(name);
    }
    let key = line.split('=').next()?.trim().trim_matches('"');
    if key.is_empty() || !line.contains('=') {
        return None;
    }
    Some(match table_at(text, line_start) {
        Some(table) => format!("{table}.{key}"),
        None => key.to_string(),
    })
}

/// Byte range of the line that sets `key` in the `index`-th (0-based) table named `table`
/// (`None`: the top level, before any header); else of that table's header line; else
/// 0..0.
pub fn find_key(text: &str, table: Option<(&str, usize)>, key: &str) -> Range<usize> {
    let mut start = 0;
    let mut header: Option<Range<usize>> = None;
    let mut inside = table.is_none();
    let mut seen = 0;
    for line in text.split_inclusive('\n') {
        let span = start..start + line.trim_end().len();
        start += line.len();
        if let Some(name) = header_name(line) {
            inside = false;
            if let Some((t, index)) = table {
                if name == t {
                    if seen == index {
                        inside = true;
                        header = Some(span.clone());
                    }
                    seen += 1;
                }
            }
            continue;
        }
        let sets = line
            .split('=')
            .next()
            .is_some_and(|k| k.trim().trim_matches('"') == key && line.contains('='));
        if inside && sets {
            return span;
        }
    }
    header.unwrap_or(0..0)
}

/// A deserialization error of `text` (the contents of `file`) in the common format:
/// `file:line:column: `key`: message` (the key when the error's line names one).
pub fn describe(file: &Path, text: &str, error: &toml::de::Error) -> String {
    let offset = error.span().map_or(0, |s| s.start);
    let at = Location::in_text(file, text, offset);
    match key_at(text, offset) {
        Some(key) => format!("{at}: `{key}`: {}", error.message().trim()),
        None => format!("{at}: {}", error.message().trim()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "name = \"s\"\nstarts = \"x\"\n\n[[parameter]]\nname = \"A\"\nlower = 1\n\n[[parameter]]\nname = \"B\"\nupper = 2\n[thermal]\ntheta0 = 293\n";

    #[test]
    fn keys_are_named_with_their_table() {
        let at = |s: &str| TEXT.find(s).unwrap();
        assert_eq!(key_at(TEXT, at("\"x\"")).as_deref(), Some("starts"));
        assert_eq!(
            key_at(TEXT, at("upper")).as_deref(),
            Some("parameter.upper")
        );
        assert_eq!(
            key_at(TEXT, at("[[parameter]]")).as_deref(),
            Some("parameter")
        );
        assert_eq!(key_at(TEXT, at("293")).as_deref(), Some("thermal.theta0"));
        assert_eq!(key_at(TEXT, at("\n\n") + 1), None);
    }

    #[test]
    fn a_key_is_found_in_the_right_table_and_entry() {
        let line = |r: Range<usize>| Location::in_text(Path::new("f"), TEXT, r.start).line;
        assert_eq!(line(find_key(TEXT, None, "starts")), 2);
        assert_eq!(line(find_key(TEXT, Some(("parameter", 0)), "name")), 5);
        assert_eq!(line(find_key(TEXT, Some(("parameter", 1)), "name")), 9);
        // a key the entry does not set: its header
        assert_eq!(line(find_key(TEXT, Some(("parameter", 1)), "lower")), 8);
        assert_eq!(line(find_key(TEXT, Some(("thermal", 0)), "theta0")), 12);
        assert_eq!(find_key(TEXT, Some(("missing", 0)), "x"), 0..0);
    }

    #[test]
    fn a_deserialization_error_reads_file_line_column_key_message() {
        #[derive(Debug, serde::Deserialize)]
        #[allow(dead_code)]
        struct Set {
            name: String,
            starts: usize,
        }
        let e = toml::from_str::<Set>("name = \"s\"\nstarts = \"x\"\n").unwrap_err();
        let text = describe(Path::new("set.toml"), "name = \"s\"\nstarts = \"x\"\n", &e);
        assert!(
            text.starts_with("set.toml:2:10: `starts`: invalid type: string \"x\""),
            "{text}"
        );
    }
}
