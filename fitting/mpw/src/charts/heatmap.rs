//! Heat maps of a scalar on a regular (x, y) grid as PNG, with a logarithmic colour
//! scale (errors spanning decades), a labelled colour bar (values below its range drawn
//! in its lowest colour, as the bar says) and cells left grey where the value is missing,
//! with a key saying why.

use anyhow::Result;
use plotters::prelude::*;
use std::path::Path;

pub struct HeatMap {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// Cell centres along x and y (increasing).
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// `value[i][j]` at (x[i], y[j]); `None` draws a grey cell.
    pub value: Vec<Vec<Option<f64>>>,
    /// Colour range (log10) of the values.
    pub log10_range: (f64, f64),
    /// What the colour bar shows (`relative stress error`); drawn as `log10 of ...`.
    pub value_label: String,
    /// Why a value is missing, for the key of grey cells (`update failed`).
    pub missing_label: String,
}

/// Font of tick labels and axis descriptions [px].
const FONT: u32 = 16;

fn edges(c: &[f64]) -> Vec<f64> {
    let n = c.len();
    let mut e = Vec::with_capacity(n + 1);
    e.push(c[0] - 0.5 * (c.get(1).copied().unwrap_or(c[0] + 1.0) - c[0]));
    for k in 1..n {
        e.push(0.5 * (c[k - 1] + c[k]));
    }
    e.push(
        c[n - 1] + 0.5 * (c[n - 1] - c.get(n.wrapping_sub(2)).copied().unwrap_or(c[n - 1] - 1.0)),
    );
    e
}

const GREY: RGBColor = RGBColor(170, 170, 170);

fn colour(t: f64) -> RGBColor {
    // Dark blue → green → yellow (perceptually ordered, colour-blind friendly enough).
    let t = t.clamp(0.0, 1.0);
    let r = (255.0 * (1.6 * t - 0.6).clamp(0.0, 1.0)) as u8;
    let g = (255.0 * (0.15 + 0.85 * t)) as u8;
    let b = (255.0 * (0.55 - 0.55 * t).clamp(0.0, 1.0) + 60.0 * (1.0 - t)) as u8;
    RGBColor(r, g, b)
}

impl HeatMap {
    pub fn write_png(&self, path: &Path) -> Result<()> {
        let root = BitMapBackend::new(path, (1000, 830)).into_drawing_area();
        root.fill(&WHITE)?;
        let (main, key_row) = root.split_vertically(800);
        let (plot, bar) = main.split_horizontally(850);
        let (xe, ye) = (edges(&self.x), edges(&self.y));
        let mut chart = ChartBuilder::on(&plot)
            .caption(&self.title, ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(xe[0]..xe[xe.len() - 1], ye[0]..ye[ye.len() - 1])?;
        let whole = |v: &f64| format!("{v:.0}");
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&whole)
            .y_label_formatter(&whole)
            .label_style(("sans-serif", FONT))
            .axis_desc_style(("sans-serif", FONT))
            .draw()?;
        let (lo, hi) = self.log10_range;
        let mut missing = false;
        for (i, row) in self.value.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                let fill = match v {
                    Some(v) if *v > 0.0 => colour((v.log10() - lo) / (hi - lo)),
                    Some(_) => colour(0.0),
                    None => {
                        missing = true;
                        GREY
                    }
                };
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(xe[i], ye[j]), (xe[i + 1], ye[j + 1])],
                    fill.filled(),
                )))?;
            }
        }
        let mut scale = ChartBuilder::on(&bar)
            .margin_top(60)
            .margin_bottom(65)
            .margin_right(30)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..1.0, lo..hi)?;
        let decade = |v: &f64| match (*v - lo).abs() < 1e-9 {
            true => format!("≤ {v:.1}"),
            false => format!("{v:.1}"),
        };
        scale
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_labels(((hi - lo) * 2.0).round() as usize + 1)
            .y_label_formatter(&decade)
            .y_desc(format!("log10 of the {}", self.value_label))
            .label_style(("sans-serif", FONT))
            .axis_desc_style(("sans-serif", FONT))
            .draw()?;
        let n = 100;
        for k in 0..n {
            let (a, b) = (
                lo + (hi - lo) * k as f64 / n as f64,
                lo + (hi - lo) * (k + 1) as f64 / n as f64,
            );
            scale.draw_series(std::iter::once(Rectangle::new(
                [(0.0, a), (1.0, b)],
                colour(k as f64 / n as f64).filled(),
            )))?;
        }
        if missing {
            let key = format!("grey: {}", self.missing_label);
            key_row.draw(&Rectangle::new([(90, 4), (106, 20)], GREY.filled()))?;
            key_row.draw(&Text::new(key, (112, 4), ("sans-serif", FONT)))?;
        }
        root.present()?;
        Ok(())
    }
}
