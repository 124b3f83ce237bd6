//! A scene run with exact parameter derivatives (`solver::Tangent`, scene key
//! `output.derivatives`): each step carries the derivatives along, and every
//! `history_every` steps the sensitivities p ∂q/∂p (the derivative times the parameter's
//! value: how much q changes per unit relative change of the parameter) go to
//! `derivatives.csv`: of each rigid body's contact force [N, plane strain N/m], columns
//! `{body}_force_{axis}_{parameter}_n` as in the history, then of each control point's
//! position [m], `{point}_{axis}_{parameter}_m`. Up to `MAX_PARAMETERS` parameters, each
//! a parameter of at least one body's model (the bodies without it do not depend on it).

use crate::output::{force_unit, AXES};
use crate::solver::{RunError, Solver, Tangent, Unsupported};
use materials::seeded::{
    for_directions, seeded_where_present, Dual, ForDirections, MAX_DIRECTIONS,
};
use materials::{AnyModel, Model};
use nalgebra::SVector;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// Most parameters a run carries derivatives along.
pub const MAX_PARAMETERS: usize = MAX_DIRECTIONS;

/// How a run takes its steps.
pub type Stepper<'a, const D: usize> = Box<dyn FnMut(&mut Solver<D>) -> Result<(), RunError> + 'a>;

/// Why a run cannot write derivatives.
#[derive(Debug, thiserror::Error)]
pub enum DerivativeError {
    #[error(transparent)]
    Unsupported(#[from] Unsupported),
    #[error("exact derivatives: {0}")]
    Parameters(String),
    #[error("writing derivatives.csv: {0}")]
    Io(#[from] io::Error),
}

/// A stepper that carries the derivatives of `solver` (before its first step) along the
/// parameters `free` of the bodies' `models` and writes them into `dir`/derivatives.csv
/// every `every` steps (and at the start).
pub fn stepper<'a, const D: usize>(
    solver: &Solver<D>,
    models: &[AnyModel],
    free: &[String],
    (dir, every): (&Path, usize),
) -> Result<Stepper<'a, D>, DerivativeError> {
    let names: Vec<&str> = free.iter().map(String::as_str).collect();
    let job = Job {
        solver,
        models,
        dir,
        every,
    };
    for_directions(&names, job)
        .map_err(|why| DerivativeError::Parameters(format!("output.derivatives: {why}")))?
}

/// What `stepper` hands to `for_directions`.
struct Job<'s, const D: usize> {
    solver: &'s Solver<D>,
    models: &'s [AnyModel],
    dir: &'s Path,
    every: usize,
}

impl<const D: usize> ForDirections for Job<'_, D> {
    type Output = Result<Stepper<'static, D>, DerivativeError>;

    fn run<const P: usize>(self, names: [&str; P]) -> Self::Output {
        let Job {
            solver,
            models,
            dir,
            every,
        } = self;
        // each parameter's value, from the first body whose model has it
        let mut scales = Vec::with_capacity(P);
        for name in names {
            match models.iter().find_map(|m| m.param(name)) {
                Some(value) => scales.push(value),
                None => {
                    return Err(DerivativeError::Parameters(format!(
                        "no body's model has a parameter `{name}` (the first has {})",
                        models
                            .first()
                            .map(|m| m.param_names().join(", "))
                            .unwrap_or_default()
                    )))
                }
            }
        }
        let seeded = models
            .iter()
            .map(|m| seeded_where_present(m, &names))
            .collect();
        let mut tangent = Tangent::new(solver, seeded)?;
        let mut writer = Writer::create(&dir.join("derivatives.csv"), solver, &names, scales)?;
        writer.write(solver, &tangent)?;
        Ok(Box::new(move |s: &mut Solver<D>| {
            s.step_with(&mut tangent)?;
            if s.step.is_multiple_of(every) {
                writer.write(s, &tangent)?;
            }
            Ok(())
        }))
    }
}

/// Streams the rows of `derivatives.csv`, flushed every row.
struct Writer {
    out: BufWriter<File>,
    /// The value of each parameter (of the first body's model) [its unit].
    scales: Vec<f64>,
}

impl Writer {
    fn create<const D: usize>(
        path: &Path,
        solver: &Solver<D>,
        names: &[&str],
        scales: Vec<f64>,
    ) -> io::Result<Self> {
        let mut out = BufWriter::new(File::create(path)?);
        let mut cols = vec!["time_s".to_string()];
        let unit = force_unit(solver.settings.kinematics);
        for r in &solver.rigid {
            for axis in &AXES[..D] {
                let body = &r.body.name;
                cols.extend(
                    names
                        .iter()
                        .map(|n| format!("{body}_force_{axis}_{n}_{unit}")),
                );
            }
        }
        for (point, _) in &solver.control_points {
            for axis in &AXES[..D] {
                cols.extend(names.iter().map(|n| format!("{point}_{axis}_{n}_m")));
            }
        }
        writeln!(out, "{}", cols.join(","))?;
        Ok(Writer { out, scales })
    }

    fn write<const D: usize, const P: usize>(
        &mut self,
        solver: &Solver<D>,
        tangent: &Tangent<D, P>,
    ) -> io::Result<()> {
        let mut row = vec![format!("{:e}", solver.time)];
        let mut push = |q: &SVector<Dual<P>, D>| {
            for c in q.iter() {
                let d = c.eps;
                row.extend((0..P).map(|k| format!("{:e}", d[k] * self.scales[k])));
            }
        };
        for body in 0..solver.rigid.len() {
            push(&tangent.contact_force(solver, body));
        }
        for &(_, i) in &solver.control_points {
            push(&tangent.position(solver, i));
        }
        writeln!(self.out, "{}", row.join(","))?;
        self.out.flush()
    }
}
