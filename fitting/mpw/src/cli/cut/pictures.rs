//! The cut commands' charts: force ranges that leave impact peaks off the scale, and
//! pictures of the last snapshot.

use anyhow::{Context, Result};
use cutting::record::snapshot_files;
use std::path::Path;

/// A y range [SI] for a force chart that shows the steady level: from the smallest value
/// to 1.5 times the 99th percentile of the values (the first contact's impact peaks last a
/// few samples and would flatten everything else), and the peak it leaves off, if any.
pub(super) fn force_range(series: &[&[f64]]) -> ((f64, f64), Option<f64>) {
    let mut all: Vec<f64> = series
        .iter()
        .flat_map(|s| s.iter().copied())
        .filter(|v| v.is_finite())
        .collect();
    all.sort_by(f64::total_cmp);
    let (Some(&lo), Some(&peak)) = (all.first(), all.last()) else {
        return ((0.0, 1.0), None);
    };
    let p99 = all[(0.99 * (all.len() - 1) as f64) as usize];
    let hi = 1.5 * p99.max(0.0) + 1e-30;
    let lo = lo.min(0.0) - 0.05 * (hi - lo.min(0.0));
    ((lo, hi), (peak > hi).then_some(peak))
}

/// A force chart's title, with the peak left off its scale.
pub(super) fn with_peak(title: String, off_scale: Option<f64>) -> String {
    match off_scale {
        Some(p) => format!("{title} (peaks to {:.1} MN/m off the scale)", p * 1e-6),
        None => title,
    }
}

pub(super) fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

/// The last snapshot's points coloured by equivalent plastic strain (a picture of the chip
/// or the cut sheet) into `out/<png>`.
pub(super) fn field_picture(out: &Path, png: &str, title: &str) -> Result<()> {
    use plotters::prelude::*;
    let Some(last) = snapshot_files(out)?.pop() else {
        return Ok(());
    };
    let s = mpm_core::output::read_snapshot(&last)?;
    let alpha = s.scalar("alpha").context("snapshot without alpha")?;
    let (lo, hi) = s.position.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    );
    let path = out.join(png);
    let root = BitMapBackend::new(&path, (1000, 700)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("{title}: α at t = {:.1} µs", s.time * 1e6),
            ("sans-serif", 24),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(lo[0] * 1e3..hi[0] * 1e3, lo[1] * 1e3..hi[1] * 1e3)?;
    chart
        .configure_mesh()
        .x_desc("x [mm]")
        .y_desc("y [mm]")
        .draw()?;
    // colour scale to the 95th percentile: a few molten points reach α of 7
    let mut sorted: Vec<f64> = alpha.to_vec();
    sorted.sort_by(f64::total_cmp);
    let top = sorted[(0.95 * (sorted.len() - 1) as f64) as usize].max(1e-12);
    chart.draw_series(s.position.iter().zip(alpha).map(|(p, &a)| {
        let t = (a / top).clamp(0.0, 1.0);
        let colour = RGBColor(
            (255.0 * t) as u8,
            (80.0 + 100.0 * (1.0 - t)) as u8,
            (255.0 * (1.0 - t)) as u8,
        );
        Circle::new((p[0] * 1e3, p[1] * 1e3), 1, colour.filled())
    }))?;
    root.present()?;
    Ok(())
}
