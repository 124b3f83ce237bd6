//! The tool forces' sensitivities to the material parameters (`mpw cut orthogonal
//! --derivatives A,B,N,C,M`): p ∂f/∂p [N/m] from the run's exact derivatives
//! (`derivatives.csv`), through the forces' filter (a linear filter: the filtered
//! sensitivity is the sensitivity of the filtered force), charted over the cut, and their
//! steady means against the steady force: p ∂f_x/∂p / f_x is the per cent change of the
//! cutting force per per cent change of p.

use crate::charts::{LineChart, Series};
use crate::cut_forces::FORCE_FILTER;
use anyhow::{bail, Context, Result};
use cutting::orthogonal_result::{OrthogonalResult, TOOL};
use cutting::record::ToolForce;
use std::path::Path;

/// Write `force_sensitivity.csv` and `force_sensitivity.png` into the run folder `out`
/// and print the steady sensitivities, for the `parameters` the run carried.
pub fn force_sensitivity(
    out: &Path,
    parameters: &[String],
    result: &OrthogonalResult,
    title: &str,
) -> Result<()> {
    let file = out.join("derivatives.csv");
    let time = &result.force.time_s;
    let us: Vec<f64> = time.iter().map(|t| t * 1e6).collect();
    let mut chart = LineChart::new(
        format!("{title}: sensitivity of the cutting force (exact, filtered)"),
        "time [µs]",
        "p ∂f_x/∂p [MN/m]",
    );
    let mut columns = vec![("time_s".to_string(), time.clone())];
    let steady = result.steady_force();
    for p in parameters {
        let s = ToolForce::read_sensitivity(&file, TOOL, p)?;
        // the history writes its times to 10 digits, derivatives.csv to all
        let same = |(a, b): (&f64, &f64)| (a - b).abs() <= 1e-8 * a.abs().max(b.abs());
        if s.time_s.len() != time.len() || !s.time_s.iter().zip(time).all(same) {
            bail!(
                "{}: its rows are not at the history's times ({} rows against {})",
                file.display(),
                s.time_s.len(),
                time.len()
            );
        }
        let (fx, fy) = (
            FORCE_FILTER.apply(&s.force_x),
            FORCE_FILTER.apply(&s.force_y),
        );
        chart = chart.with(Series::scaled(p, &us, &fx, 1.0, 1e-6));
        if let (Some([f_x, f_y]), Some(dx), Some(dy)) =
            (steady, result.steady_mean(&fx), result.steady_mean(&fy))
        {
            println!(
                "  {p}: steady p ∂f_x/∂p {:.3} MN/m ({:.2} % of f_x per % of {p}), p ∂f_y/∂p {:.3} MN/m (f_y {:.3} MN/m)",
                dx * 1e-6,
                100.0 * dx / f_x,
                dy * 1e-6,
                f_y * 1e-6
            );
        }
        columns.push((format!("tool_force_x_{p}_filtered_n_per_m"), fx));
        columns.push((format!("tool_force_y_{p}_filtered_n_per_m"), fy));
    }
    chart.write_png(&out.join("force_sensitivity.png"))?;
    write_columns(&out.join("force_sensitivity.csv"), &columns)
}

/// Named columns of equal length as CSV.
fn write_columns(path: &Path, columns: &[(String, Vec<f64>)]) -> Result<()> {
    let names: Vec<&str> = columns.iter().map(|(n, _)| n.as_str()).collect();
    let mut text = names.join(",") + "\n";
    for k in 0..columns[0].1.len() {
        let row: Vec<String> = columns.iter().map(|(_, v)| format!("{:e}", v[k])).collect();
        text += &(row.join(",") + "\n");
    }
    std::fs::write(path, text).with_context(|| format!("{}: cannot write", path.display()))
}
