//! Exact derivatives of the Taylor bar's final length L_f, outer footprint diameter D_f and
//! area-equivalent footprint D_A (module `taylor`) with respect to the Johnson-Cook
//! parameters A, B, N, C and M, carried through the whole explicit run in forward mode
//! (`mpm_core::solver::Tangent`), against central differences of whole runs,
//! (q(p + h) − q(p − h)) / 2h, over relative steps h/p from 1e-2 to 1e-8.
//!
//! The difference quotient has three errors: truncation (∝ h², large steps), round-off
//! amplified through the run (∝ 1/h, small steps), and the branch events of the run (a
//! point crossing a cell face, a node passing the mass cutoff, a point's first yield)
//! that fall within ±h and make it average one-sided slopes. The exact derivative is the
//! derivative of the branch the run took; where the events are sparse it sits on the
//! plateau the quotient reaches between the first two errors.

use super::taylor::{axisymmetric_bar, markers, measure, measure_real, COARSE, COPPER};
use crate::verify::row::Row;
use materials::seeded::seeded;
use materials::{load_material, AnyModel, Model};
use mpm_core::failure::SimulationError;
use mpm_core::shape::ShapeFunction;
use mpm_core::solver::{Solver, Tangent};
use rayon::prelude::*;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

/// The free parameters, in the order of the derivatives.
pub const FREE: [&str; 5] = ["A", "B", "N", "C", "M"];
/// The observed quantities, in the order of the values.
pub const QUANTITIES: [&str; 3] = ["L_f", "D_f", "D_A"];
/// The relative steps h/p of the central differences for the chart of their error.
pub const STEPS: [f64; 7] = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];
/// The steps of the `mpw verify` rows.
pub const ROW_STEPS: [f64; 4] = [1e-3, 1e-5, 1e-7, 1e-8];

/// ∂q/∂p for each quantity (row) and parameter (column) [m per parameter unit].
pub type Jacobian<const P: usize = 5> = [[f64; P]; 3];

/// A run with the derivative pass along `P` parameters.
#[derive(Debug, Clone)]
pub struct Derivatives<const P: usize = 5> {
    pub exact: Jacobian<P>,
    /// (t [s], p ∂q/∂p [m]) every microsecond: how much each parameter moves each
    /// quantity through the impact.
    pub history: Vec<(f64, Jacobian<P>)>,
    /// Wall time of the run [s].
    pub wall: f64,
}

/// The bar of `model` on the grid of spacing `dx` [m], 2 particles per cell and
/// direction, linear shape functions, and its marked particles.
fn bar(model: &AnyModel, dx: f64) -> (Solver<2>, (usize, Vec<usize>), f64) {
    let s = dx / 2.0;
    let solver = axisymmetric_bar(
        Arc::new(*model),
        ShapeFunction::Linear,
        COPPER.velocity,
        (dx, s),
    );
    let marked = markers(&solver, s);
    (solver, marked, s)
}

/// The run to `end` [s] with the derivatives of L_f, D_f and D_A with respect to the
/// parameters `free`.
pub fn with_derivatives<const P: usize>(
    model: &AnyModel,
    free: &[&str; P],
    dx: f64,
    end: f64,
) -> anyhow::Result<Derivatives<P>> {
    let started = Instant::now();
    let (mut solver, (top, bottom), s) = bar(model, dx);
    let seeded = seeded(model, free).map_err(anyhow::Error::msg)?;
    let mut tangent = Tangent::new(&solver, vec![seeded])?;
    solver.initialize();
    let observe = |solver: &Solver<2>, tangent: &Tangent<2, P>| {
        let (l, d, a) = measure(
            |i| {
                (
                    tangent.position(solver, i),
                    tangent.deformation(solver, i),
                    tangent.volume(solver, i),
                )
            },
            (top, &bottom),
            s,
            1.0,
        );
        [l, d, a]
    };
    let mut history = Vec::new();
    while solver.time < end - 0.5 * solver.dt {
        solver.step_with(&mut tangent)?;
        if solver.time >= history.len() as f64 * 1e-6 {
            let q = observe(&solver, &tangent);
            let scaled = q.map(|q| {
                std::array::from_fn(|k| q.eps[k] * model.param(free[k]).unwrap_or(f64::NAN))
            });
            history.push((solver.time, scaled));
        }
    }
    let q = observe(&solver, &tangent);
    Ok(Derivatives {
        exact: q.map(|q| q.eps.into()),
        history,
        wall: started.elapsed().as_secs_f64(),
    })
}

/// L_f, D_f and D_A of a plain run to `end` [s], and its wall time [s].
pub fn plain(model: &AnyModel, dx: f64, end: f64) -> Result<([f64; 3], f64), SimulationError> {
    let started = Instant::now();
    let (mut solver, (top, bottom), s) = bar(model, dx);
    solver.initialize();
    while solver.time < end - 0.5 * solver.dt {
        solver.step()?;
    }
    let (l, d, a) = measure_real(&solver, (top, &bottom), s, 1.0);
    Ok(([l, d, a], started.elapsed().as_secs_f64()))
}

/// `model` with parameter `name` set to `value`.
fn with(model: &AnyModel, name: &str, value: f64) -> AnyModel {
    model.map_params(|n, v| if n == name { value } else { v })
}

/// Central differences of L_f, D_f and D_A with respect to parameter `k` at the relative
/// step `rel`.
pub fn central(
    model: &AnyModel,
    (dx, end): (f64, f64),
    k: usize,
    rel: f64,
) -> Result<[f64; 3], SimulationError> {
    let p = model.param(FREE[k]).unwrap_or(f64::NAN);
    let h = rel * p;
    let (up, _) = plain(&with(model, FREE[k], p + h), dx, end)?;
    let (down, _) = plain(&with(model, FREE[k], p - h), dx, end)?;
    Ok(std::array::from_fn(|q| (up[q] - down[q]) / (2.0 * h)))
}

/// The exact run, and the central differences for every parameter (outer) and step of
/// `steps` (inner), in parallel.
pub fn sweep(
    model: &AnyModel,
    (dx, end): (f64, f64),
    steps: &[f64],
) -> anyhow::Result<(Derivatives, Vec<Vec<[f64; 3]>>)> {
    let exact = with_derivatives(model, &FREE, dx, end)?;
    let runs: Vec<(usize, f64)> = (0..FREE.len())
        .flat_map(|k| steps.iter().map(move |&rel| (k, rel)))
        .collect();
    let fd: Result<Vec<[f64; 3]>, SimulationError> = runs
        .par_iter()
        .map(|&(k, rel)| central(model, (dx, end), k, rel))
        .collect();
    let fd = fd?;
    let table = fd.chunks(steps.len()).map(<[_]>::to_vec).collect();
    Ok((exact, table))
}

/// The largest |p ∂q/∂p| over the parameters: the scale of quantity `q`'s sensitivities [m].
pub fn scale(model: &AnyModel, exact: &Jacobian, q: usize) -> f64 {
    (0..FREE.len())
        .map(|k| (exact[q][k] * model.param(FREE[k]).unwrap_or(f64::NAN)).abs())
        .fold(0.0, f64::max)
}

/// The exact derivatives and the central differences of every parameter and step, on
/// the coarse bar (dx = 0.635 mm) to 80 µs, with the wall time of one plain run.
pub struct Study {
    pub model: AnyModel,
    pub exact: Derivatives,
    /// The relative steps of the central differences.
    pub steps: Vec<f64>,
    /// `central[k][j]`: parameter k, step `steps[j]`.
    pub central: Vec<Vec<[f64; 3]>>,
    pub plain_wall: f64,
}

/// End of the runs [s] (the Taylor rows' time).
pub const END: f64 = 80e-6;

impl Study {
    /// The study with central differences at the relative steps `steps`.
    pub fn run(materials: &Path, steps: &[f64]) -> anyhow::Result<Study> {
        let model = load_material(materials.join(COPPER.material))?.model;
        let (_, plain_wall) = plain(&model, COARSE, END)?;
        let (exact, central) = sweep(&model, (COARSE, END), steps)?;
        Ok(Study {
            model,
            exact,
            steps: steps.to_vec(),
            central,
            plain_wall,
        })
    }

    /// Index of the relative step `rel` in `steps`.
    fn step_index(&self, rel: f64) -> usize {
        self.steps
            .iter()
            .position(|&h| h == rel)
            .expect("a step of the study")
    }

    /// |central − exact| · p / scale of quantity `q`, parameter `k`, step `steps[j]`.
    pub fn error(&self, q: usize, k: usize, j: usize) -> f64 {
        let p = self.model.param(FREE[k]).unwrap_or(f64::NAN);
        let d = self.exact.exact[q][k];
        (self.central[k][j][q] - d).abs() * p / scale(&self.model, &self.exact.exact, q)
    }
}

/// `mpw verify` rows: the exact derivative of each quantity and parameter against the
/// closer of the central differences at h/p = 1e-7 and 1e-8 (steps below the spacing of
/// the run's events, where the quotient measures the same branch); the quotient's error
/// at the usual steps (info); the cost. `full` adds how the exact derivatives change
/// over ±1e-4 in A.
pub fn cases(materials: &Path, full: bool, out: &mut Vec<Row>) {
    let name = "mpm/taylor-derivatives";
    let study = match Study::run(materials, &ROW_STEPS) {
        Ok(s) => s,
        Err(e) => {
            out.push(Row::holds(format!("{name}: {e}"), false));
            return;
        }
    };
    let small = [study.step_index(1e-7), study.step_index(1e-8)];
    for (q, quantity) in QUANTITIES.iter().enumerate() {
        for (k, parameter) in FREE.iter().enumerate() {
            let error = small.map(|j| study.error(q, k, j));
            // round-off through ~2000 steps at h/p = 1e-8 is ~1e-6 of the largest
            // sensitivity; a missing term is off by 1e-2 or more
            out.push(Row::at_most(
                format!("{name}/d{quantity}/d{parameter} exact vs central (h/p 1e-7|1e-8)"),
                error[0].min(error[1]),
                1e-5,
            ));
        }
        for rel in [1e-3, 1e-5] {
            let worst = (0..FREE.len())
                .map(|k| study.error(q, k, study.step_index(rel)))
                .fold(0.0, f64::max);
            out.push(Row::reported(
                format!("{name}/d{quantity} central at h/p {rel:.0e}: largest error / scale"),
                worst,
            ));
        }
    }
    out.push(Row::reported(
        format!("{name}/cost: value + 5 derivatives / one run"),
        study.exact.wall / study.plain_wall,
    ));
    if full {
        stability_rows(&study, out);
    }
}

/// How much the exact derivatives with respect to A change when A moves by ±1e-4
/// (relative to their scale): small where the run's response is piecewise smooth with
/// small jumps at its events.
fn stability_rows(study: &Study, out: &mut Vec<Row>) {
    let a = study.model.param("A").unwrap_or(f64::NAN);
    for delta in [-1e-4, 1e-4] {
        let moved = with(&study.model, "A", a * (1.0 + delta));
        match with_derivatives(&moved, &FREE, COARSE, END) {
            Ok(d) => {
                for (q, quantity) in QUANTITIES.iter().enumerate() {
                    let change = (d.exact[q][0] - study.exact.exact[q][0]).abs() * a
                        / scale(&study.model, &study.exact.exact, q);
                    out.push(Row::reported(
                        format!("mpm/taylor-derivatives/d{quantity}/dA at A(1{delta:+.0e}): change / scale"),
                        change,
                    ));
                }
            }
            Err(e) => out.push(Row::holds(
                format!("mpm/taylor-derivatives/A(1{delta:+.0e}): {e}"),
                false,
            )),
        }
    }
}
