//! Line charts of several labelled (x, y) series as PNG, with axis labels that carry the
//! units. Axis ranges cover all finite points with a 5 % margin, or a given y range (what
//! runs off it is drawn along the frame); non-finite points are left out of the drawing
//! (the data files keep them); the legend covers no data (`legend`).

pub mod cell_map;
pub mod fit;
pub mod heatmap;
pub mod legend;

use anyhow::{bail, Result};
use plotters::prelude::*;
use std::path::Path;

/// One labelled curve.
#[derive(Debug, Clone)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A series from separate x and y slices of equal length, scaled by `x_scale` and
    /// `y_scale` (e.g. 1e6 to plot seconds as µs).
    pub fn scaled(
        label: impl Into<String>,
        x: &[f64],
        y: &[f64],
        x_scale: f64,
        y_scale: f64,
    ) -> Series {
        Series {
            label: label.into(),
            points: x
                .iter()
                .zip(y)
                .map(|(a, b)| (a * x_scale, b * y_scale))
                .collect(),
        }
    }
}

/// The finite points of a series.
fn finite_points(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect()
}

/// A chart: title, axis labels (with units), series.
#[derive(Debug, Clone)]
pub struct LineChart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// The x axis counts something (evaluations): ticks only at whole numbers.
    pub integer_x: bool,
    /// Mark each point (a few points per series, some series of one point).
    pub markers: bool,
    /// A fixed y range (data outside it run off the frame); `None`: all finite points.
    pub y_range: Option<(f64, f64)>,
}

const SIZE: (u32, u32) = (1000, 700);

impl LineChart {
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> LineChart {
        LineChart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            integer_x: false,
            markers: false,
            y_range: None,
        }
    }

    /// Show y in `lo..hi` only: values beyond are drawn along the frame (say so in the
    /// title).
    pub fn y_range(mut self, lo: f64, hi: f64) -> LineChart {
        self.y_range = Some((lo, hi));
        self
    }

    /// Ticks of the x axis only at whole numbers.
    pub fn integer_x(mut self) -> LineChart {
        self.integer_x = true;
        self
    }

    /// A circle at each point.
    pub fn markers(mut self) -> LineChart {
        self.markers = true;
        self
    }

    pub fn with(mut self, series: Series) -> LineChart {
        self.series.push(series);
        self
    }

    /// Draw the chart into a PNG file.
    pub fn write_png(&self, path: &Path) -> Result<()> {
        let finite = || {
            self.series
                .iter()
                .flat_map(|s| s.points.iter())
                .filter(|(x, y)| x.is_finite() && y.is_finite())
        };
        let Some((x0, x1, y0, y1)) =
            finite().fold(None, |acc: Option<(f64, f64, f64, f64)>, &(x, y)| {
                Some(match acc {
                    None => (x, x, y, y),
                    Some((a, b, c, d)) => (a.min(x), b.max(x), c.min(y), d.max(y)),
                })
            })
        else {
            bail!("chart `{}` has no finite points", self.title);
        };
        let pad = |lo: f64, hi: f64| {
            let m = if hi > lo {
                0.05 * (hi - lo)
            } else {
                0.5 * lo.abs().max(1.0)
            };
            (lo - m, hi + m)
        };
        let ((x0, x1), (y0, y1)) = (pad(x0, x1), self.y_range.unwrap_or(pad(y0, y1)));
        // with a fixed y range, what runs off it is drawn along the frame (the title says so)
        let curves: Vec<Vec<(f64, f64)>> = self
            .series
            .iter()
            .map(|s| {
                let points = finite_points(&s.points).into_iter();
                let mut kept: Vec<(f64, f64)> = match self.y_range {
                    Some(_) => points.map(|(x, y)| (x, y.clamp(y0, y1))).collect(),
                    None => points.collect(),
                };
                kept.dedup();
                kept
            })
            .collect();
        let labels: Vec<&str> = self.series.iter().map(|s| s.label.as_str()).collect();
        let plot = (
            f64::from(SIZE.0) - 80.0 - 30.0,
            f64::from(SIZE.1) - 50.0 - 60.0,
        );
        let (corner, (y0, y1)) = legend::place(
            &curves,
            (x0, x1),
            (y0, y1),
            legend::LegendBox::of(&labels, plot),
        );

        let root = BitMapBackend::new(path, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", 26))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let whole = |x: &f64| match (x - x.round()).abs() < 1e-9 {
            true => format!("{x:.0}"),
            false => String::new(),
        };
        let mut mesh = chart.configure_mesh();
        if self.integer_x {
            mesh.x_labels(((x1 - x0).floor() as usize + 1).clamp(2, 11))
                .x_label_formatter(&whole);
        }
        mesh.x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 16))
            .draw()?;
        for (k, (s, points)) in self.series.iter().zip(curves).enumerate() {
            let color = Palette99::pick(k).to_rgba();
            // a thick polyline's miter joins at sharp turns reach far off the frame: a
            // series denser than the pixels is drawn one pixel wide
            let width = if points.len() > SIZE.0 as usize { 1 } else { 2 };
            if self.markers {
                let circles = points.iter().map(|&p| Circle::new(p, 4, color.filled()));
                chart.draw_series(circles)?;
            }
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(width)))?
                .label(s.label.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .position(corner)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .draw()?;
        root.present()?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_a_png_of_the_stated_size() {
        let dir = std::env::temp_dir().join(format!("mpw-chart-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("line.png");
        let x: Vec<f64> = (0..50).map(|k| k as f64 * 1e-6).collect();
        let y: Vec<f64> = x.iter().map(|t| (t * 1e5).sin()).collect();
        LineChart::new("sine", "time [µs]", "value [-]")
            .with(Series::scaled("sin", &x, &y, 1e6, 1.0))
            .write_png(&path)
            .unwrap();
        let bytes = std::fs::read(&path).unwrap();
        // PNG signature, then the IHDR chunk with width and height (big endian).
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        let width = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
        let height = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
        assert_eq!((width, height), SIZE);
        let empty = LineChart::new("empty", "x", "y").write_png(&dir.join("empty.png"));
        assert!(empty.is_err());
    }
}
