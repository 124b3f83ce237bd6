//! Run output: a CSV time history and particle snapshots as legacy binary VTK files
//! (POLYDATA vertices) that ParaView opens.
//!
//! History columns (each name carries its unit): t [s], kinetic, internal (stress work),
//! external work, boundary work and energy error [J]; momentum p_i [kg m/s]; with several
//! bodies, each body's kinetic energy kinetic_<body> [J]; per rigid body the contact force
//! on it F_i [N] and the number of points in contact; per control point its position
//! x_i [m]. Plane strain: per metre of thickness ([J/m], [kg/s], [N/m]).
//! Snapshot point data: velocity [m/s], Cauchy stress σ (3×3) [Pa], von Mises stress [Pa],
//! α [-], θ [K], J = det F [-], body index.

use crate::kinematics::Kinematics;
use crate::solver::observer::{Observer, Verdict, CONTINUE};
use crate::solver::Solver;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Axis names of columns and results.
pub const AXES: [&str; 3] = ["x", "y", "z"];

/// Units of the history columns: plane-strain quantities are per metre of thickness,
/// axisymmetric ones of the full ring.
struct Units {
    energy: &'static str,
    momentum: &'static str,
    force: &'static str,
}

impl Units {
    fn of(kinematics: Kinematics) -> Self {
        match kinematics {
            Kinematics::PlaneStrain => Units {
                energy: "J/m",
                momentum: "kg/s",
                force: "N/m",
            },
            Kinematics::Axisymmetric | Kinematics::Solid => Units {
                energy: "J",
                momentum: "kg m/s",
                force: "N",
            },
        }
    }
}

/// Streams one history row per observed step (wrap it in `observer::Every` to thin it);
/// flushed every row so a failed run keeps its history. Column names carry their units,
/// e.g. `kinetic [J]`, `platen_force_z [N]`.
pub struct HistoryWriter {
    out: BufWriter<File>,
}

impl HistoryWriter {
    pub fn create<const D: usize>(path: &Path, solver: &Solver<D>) -> io::Result<Self> {
        let mut out = BufWriter::new(File::create(path)?);
        let u = Units::of(solver.settings.kinematics);
        let mut cols: Vec<String> = vec!["t [s]".into()];
        cols.extend(
            [
                "kinetic",
                "internal",
                "external_work",
                "boundary_work",
                "energy_error",
            ]
            .map(|c| format!("{c} [{}]", u.energy)),
        );
        cols.extend((0..D).map(|i| format!("momentum_{} [{}]", AXES[i], u.momentum)));
        if solver.blocks.len() > 1 {
            cols.extend(
                solver
                    .blocks
                    .iter()
                    .map(|b| format!("kinetic_{} [{}]", b.name, u.energy)),
            );
        }
        for r in &solver.rigid {
            cols.extend((0..D).map(|i| format!("{}_force_{} [{}]", r.body.name, AXES[i], u.force)));
            cols.push(format!("{}_contacts [-]", r.body.name));
        }
        for (name, _) in &solver.control_points {
            cols.extend((0..D).map(|i| format!("{name}_{} [m]", AXES[i])));
        }
        writeln!(out, "{}", cols.join(","))?;
        Ok(HistoryWriter { out })
    }

    /// A row for the current state.
    pub fn write<const D: usize>(&mut self, s: &Solver<D>) -> io::Result<()> {
        let e = &s.energies;
        let mut row = vec![
            s.time,
            e.kinetic,
            e.internal,
            e.external,
            e.boundary,
            e.error(),
        ];
        row.extend(s.momentum().iter());
        if s.blocks.len() > 1 {
            row.extend((0..s.blocks.len()).map(|b| s.body_kinetic_energy(b)));
        }
        for r in &s.rigid {
            row.extend(r.contact.force.iter());
            row.push(r.contact.active as f64);
        }
        for (_, p) in &s.control_points {
            row.extend(s.particles.position[*p].iter());
        }
        let text: Vec<String> = row.iter().map(|v| format!("{v:.9e}")).collect();
        writeln!(self.out, "{}", text.join(","))?;
        self.out.flush()
    }
}

impl<const D: usize> Observer<D> for HistoryWriter {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        self.write(s)?;
        CONTINUE
    }
}

/// VTK snapshots at `count` evenly spaced times up to `end` [s] (index 0 is the initial
/// state).
pub struct SnapshotWriter {
    dir: PathBuf,
    interval: f64,
    next: usize,
}

impl SnapshotWriter {
    pub fn new(dir: &Path, end: f64, count: usize) -> Self {
        SnapshotWriter {
            dir: dir.into(),
            interval: end / count.max(1) as f64,
            next: 0,
        }
    }

    /// Write the current state as the next snapshot whatever the time.
    pub fn write_next<const D: usize>(&mut self, s: &Solver<D>) -> io::Result<()> {
        write_snapshot(&self.dir, self.next, s)?;
        self.next += 1;
        Ok(())
    }
}

impl<const D: usize> Observer<D> for SnapshotWriter {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        if s.time >= self.next as f64 * self.interval - 0.5 * s.dt {
            self.write_next(s)?;
        }
        CONTINUE
    }
}

/// The first three components of `x`, padded with zeros.
fn pad(x: &[f64]) -> [f64; 3] {
    std::array::from_fn(|i| x.get(i).copied().unwrap_or(0.0))
}

fn be(out: &mut impl Write, values: impl IntoIterator<Item = f64>) -> io::Result<()> {
    for v in values {
        out.write_all(&(v as f32).to_be_bytes())?;
    }
    Ok(())
}

/// Write the particles of `solver` to `dir/snapshot_NNNNN.vtk`; returns the path.
pub fn write_snapshot<const D: usize>(
    dir: &Path,
    index: usize,
    solver: &Solver<D>,
) -> io::Result<PathBuf> {
    let path = dir.join(format!("snapshot_{index:05}.vtk"));
    let mut out = BufWriter::new(File::create(&path)?);
    let p = &solver.particles;
    let n = p.len();
    writeln!(
        out,
        "# vtk DataFile Version 3.0\nmpw particles t = {:e} s\nBINARY\nDATASET POLYDATA",
        solver.time
    )?;
    writeln!(out, "POINTS {n} float")?;
    for x in &p.position {
        be(&mut out, pad(x.as_slice()))?;
    }
    writeln!(out, "\nVERTICES {n} {}", 2 * n)?;
    for i in 0..n {
        out.write_all(&1i32.to_be_bytes())?;
        out.write_all(&(i as i32).to_be_bytes())?;
    }
    writeln!(out, "\nPOINT_DATA {n}\nVECTORS velocity float")?;
    for v in &p.velocity {
        be(&mut out, pad(v.as_slice()))?;
    }
    writeln!(out, "\nTENSORS stress float")?;
    for s in &p.stress {
        be(&mut out, s.transpose().iter().cloned())?;
    }
    let mut scalar = |name: &str, values: &mut dyn Iterator<Item = f64>| -> io::Result<()> {
        writeln!(out, "\nSCALARS {name} float 1\nLOOKUP_TABLE default")?;
        be(&mut out, values)
    };
    scalar("von_mises", &mut p.stress.iter().map(von_mises))?;
    let history = |f: fn(&materials::State<f64>) -> f64| {
        solver
            .blocks
            .iter()
            .flat_map(move |b| b.state.iter().map(f))
    };
    scalar("alpha", &mut history(|s| s.alpha))?;
    scalar("theta", &mut history(|s| s.theta))?;
    scalar("J", &mut p.deformation.iter().map(|f| f.determinant()))?;
    let body = |(k, b): (usize, &crate::MaterialBlock)| b.range.clone().map(move |_| k as f64);
    scalar("body", &mut solver.blocks.iter().enumerate().flat_map(body))?;
    out.flush()?;
    Ok(path)
}

/// von Mises equivalent stress √(3/2 dev σ : dev σ) [Pa].
pub fn von_mises(s: &nalgebra::Matrix3<f64>) -> f64 {
    let dev = s - nalgebra::Matrix3::identity() * (s.trace() / 3.0);
    (1.5 * dev.dot(&dev)).sqrt()
}
