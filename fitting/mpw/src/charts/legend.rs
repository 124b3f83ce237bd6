//! Where a chart's legend goes so that it covers no data: the corner of the plot whose
//! legend-sized box holds the fewest points of the curves (each segment sampled, so a
//! sparse curve crossing the box counts); if every corner holds some, the y range grows at
//! the top by the legend's height and the legend sits in that empty band.

use plotters::chart::SeriesLabelPosition;

/// The legend's box as fractions of the plot's width and height.
#[derive(Debug, Clone, Copy)]
pub struct LegendBox {
    pub width: f64,
    pub height: f64,
}

impl LegendBox {
    /// The box of `labels` in a plot of `plot` pixels (`plotters`' legend: a 20 px line, a
    /// gap, 16 px text about 9 px per character, rows about 22 px, and its margins).
    pub fn of(labels: &[&str], plot: (f64, f64)) -> LegendBox {
        let chars = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
        let width = 50.0 + 9.0 * chars as f64;
        let height = 22.0 * labels.len() as f64 + 20.0;
        LegendBox {
            width: (width / plot.0).min(1.0),
            height: (height / plot.1).min(1.0),
        }
    }
}

/// Where the legend goes, and the y range of the plot (grown at the top when no corner
/// is free). `curves`: the drawn points in data coordinates; `x`, `y`: the plot's ranges.
pub fn place(
    curves: &[Vec<(f64, f64)>],
    x: (f64, f64),
    y: (f64, f64),
    legend: LegendBox,
) -> (SeriesLabelPosition, (f64, f64)) {
    // Every point and nine points inside each segment, in fractions of the plot [0, 1]².
    let unit = |(px, py): (f64, f64)| ((px - x.0) / (x.1 - x.0), (py - y.0) / (y.1 - y.0));
    let mut samples = Vec::new();
    for c in curves {
        for w in c.windows(2) {
            let (a, b) = (unit(w[0]), unit(w[1]));
            samples.extend((0..10).map(|k| {
                let s = k as f64 / 10.0;
                (a.0 + s * (b.0 - a.0), a.1 + s * (b.1 - a.1))
            }));
        }
        samples.extend(c.last().map(|&p| unit(p)));
    }
    let (w, h) = (legend.width, legend.height);
    let corners = [
        (SeriesLabelPosition::UpperLeft, (0.0, w), (1.0 - h, 1.0)),
        (
            SeriesLabelPosition::UpperRight,
            (1.0 - w, 1.0),
            (1.0 - h, 1.0),
        ),
        (SeriesLabelPosition::LowerRight, (1.0 - w, 1.0), (0.0, h)),
        (SeriesLabelPosition::LowerLeft, (0.0, w), (0.0, h)),
    ];
    let covered = |(x0, x1): (f64, f64), (y0, y1): (f64, f64)| {
        samples
            .iter()
            .filter(|(u, v)| (x0..=x1).contains(u) && (y0..=y1).contains(v))
            .count()
    };
    let counts: Vec<usize> = corners
        .iter()
        .map(|(_, cx, cy)| covered(*cx, *cy))
        .collect();
    let best = (0..4).min_by_key(|&k| counts[k]).unwrap();
    if counts[best] == 0 {
        return (corners[best].0.clone(), y);
    }
    // No free corner: raise the top so that the data end below the legend's band. The
    // upper corner whose columns hold fewer points keeps the legend clear of labels.
    let grown = (y.0, y.0 + (y.1 - y.0) / (1.0 - h));
    let side = match counts[0] <= counts[1] {
        true => SeriesLabelPosition::UpperLeft,
        false => SeriesLabelPosition::UpperRight,
    };
    (side, grown)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corner(p: &SeriesLabelPosition) -> &'static str {
        match p {
            SeriesLabelPosition::UpperLeft => "upper left",
            SeriesLabelPosition::UpperRight => "upper right",
            SeriesLabelPosition::LowerLeft => "lower left",
            SeriesLabelPosition::LowerRight => "lower right",
            _ => "other",
        }
    }

    const BOX: LegendBox = LegendBox {
        width: 0.3,
        height: 0.2,
    };

    /// A hardening curve (rising, flattening) fills the upper right and the lower left;
    /// the legend goes to a free corner and the range is kept.
    #[test]
    fn a_rising_curve_leaves_a_free_corner() {
        let curve: Vec<(f64, f64)> = (0..=100)
            .map(|k| {
                let e = k as f64 * 0.002;
                (e, 300.0 + 800.0 * e.powf(0.3))
            })
            .collect();
        let (at, y) = place(&[curve], (0.0, 0.2), (300.0, 800.0), BOX);
        assert!(
            ["upper left", "lower right"].contains(&corner(&at)),
            "{}",
            corner(&at)
        );
        assert_eq!(y, (300.0, 800.0));
    }

    /// A decaying oscillation about zero touches every corner; the plot grows at the top by
    /// the legend's height (the data then end at 1 − h of the plot) and the legend goes up.
    #[test]
    fn data_in_every_corner_make_room_at_the_top() {
        let curve: Vec<(f64, f64)> = (0..=400)
            .map(|k| {
                let t = k as f64 / 400.0;
                (t, (60.0 * t).sin() * (1.0 - 0.2 * t))
            })
            .collect();
        let (at, y) = place(&[curve], (0.0, 1.0), (-1.0, 1.0), BOX);
        assert!(corner(&at).starts_with("upper"));
        assert!((y.1 - (-1.0 + 2.0 / 0.8)).abs() < 1e-12, "{y:?}");
        // the old top (1.0) is now at 1 − h of the grown range
        assert!(((1.0 - y.0) / (y.1 - y.0) - 0.8).abs() < 1e-12);
    }

    /// A sparse curve whose segment crosses a corner's box counts there although none of
    /// its two points lies in it.
    #[test]
    fn a_segment_crossing_a_corner_counts() {
        let diagonal = vec![(0.0, 1.0), (1.0, 0.0)];
        let through_upper_left = vec![(0.0, 0.9), (0.5, 1.0)];
        let (at, _) = place(&[diagonal, through_upper_left], (0.0, 1.0), (0.0, 1.0), BOX);
        assert!(
            ["upper right", "lower left"].contains(&corner(&at)),
            "{}",
            corner(&at)
        );
    }
}
