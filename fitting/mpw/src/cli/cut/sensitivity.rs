//! The tool forces' sensitivities to the material parameters (`mpw cut orthogonal
//! --derivatives A,B,N,C,M`): p ∂f/∂p [N/m] from the run's exact derivatives
//! (`derivatives.csv`), through the forces' filter (a linear filter: the filtered
//! sensitivity is the sensitivity of the filtered force), charted over the cut on a log
//! scale against the largest filtered f_x, and their steady means against the steady
//! force: p ∂f_x/∂p / f_x is the per cent change of the cutting force per per cent of p.
//!
//! The derivative is that of the discrete run along the branch it took. Once the chip
//! forms, the cut's tangent grows exponentially (a perturbation of the trajectory grows
//! through the shear zone's thermal softening and the contact events), and the
//! sensitivity soon exceeds the force many times over: from the first row where it passes
//! `GROWN` times the largest force, the means are not printed and a warning says from
//! when; the force's smooth dependence on p is then that of differences with steps of a
//! few per cent, not a derivative.

use crate::charts::{LineChart, Series};
use crate::cut_forces::FORCE_FILTER;
use anyhow::{bail, Context, Result};
use cutting::orthogonal_result::{OrthogonalResult, TOOL};
use cutting::record::ToolForce;
use std::path::Path;

/// The multiple of the largest filtered f_x beyond which a sensitivity has grown past
/// what the force's dependence on p can be.
const GROWN: f64 = 10.0;

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
    let largest = result
        .filtered_x
        .iter()
        .fold(0.0, |m: f64, f| m.max(f.abs()));
    let mut chart = LineChart::new(
        format!("{title}: sensitivity of the cutting force (exact, filtered)"),
        "time [µs]",
        "log10 |p ∂f_x/∂p| / max f_x",
    );
    let mut columns = vec![("time_s".to_string(), time.clone())];
    let mut grown: Option<f64> = None;
    let mut steady = Vec::new();
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
        let relative: Vec<f64> = fx.iter().map(|d| (d.abs() / largest).log10()).collect();
        chart = chart.with(Series::scaled(p, &us, &relative, 1.0, 1.0));
        if let Some(k) = fx.iter().position(|d| d.abs() > GROWN * largest) {
            grown = Some(grown.map_or(time[k], |t| t.min(time[k])));
        }
        steady.push((p, result.steady_mean(&fx), result.steady_mean(&fy)));
        columns.push((format!("tool_force_x_{p}_filtered_n_per_m"), fx));
        columns.push((format!("tool_force_y_{p}_filtered_n_per_m"), fy));
    }
    chart.write_png(&out.join("force_sensitivity.png"))?;
    write_columns(&out.join("force_sensitivity.csv"), &columns)?;
    match (grown, result.steady_force()) {
        (Some(t), _) => println!(
            "warning: the exact sensitivities pass {GROWN} times the largest force from t = {:.2} µs on: the run's tangent grows exponentially there, so they are not the force's smooth dependence on the parameters (use differences with steps of a few per cent); no steady means",
            t * 1e6
        ),
        (None, Some([f_x, f_y])) => {
            for (p, dx, dy) in steady {
                let (dx, dy) = (dx.unwrap_or(f64::NAN), dy.unwrap_or(f64::NAN));
                println!(
                    "  {p}: steady p ∂f_x/∂p {:.3} MN/m ({:.2} % of f_x per % of {p}), p ∂f_y/∂p {:.3} MN/m (f_y {:.3} MN/m)",
                    dx * 1e-6,
                    100.0 * dx / f_x,
                    dy * 1e-6,
                    f_y * 1e-6
                );
            }
        }
        (None, None) => println!("the run ended before the steady window: no steady means"),
    }
    Ok(())
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
