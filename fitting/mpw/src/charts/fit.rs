//! Charts of a fit (PNG): each experiment against the fitted model (an SHPB record also as
//! true stress against true strain, measured and model, per face), residuals,
//! convergence history (log10 S against model evaluations), the correlation matrix of
//! every stage, and the optimizer comparison (log10 S against evaluations and wall time).
//! Line charts use `crate::charts`; the correlation matrix is a plotters heat map.

use crate::charts::{LineChart, Series};
use anyhow::Result;
use fitting::fit::objective::Block;
use fitting::fit::optimize::run::FitResult;
use fitting::fit::reports::report::sanitize;
use fitting::fit::sets::fit_set::FitSet;
use fitting::fit::statistics::bootstrap::Bootstrap;
use fitting::fit::statistics::scatter::scatter;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::fmt::Write as _;
use std::path::Path;

/// An SHPB record as engineers read it: true stress against true strain from each face
/// force, measured and model, both at the measured strain of the sample.
fn stress_strain_chart(b: &Block, p: &[f64]) -> Option<LineChart> {
    let ss = b.stress_strain.as_ref()?;
    let per = ss.strain.len();
    let mut chart = LineChart::new(
        format!("{}: true stress against true strain", b.name),
        "true strain, compression positive [-]",
        "true stress F exp(−ε)/A0 [MPa]",
    );
    for (c, ch) in b.channels.iter().enumerate() {
        let stress = |force: &[f64]| -> Vec<f64> {
            force[c * per..(c + 1) * per]
                .iter()
                .zip(&ss.stress_per_force)
                .map(|(f, k)| f * k)
                .collect()
        };
        chart = chart
            .with(Series::scaled(
                format!("{ch} measured"),
                &ss.strain,
                &stress(&b.measured),
                1.0,
                1e-6,
            ))
            .with(Series::scaled(
                format!("{ch} model"),
                &ss.strain,
                &stress(p),
                1.0,
                1e-6,
            ));
    }
    Some(chart)
}

/// All charts of one fit into `dir`.
pub fn fit_charts(dir: &Path, set: &FitSet, result: &FitResult) -> Result<()> {
    std::fs::create_dir_all(dir)?;
    for (b, p) in set.blocks.iter().zip(&result.predictions) {
        let per = b.measured.len() / b.channels.len();
        let mut fit = LineChart::new(
            format!("{}: measured and fitted", b.name),
            &b.x_label,
            &b.y_label,
        );
        let mut res = LineChart::new(
            format!("{}: residual fitted - measured", b.name),
            &b.x_label,
            format!("residual {}", b.y_label),
        );
        // one model line where the channels' predictions coincide (a uniform specimen has
        // F1 = F2), one per channel where they differ (an MPM level)
        let differ = (1..b.channels.len()).any(|c| p[c * per..(c + 1) * per] != p[..per]);
        for (c, ch) in b.channels.iter().enumerate() {
            let range = c * per..(c + 1) * per;
            let x = &b.x[range.clone()];
            // A single unnamed channel (tensile) reads "measured", not "measured measured".
            let (measured, residual) = match ch.as_str() {
                "measured" => ("measured".to_string(), "residual".to_string()),
                _ => (format!("{ch} measured"), format!("{ch} residual")),
            };
            fit = fit.with(Series::scaled(
                measured,
                x,
                &b.measured[range.clone()],
                1.0,
                b.y_chart_scale,
            ));
            let r: Vec<f64> = range.clone().map(|k| p[k] - b.measured[k]).collect();
            res = res.with(Series::scaled(residual, x, &r, 1.0, b.y_chart_scale));
            if c == 0 || differ {
                let label = if differ {
                    format!("{ch} model")
                } else {
                    "model".to_string()
                };
                fit = fit.with(Series::scaled(label, x, &p[range], 1.0, b.y_chart_scale));
            }
        }
        let stem = sanitize(&b.name);
        fit.write_png(&dir.join(format!("{stem}_fit.png")))?;
        res.write_png(&dir.join(format!("{stem}_residual.png")))?;
        if let Some(chart) = stress_strain_chart(b, p) {
            chart.write_png(&dir.join(format!("{stem}_stress_strain.png")))?;
        }
    }
    scatter_charts(dir, set, &result.predictions, None)?;
    if result.stages.is_empty() {
        return Ok(());
    }
    let mut conv = LineChart::new(
        "convergence",
        "model evaluations (real + AD passes) [-]",
        "log10 objective S [-]",
    )
    .integer_x();
    for (si, s) in result.stages.iter().enumerate() {
        for (ri, run) in s.runs.iter().enumerate() {
            let pts: Vec<(f64, f64)> = run
                .history
                .iter()
                .map(|h| ((h.evaluations + h.jacobians) as f64, h.cost.log10()))
                .collect();
            conv = conv.with(Series {
                label: format!("stage {} start {}", si + 1, ri + 1),
                points: pts,
            });
        }
    }
    conv.write_png(&dir.join("convergence.png"))?;
    for (si, s) in result.stages.iter().enumerate() {
        // An interrupted stage has no correlations.
        if s.free.len() > 1 && !s.correlation.is_empty() {
            correlation_png(
                &dir.join(format!("correlation_stage{}.png", si + 1)),
                &s.free,
                &s.correlation,
            )?;
        }
    }
    Ok(())
}

/// Per group of several records (`group_<label>_scatter.png`): the mean measured curve,
/// its ±1 sd band over the records and the mean of the model's predictions (`fit::statistics::scatter`),
/// with the bootstrap's 95 % band of the latter when there is one.
pub fn scatter_charts(
    dir: &Path,
    set: &FitSet,
    predictions: &[Vec<f64>],
    bootstrap: Option<&Bootstrap>,
) -> Result<()> {
    let blocks: Vec<&Block> = set.blocks.iter().collect();
    for g in scatter(&blocks, predictions) {
        if g.strain.is_empty() {
            continue;
        }
        let b = blocks[g.group.members[0]];
        let y = |label: &str, v: &[f64]| Series::scaled(label, &g.strain, v, 1.0, b.y_chart_scale);
        let sd = |sign: f64| -> Vec<f64> {
            g.mean
                .iter()
                .zip(&g.sd)
                .map(|(m, s)| m + sign * s)
                .collect()
        };
        let n = g.group.members.len();
        let mut chart = LineChart::new(
            format!("{}: {n} records, mean and ±1 sd, model", g.group.label),
            &b.x_label,
            &b.y_label,
        )
        .with(y("measured mean", &g.mean))
        .with(y("measured mean + sd", &sd(1.0)))
        .with(y("measured mean - sd", &sd(-1.0)))
        .with(y("model (mean over the records)", &g.model_mean));
        let band =
            bootstrap.and_then(|bs| bs.bands.iter().find(|band| band.group == g.group.label));
        if let Some(band) = band {
            chart = chart
                .with(y("model, bootstrap 2.5 %", &band.lo95))
                .with(y("model, bootstrap 97.5 %", &band.hi95));
        }
        chart.write_png(&dir.join(format!("group_{}_scatter.png", sanitize(&g.group.label))))?;
    }
    Ok(())
}

/// Diverging colour of a correlation r ∈ [−1, 1]: blue (−1), white (0), red (+1).
fn correlation_colour(r: f64) -> RGBColor {
    let v = if r.is_finite() {
        r.clamp(-1.0, 1.0)
    } else {
        0.0
    };
    let fade = (255.0 * (1.0 - v.abs())) as u8;
    match v >= 0.0 {
        true => RGBColor(255, fade, fade),
        false => RGBColor(fade, fade, 255),
    }
}

/// The correlation matrix as a grid of cells in pixel coordinates: row k and column k are
/// parameter k (rows top to bottom, columns left to right, labels at the cell centres), the
/// value printed in every cell, and a colour bar from −1 to +1.
fn correlation_png(path: &Path, names: &[String], corr: &[Vec<f64>]) -> Result<()> {
    let n = names.len() as i32;
    let root = BitMapBackend::new(path, (760, 640)).into_drawing_area();
    root.fill(&WHITE)?;
    let (x0, y0, size) = (90, 70, 480 / n);
    let centred = |px: i32| {
        ("sans-serif", px)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Center))
    };
    root.draw(&Text::new(
        "parameter correlation (from JᵀJ)",
        (x0 + n * size / 2, 25),
        centred(24),
    ))?;
    for i in 0..n {
        let name = &names[i as usize];
        root.draw(&Text::new(
            name.clone(),
            (x0 - 30, y0 + i * size + size / 2),
            centred(20),
        ))?;
        root.draw(&Text::new(
            name.clone(),
            (x0 + i * size + size / 2, y0 + n * size + 22),
            centred(20),
        ))?;
        for j in 0..n {
            let r = corr[i as usize][j as usize];
            let (x, y) = (x0 + j * size, y0 + i * size);
            root.draw(&Rectangle::new(
                [(x, y), (x + size, y + size)],
                correlation_colour(r).filled(),
            ))?;
            root.draw(&Rectangle::new(
                [(x, y), (x + size, y + size)],
                BLACK.stroke_width(1),
            ))?;
            root.draw(&Text::new(
                format!("{r:.3}"),
                (x + size / 2, y + size / 2),
                centred(20),
            ))?;
        }
    }
    // Colour bar: +1 at the top, −1 at the bottom.
    let (bx, height) = (x0 + n * size + 50, n * size);
    for k in 0..height {
        let r = 1.0 - 2.0 * f64::from(k) / f64::from(height - 1);
        root.draw(&Rectangle::new(
            [(bx, y0 + k), (bx + 24, y0 + k + 1)],
            correlation_colour(r).filled(),
        ))?;
    }
    root.draw(&Rectangle::new(
        [(bx, y0), (bx + 24, y0 + height)],
        BLACK.stroke_width(1),
    ))?;
    for (r, y) in [(1.0, y0), (0.0, y0 + height / 2), (-1.0, y0 + height)] {
        root.draw(&Text::new(format!("{r:+.0}"), (bx + 48, y), centred(18)))?;
    }
    root.draw(&Text::new("r", (bx + 12, y0 - 18), centred(18)))?;
    root.present()?;
    Ok(())
}

/// Optimizer comparison charts and a summary table; `runs` are single-start fits of
/// the same set with different optimizers.
pub fn comparison(dir: &Path, runs: &[FitResult]) -> Result<String> {
    let mut by_evals = LineChart::new(
        "optimizer comparison",
        "model evaluations (real + AD passes) [-]",
        "log10 objective S [-]",
    )
    .integer_x();
    let mut by_time = LineChart::new(
        "optimizer comparison",
        "wall time [s]",
        "log10 objective S [-]",
    );
    let mut out = String::from("\nOptimizer comparison (single start):\n");
    let _ = writeln!(
        out,
        "  {:<50} {:>12} {:>8} {:>8} {:>9}",
        "optimizer", "final S", "evals", "AD jac", "wall s"
    );
    for r in runs {
        for s in &r.stages {
            let run = &s.runs[s.best];
            let pts = |f: &dyn Fn(&fitting::fit::optimize::trace::HistoryPoint) -> f64| -> Vec<(f64, f64)> {
                run.history.iter().map(|h| (f(h), h.cost.log10())).collect()
            };
            by_evals = by_evals.with(Series {
                label: run.optimizer.clone(),
                points: pts(&|h| (h.evaluations + h.jacobians) as f64),
            });
            by_time = by_time.with(Series {
                label: run.optimizer.clone(),
                points: pts(&|h| h.wall_s),
            });
            let _ = writeln!(
                out,
                "  {:<50} {:>12.6e} {:>8} {:>8} {:>9.2}",
                run.optimizer, run.cost, s.evaluations, s.jacobians, run.wall_s
            );
        }
    }
    by_evals.write_png(&dir.join("compare_evaluations.png"))?;
    by_time.write_png(&dir.join("compare_wall_time.png"))?;
    Ok(out)
}
