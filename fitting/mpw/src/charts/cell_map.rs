//! A map of labelled cells as PNG: columns and rows named by their values, each cell
//! coloured by a fraction in [0, 1] (red: 0, green: 1) and carrying its own text (for
//! example the feed a run reached and its wall time), so that a reader sees at a glance
//! which combination survives and at what cost.

use anyhow::Result;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

pub struct CellMap {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// Column and row names, left to right and bottom to top.
    pub columns: Vec<String>,
    pub rows: Vec<String>,
    /// (column, row, fraction in [0, 1] or NaN for no value, text; lines split by '\n').
    pub cells: Vec<(usize, usize, f64, String)>,
}

/// Red (0) to green (1); grey for a cell without a value (NaN: not run).
fn colour(t: f64) -> RGBColor {
    if t.is_nan() {
        return RGBColor(210, 210, 210);
    }
    let t = t.clamp(0.0, 1.0);
    RGBColor((230.0 - 130.0 * t) as u8, (120.0 + 100.0 * t) as u8, 110)
}

impl CellMap {
    pub fn write_png(&self, path: &Path) -> Result<()> {
        let root = BitMapBackend::new(path, (900, 700)).into_drawing_area();
        root.fill(&WHITE)?;
        let (x0, y0, w, h) = (140i32, 80i32, 720i32, 520i32);
        let (nc, nr) = (
            self.columns.len().max(1) as i32,
            self.rows.len().max(1) as i32,
        );
        let (cw, ch) = (w / nc, h / nr);
        let centred = |size: u32| {
            ("sans-serif", size)
                .into_font()
                .color(&BLACK)
                .pos(Pos::new(HPos::Center, VPos::Center))
        };
        root.draw(&Text::new(self.title.clone(), (450, 30), centred(22)))?;
        for (c, name) in self.columns.iter().enumerate() {
            let x = x0 + c as i32 * cw + cw / 2;
            root.draw(&Text::new(name.clone(), (x, y0 + h + 20), centred(16)))?;
        }
        root.draw(&Text::new(
            self.x_label.clone(),
            (x0 + w / 2, y0 + h + 50),
            centred(18),
        ))?;
        for (r, name) in self.rows.iter().enumerate() {
            let y = y0 + h - r as i32 * ch - ch / 2;
            root.draw(&Text::new(name.clone(), (x0 - 30, y), centred(16)))?;
        }
        root.draw(&Text::new(
            self.y_label.clone(),
            (x0 - 30, y0 - 25),
            centred(16),
        ))?;
        for (c, r, fraction, text) in &self.cells {
            let (left, top) = (x0 + *c as i32 * cw, y0 + h - (*r as i32 + 1) * ch);
            root.draw(&Rectangle::new(
                [(left, top), (left + cw, top + ch)],
                colour(*fraction).filled(),
            ))?;
            root.draw(&Rectangle::new([(left, top), (left + cw, top + ch)], BLACK))?;
            let lines: Vec<&str> = text.lines().collect();
            for (k, line) in lines.iter().enumerate() {
                let dy = (k as i32 - (lines.len() as i32 - 1) / 2) * 24
                    - if lines.len() % 2 == 0 { 12 } else { 0 };
                root.draw(&Text::new(
                    line.to_string(),
                    (left + cw / 2, top + ch / 2 + dy),
                    centred(18),
                ))?;
            }
        }
        root.present()?;
        Ok(())
    }
}
