//! A numeric CSV table: `#` comment lines and blank lines, one header line of column
//! names, then rows of comma-separated numbers (no quoting).
//! Each row keeps its line number so that every bad value can be reported as
//! `file:line: column k "name"`. The comment lines above the header are kept: they may
//! hold metadata (`# temperature_K: 297.04`, read by `header`).

use super::error::{ExperimentError, Location};
use crate::experiment::limits::TEXT_FILE_BYTES;
use std::path::{Path, PathBuf};

pub(crate) struct CsvTable {
    pub file: PathBuf,
    header_line: usize,
    names: Vec<String>,
    /// (line number, text after `#`) of the comment lines above the header.
    pub comments: Vec<(usize, String)>,
    /// (line number, fields) of each data row.
    rows: Vec<(usize, Vec<String>)>,
}

impl CsvTable {
    pub fn read(file: &Path) -> Result<CsvTable, ExperimentError> {
        if let Ok(meta) = std::fs::metadata(file) {
            TEXT_FILE_BYTES
                .check(meta.len() as f64, || {
                    "the file is read whole; split it or thin its samples".into()
                })
                .map_err(|source| ExperimentError::TooLarge {
                    file: file.to_path_buf(),
                    source: Box::new(source),
                })?;
        }
        let text = std::fs::read_to_string(file).map_err(|reason| ExperimentError::Io {
            file: file.to_path_buf(),
            reason,
        })?;
        let mut header: Option<(usize, Vec<String>)> = None;
        let mut rows = Vec::new();
        let mut comments = Vec::new();
        for (k, raw) in text.lines().enumerate() {
            let line = k + 1;
            let trimmed = raw.trim();
            if let Some(comment) = trimmed.strip_prefix('#') {
                if header.is_none() {
                    comments.push((line, comment.trim().to_string()));
                }
                continue;
            }
            if trimmed.is_empty() {
                continue;
            }
            let fields: Vec<String> = trimmed.split(',').map(|f| f.trim().to_string()).collect();
            match &header {
                None => {
                    for (k, name) in fields.iter().enumerate() {
                        if fields[..k].contains(name) {
                            return Err(ExperimentError::DuplicateColumn {
                                file: file.to_path_buf(),
                                line,
                                column: k + 1,
                                name: name.clone(),
                            });
                        }
                    }
                    header = Some((line, fields));
                }
                Some((_, names)) => {
                    if fields.len() != names.len() {
                        return Err(ExperimentError::FieldCount {
                            file: file.to_path_buf(),
                            line,
                            found: fields.len(),
                            expected: names.len(),
                        });
                    }
                    rows.push((line, fields));
                }
            }
        }
        let (header_line, names) = header.ok_or(ExperimentError::TooFewRows {
            file: file.to_path_buf(),
            found: 0,
            needed: 2,
        })?;
        Ok(CsvTable {
            file: file.to_path_buf(),
            header_line,
            names,
            rows,
            comments,
        })
    }

    /// `read`, and at least `needed` data rows.
    pub fn read_rows(file: &Path, needed: usize) -> Result<CsvTable, ExperimentError> {
        let table = CsvTable::read(file)?;
        if table.len() < needed {
            return Err(ExperimentError::TooFewRows {
                file: file.to_path_buf(),
                found: table.len(),
                needed,
            });
        }
        Ok(table)
    }

    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Line number of data row `i`.
    pub fn line_of(&self, i: usize) -> usize {
        self.rows[i].0
    }

    /// 1-based position of column `name` in the header.
    pub fn position(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name).map(|k| k + 1)
    }

    /// The values of column `name` as finite numbers; `named_by` is the TOML key that
    /// asked for it (reported if the column is missing).
    pub fn column(&self, name: &str, named_by: &Location) -> Result<Vec<f64>, ExperimentError> {
        let k = self
            .position(name)
            .ok_or_else(|| ExperimentError::MissingColumn {
                file: self.file.clone(),
                line: self.header_line,
                name: name.to_string(),
                named_by: named_by.clone(),
                available: self.names.join(", "),
            })?
            - 1;
        self.rows
            .iter()
            .map(|(line, record)| {
                let text = &record[k];
                let value: f64 = text.parse().map_err(|_| ExperimentError::BadNumber {
                    file: self.file.clone(),
                    line: *line,
                    column: k + 1,
                    name: name.to_string(),
                    text: text.to_string(),
                })?;
                if !value.is_finite() {
                    return Err(ExperimentError::NotFinite {
                        file: self.file.clone(),
                        line: *line,
                        column: k + 1,
                        name: name.to_string(),
                        value,
                    });
                }
                Ok(value)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(name: &str, text: &str) -> Result<CsvTable, ExperimentError> {
        let dir = std::env::temp_dir().join(format!("mpw-table-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join(name);
        std::fs::write(&file, text).unwrap();
        CsvTable::read(&file)
    }

    fn here() -> Location {
        Location {
            file: "e.toml".into(),
            line: 3,
            column: 1,
        }
    }

    #[test]
    fn line_numbers_count_comment_and_blank_lines() {
        let t = table("lines.csv", "# a\n# b\n\ntime_s, x\n0, 1\n\n1, 2\n").unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!((t.line_of(0), t.line_of(1)), (5, 7));
        assert_eq!(t.column("x", &here()).unwrap(), vec![1.0, 2.0]);
    }

    #[test]
    fn missing_column_names_header_line_and_toml_key() {
        let t = table("missing.csv", "# c\ntime_s,x\n0,1\n").unwrap();
        let e = t.column("stress", &here()).unwrap_err();
        assert!(
            matches!(e, ExperimentError::MissingColumn { line: 2, .. }),
            "{e}"
        );
        let msg = e.to_string();
        assert!(
            msg.contains("missing.csv:2") && msg.contains("e.toml:3:1"),
            "{msg}"
        );
    }

    #[test]
    fn bad_numbers_nan_and_field_counts_are_located() {
        let t = table("bad.csv", "t,x\n0,1\n1,abc\n").unwrap();
        let e = t.column("x", &here()).unwrap_err();
        assert!(
            matches!(&e, ExperimentError::BadNumber { line: 3, column: 2, text, .. } if text == "abc"),
            "{e}"
        );
        let t = table("nan.csv", "t,x\n0,1\n1,NaN\n").unwrap();
        let e = t.column("x", &here()).unwrap_err();
        assert!(
            matches!(
                e,
                ExperimentError::NotFinite {
                    line: 3,
                    column: 2,
                    ..
                }
            ),
            "{e}"
        );
        let e = table("count.csv", "t,x\n0,1\n1,2,3\n").err().unwrap();
        assert!(
            matches!(
                e,
                ExperimentError::FieldCount {
                    line: 3,
                    found: 3,
                    expected: 2,
                    ..
                }
            ),
            "{e}"
        );
        let e = table("dup.csv", "t,x,t\n0,1,2\n").err().unwrap();
        assert!(
            matches!(e, ExperimentError::DuplicateColumn { column: 3, .. }),
            "{e}"
        );
    }
}
