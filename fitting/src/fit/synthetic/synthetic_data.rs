//! The MPM-level synthetic's data (`mpm_synthetic::data`) in a file, so that a check which
//! fits to it does not run the 3D model for minutes first: a CSV of `time_s,f2_n` under a
//! header that names what made it, `# key = value` lines: the data model
//! (`model = mpm-3d-quarter:40`), its shape function (`kernel = cpdi`) and every parameter
//! of the true material (`param E = 2.07e11`, ...). Numbers are written in the shortest form
//! that reads back to the same f64, so a file read back is the series that was written.
//!
//! Reading checks the header against the model, kernel and material asked for and the
//! times against `mpm_synthetic::compared_times`: a file made by another model or truth
//! is an error naming the file and the key, never silently fitted.

use super::mpm_synthetic::compared_times;
use crate::fit::levels::model::Material;
use crate::shpb_model::Discretization;
use anyhow::{bail, Context, Result};
use materials::material::Model;
use mpm_core::shape::ShapeFunction;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// The header of the data made by `at` with `kernel` and `truth`.
fn header(truth: &Material, at: Discretization, kernel: ShapeFunction) -> BTreeMap<String, String> {
    let mut keys = BTreeMap::from([
        ("model".to_string(), at.to_string()),
        ("kernel".to_string(), kernel.name().to_string()),
    ]);
    for name in truth.param_names() {
        let value = truth.param(name).expect("a named parameter has a value");
        keys.insert(format!("param {name}"), format!("{value:e}"));
    }
    keys
}

/// Write `f2` [N] (at `compared_times`), the data of `at` with `kernel` and `truth`.
pub fn write(
    path: &Path,
    f2: &[f64],
    truth: &Material,
    (at, kernel): (Discretization, ShapeFunction),
) -> Result<()> {
    let times = compared_times();
    assert_eq!(times.len(), f2.len(), "one force per compared time");
    let mut text = String::from(
        "# F2 [N], the transmitter-face force of the MPM-level synthetic's data model\n\
         # (fitting::fit::synthetic::mpm_synthetic), written by `mpw synth --shpb-3d FILE`\n",
    );
    for (key, value) in header(truth, at, kernel) {
        writeln!(text, "# {key} = {value}")?;
    }
    text.push_str("time_s,f2_n\n");
    for (t, f) in times.iter().zip(f2) {
        writeln!(text, "{t:e},{f:e}")?;
    }
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))
}

/// F2 [N] at `compared_times` from `path`, which must hold the data of `at` with `kernel`
/// and `truth`.
pub fn read(
    path: &Path,
    truth: &Material,
    (at, kernel): (Discretization, ShapeFunction),
) -> Result<Vec<f64>> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let file = path.display();
    let mut found = BTreeMap::new();
    let mut rows = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if let Some(comment) = line.strip_prefix('#') {
            if let Some((key, value)) = comment.split_once('=') {
                found.insert(key.trim().to_string(), value.trim().to_string());
            }
        } else if line != "time_s,f2_n" {
            let parse = |field: Option<&str>| field.and_then(|x| x.trim().parse::<f64>().ok());
            let mut fields = line.split(',');
            match (parse(fields.next()), parse(fields.next()), fields.next()) {
                (Some(t), Some(f), None) => rows.push((n + 1, t, f)),
                _ => bail!(
                    "{file}, line {}: expected `time_s,f2_n` (two numbers)",
                    n + 1
                ),
            }
        }
    }
    for (key, expected) in header(truth, at, kernel) {
        match found.get(&key) {
            Some(value) if *value == expected => {}
            Some(value) => bail!(
                "{file}: `{key}` is {value}, the data asked for has {expected} \
                 (write it again: mpw synth --shpb-3d {file})"
            ),
            None => bail!("{file}: no `# {key} = ...` line in the header"),
        }
    }
    let times = compared_times();
    if rows.len() != times.len() {
        bail!(
            "{file}: {} rows, expected {} (one per compared time)",
            rows.len(),
            times.len()
        );
    }
    for ((line, t, _), expected) in rows.iter().zip(&times) {
        if t != expected {
            bail!("{file}, line {line}: time {t:e} s, expected {expected:e} s");
        }
    }
    Ok(rows.into_iter().map(|(_, _, f)| f).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::levels::model::with_values;
    use crate::shpb_model::ModelLevel;

    fn truth() -> Material {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/materials/steel_945.toml");
        materials::load_elasto_plastic(file).unwrap()
    }

    const AT: Discretization = Discretization {
        level: ModelLevel::Quarter3d,
        layers: 40,
    };

    #[test]
    fn a_written_series_reads_back_to_the_bit() {
        let dir = std::env::temp_dir().join(format!("synthetic_data_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("f2.csv");
        let f2: Vec<f64> = (0..compared_times().len())
            .map(|k| 1.0e5 * (k as f64 * 0.37).sin() + 1.0 / 3.0)
            .collect();
        write(&path, &f2, &truth(), (AT, ShapeFunction::Cpdi)).unwrap();
        let back = read(&path, &truth(), (AT, ShapeFunction::Cpdi)).unwrap();
        assert!(back
            .iter()
            .zip(&f2)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        // another truth, another kernel: refused, naming the key
        let other = with_values(&truth(), &["B"], &[330e6]);
        let err = read(&path, &other, (AT, ShapeFunction::Cpdi)).unwrap_err();
        assert!(err.to_string().contains("`param B`"), "{err}");
        let err = read(&path, &truth(), (AT, ShapeFunction::Linear)).unwrap_err();
        assert!(err.to_string().contains("`kernel`"), "{err}");
        // a damaged row and a missing row: refused, naming the line or the count
        let text = std::fs::read_to_string(&path).unwrap();
        let rows_start = text.lines().position(|l| l == "time_s,f2_n").unwrap() + 1;
        let mut lines: Vec<&str> = text.lines().collect();
        lines[rows_start + 2] = "1.3e-5,5.2e4x";
        std::fs::write(&path, lines.join("\n")).unwrap();
        let err = read(&path, &truth(), (AT, ShapeFunction::Cpdi)).unwrap_err();
        assert!(
            err.to_string()
                .contains(&format!("line {}", rows_start + 3)),
            "{err}"
        );
        lines.remove(rows_start + 2);
        std::fs::write(&path, lines.join("\n")).unwrap();
        let err = read(&path, &truth(), (AT, ShapeFunction::Cpdi)).unwrap_err();
        assert!(err.to_string().contains("rows, expected"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
