//! Run output: a CSV time history, and particle snapshots as VTK XML PolyData files
//! (`.vtp`, one vertex per point) listed with their times in a ParaView collection
//! (`snapshots.pvd`).
//!
//! History columns, each name ending in its unit as every CSV the tools write does
//! (`time_s`, `kinetic_j`): time [s]; kinetic, internal (stress work), external work,
//! boundary work and energy error [J]; momentum p_i [kg m/s]; with several bodies, each
//! body's kinetic energy `kinetic_<body>_j`; per rigid body the contact force on it F_i [N]
//! and the number of points in contact; per control point its position x_i [m]. Plane
//! strain: per metre of thickness (`_j_per_m`, `_kg_per_s`, `_n_per_m`).
//! Snapshot point data: velocity [m/s], Cauchy stress σ (3×3) [Pa], von Mises stress [Pa],
//! α [-], θ [K], the equivalent plastic strain rate of the last step Δα/Δt [1/s],
//! J = det F [-], body index. `read_snapshot` reads a snapshot back (positions, time, the
//! scalar and vector arrays), for charts and measures of the fields.

use crate::kinematics::Kinematics;
use crate::solver::observer::{Observer, Verdict, CONTINUE};
use crate::solver::Solver;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Axis names of columns and results.
pub const AXES: [&str; 3] = ["x", "y", "z"];

/// Units of the history columns as name suffixes: plane-strain quantities are per metre of
/// thickness, axisymmetric ones of the full ring.
struct Units {
    energy: &'static str,
    momentum: &'static str,
    force: &'static str,
}

impl Units {
    fn of(kinematics: Kinematics) -> Self {
        match kinematics {
            Kinematics::PlaneStrain => Units {
                energy: "j_per_m",
                momentum: "kg_per_s",
                force: "n_per_m",
            },
            Kinematics::Axisymmetric | Kinematics::Solid => Units {
                energy: "j",
                momentum: "kg_m_per_s",
                force: "n",
            },
        }
    }
}

/// The unit suffix of a force column: `n_per_m` in plane strain, `n` otherwise.
pub fn force_unit(kinematics: Kinematics) -> &'static str {
    Units::of(kinematics).force
}

/// Streams one history row per observed step (wrap it in `observer::Every` to thin it);
/// flushed every row so a failed run keeps its history. Column names end in their units,
/// e.g. `kinetic_j`, `platen_force_z_n`.
pub struct HistoryWriter {
    out: BufWriter<File>,
}

impl HistoryWriter {
    pub fn create<const D: usize>(path: &Path, solver: &Solver<D>) -> io::Result<Self> {
        let mut out = BufWriter::new(File::create(path)?);
        let u = Units::of(solver.settings.kinematics);
        let mut cols: Vec<String> = vec!["time_s".into()];
        cols.extend(
            [
                "kinetic",
                "internal",
                "external_work",
                "boundary_work",
                "energy_error",
            ]
            .map(|c| format!("{c}_{}", u.energy)),
        );
        cols.extend((0..D).map(|i| format!("momentum_{}_{}", AXES[i], u.momentum)));
        if solver.blocks.len() > 1 {
            cols.extend(
                solver
                    .blocks
                    .iter()
                    .map(|b| format!("kinetic_{}_{}", b.name, u.energy)),
            );
        }
        for r in &solver.rigid {
            cols.extend((0..D).map(|i| format!("{}_force_{}_{}", r.body.name, AXES[i], u.force)));
            cols.push(format!("{}_contacts", r.body.name));
        }
        for (name, _) in &solver.control_points {
            cols.extend((0..D).map(|i| format!("{name}_{}_m", AXES[i])));
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
/// state), and the collection `snapshots.pvd` listing them with their times, rewritten after
/// each snapshot so that a stopped run's collection is complete: ParaView opens it as one
/// time series with the real times.
pub struct SnapshotWriter {
    dir: PathBuf,
    interval: f64,
    /// Time [s] of each snapshot written so far.
    times: Vec<f64>,
}

/// The collection file of a run's snapshots.
pub const COLLECTION: &str = "snapshots.pvd";

impl SnapshotWriter {
    pub fn new(dir: &Path, end: f64, count: usize) -> Self {
        SnapshotWriter {
            dir: dir.into(),
            interval: end / count.max(1) as f64,
            times: Vec::new(),
        }
    }

    /// Write the current state as the next snapshot whatever the time.
    pub fn write_next<const D: usize>(&mut self, s: &Solver<D>) -> io::Result<()> {
        write_snapshot(&self.dir, self.times.len(), s)?;
        self.times.push(s.time);
        self.write_collection()
    }

    fn write_collection(&self) -> io::Result<()> {
        let mut out = BufWriter::new(File::create(self.dir.join(COLLECTION))?);
        writeln!(out, "<?xml version=\"1.0\"?>")?;
        writeln!(
            out,
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">"
        )?;
        writeln!(out, "  <Collection>")?;
        for (k, t) in self.times.iter().enumerate() {
            writeln!(
                out,
                "    <DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"{}\"/>",
                snapshot_name(k)
            )?;
        }
        writeln!(out, "  </Collection>\n</VTKFile>")?;
        out.flush()
    }
}

impl<const D: usize> Observer<D> for SnapshotWriter {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        if s.time >= self.times.len() as f64 * self.interval - 0.5 * s.dt {
            self.write_next(s)?;
        }
        CONTINUE
    }
}

/// The file name of snapshot `index`.
pub fn snapshot_name(index: usize) -> String {
    format!("snapshot_{index:05}.vtp")
}

/// The first three components of `x`, padded with zeros.
fn pad(x: &[f64]) -> [f64; 3] {
    std::array::from_fn(|i| x.get(i).copied().unwrap_or(0.0))
}

/// One array of a snapshot: its XML attributes and its little-endian bytes.
struct DataArray {
    attributes: String,
    bytes: Vec<u8>,
}

impl DataArray {
    /// Float32 values with `components` per point.
    fn float(name: &str, components: usize, values: impl IntoIterator<Item = f64>) -> Self {
        let bytes = values
            .into_iter()
            .flat_map(|v| (v as f32).to_le_bytes())
            .collect();
        DataArray {
            attributes: format!(
                "type=\"Float32\" Name=\"{name}\" NumberOfComponents=\"{components}\""
            ),
            bytes,
        }
    }

    fn int(name: &str, values: impl IntoIterator<Item = i64>) -> Self {
        DataArray {
            attributes: format!("type=\"Int64\" Name=\"{name}\""),
            bytes: values.into_iter().flat_map(i64::to_le_bytes).collect(),
        }
    }
}

/// Write the particles of `solver` to `dir/snapshot_NNNNN.vtp` (VTK XML PolyData, one
/// vertex per point, raw appended binary data: each array a UInt64 byte count and its
/// bytes); the time is the field `TimeValue`. Returns the path.
pub fn write_snapshot<const D: usize>(
    dir: &Path,
    index: usize,
    solver: &Solver<D>,
) -> io::Result<PathBuf> {
    let path = dir.join(snapshot_name(index));
    let p = &solver.particles;
    let n = p.len();
    let history = |f: fn(&materials::State<f64>) -> f64| {
        solver
            .blocks
            .iter()
            .flat_map(move |b| b.state.iter().map(f))
            .collect::<Vec<f64>>()
    };
    let body = |(k, b): (usize, &crate::MaterialBlock)| b.range.clone().map(move |_| k as f64);
    let point_data = [
        DataArray::float(
            "velocity",
            3,
            p.velocity.iter().flat_map(|v| pad(v.as_slice())),
        ),
        DataArray::float(
            "stress",
            9,
            p.stress
                .iter()
                .flat_map(|s| s.transpose().iter().copied().collect::<Vec<_>>()),
        ),
        DataArray::float("von_mises", 1, p.stress.iter().map(von_mises)),
        DataArray::float("alpha", 1, history(|s| s.alpha)),
        DataArray::float("theta", 1, history(|s| s.theta)),
        DataArray::float(
            "alpha_rate",
            1,
            history(|s| s.dalpha).into_iter().map(|d| d / solver.dt),
        ),
        DataArray::float("J", 1, p.deformation.iter().map(|f| f.determinant())),
        DataArray::float("body", 1, solver.blocks.iter().enumerate().flat_map(body)),
    ];
    let points = DataArray::float(
        "position",
        3,
        p.position.iter().flat_map(|x| pad(x.as_slice())),
    );
    let verts = [
        DataArray::int("connectivity", 0..n as i64),
        DataArray::int("offsets", 1..=n as i64),
    ];
    let mut out = BufWriter::new(File::create(&path)?);
    let mut offset = 0;
    let mut declare = |out: &mut BufWriter<File>, a: &DataArray| -> io::Result<()> {
        writeln!(
            out,
            "        <DataArray {} format=\"appended\" offset=\"{offset}\"/>",
            a.attributes
        )?;
        offset += 8 + a.bytes.len();
        Ok(())
    };
    writeln!(out, "<?xml version=\"1.0\"?>")?;
    writeln!(out, "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">")?;
    writeln!(out, "  <PolyData>")?;
    writeln!(out, "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{:e}</DataArray>\n    </FieldData>", solver.time)?;
    writeln!(out, "    <Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"{n}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">")?;
    writeln!(
        out,
        "      <PointData Scalars=\"von_mises\" Vectors=\"velocity\" Tensors=\"stress\">"
    )?;
    for a in &point_data {
        declare(&mut out, a)?;
    }
    writeln!(out, "      </PointData>\n      <Points>")?;
    declare(&mut out, &points)?;
    writeln!(out, "      </Points>\n      <Verts>")?;
    for a in &verts {
        declare(&mut out, a)?;
    }
    writeln!(out, "      </Verts>\n    </Piece>\n  </PolyData>")?;
    write!(out, "  <AppendedData encoding=\"raw\">\n   _")?;
    for a in point_data.iter().chain([&points]).chain(&verts) {
        out.write_all(&(a.bytes.len() as u64).to_le_bytes())?;
        out.write_all(&a.bytes)?;
    }
    writeln!(out, "\n  </AppendedData>\n</VTKFile>")?;
    out.flush()?;
    Ok(path)
}

/// A snapshot read back: its time, the point positions, every one- and three-component
/// array.
#[derive(Debug, Clone, Default)]
pub struct Snapshot {
    /// [s]
    pub time: f64,
    /// Point positions (x, y, z) [m] (z = 0 in 2D).
    pub position: Vec<[f64; 3]>,
    /// Scalar point arrays by name (`alpha`, `theta`, `alpha_rate`, `von_mises`, ...).
    pub scalars: Vec<(String, Vec<f64>)>,
    /// Three-component point arrays by name (`velocity`).
    pub vectors: Vec<(String, Vec<[f64; 3]>)>,
}

impl Snapshot {
    /// The three-component array `name`.
    pub fn vector(&self, name: &str) -> Option<&[[f64; 3]]> {
        self.vectors
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }

    /// The scalar array `name`.
    pub fn scalar(&self, name: &str) -> Option<&[f64]> {
        self.scalars
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }
}

/// Read a snapshot written by `write_snapshot`.
pub fn read_snapshot(path: &Path) -> io::Result<Snapshot> {
    let bytes = std::fs::read(path)?;
    let bad = |what: &str| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "{}: {what} (not a snapshot written by mpw?)",
                path.display()
            ),
        )
    };
    let marker = b"<AppendedData encoding=\"raw\">\n   _";
    let start = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .ok_or_else(|| bad("no raw appended data"))?
        + marker.len();
    let xml = String::from_utf8_lossy(&bytes[..start]);
    let attr = |line: &str, key: &str| -> Option<String> {
        let from = line.find(&format!("{key}=\""))? + key.len() + 2;
        Some(line[from..from + line[from..].find('"')?].to_string())
    };
    let block = |offset: usize| -> io::Result<&[u8]> {
        let at = start + offset;
        let head = bytes
            .get(at..at + 8)
            .ok_or_else(|| bad("an offset past the end"))?;
        let len = u64::from_le_bytes(head.try_into().unwrap()) as usize;
        bytes
            .get(at + 8..at + 8 + len)
            .ok_or_else(|| bad("an array past the end"))
    };
    let floats = |b: &[u8]| -> Vec<f64> {
        b.chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()) as f64)
            .collect()
    };
    let mut out = Snapshot::default();
    for line in xml.lines() {
        if line.contains("Name=\"TimeValue\"") {
            let value = line.split('>').nth(1).and_then(|v| v.split('<').next());
            out.time = value
                .and_then(|v| v.trim().parse().ok())
                .ok_or_else(|| bad("no time"))?;
        }
        let (Some(name), Some(offset)) = (attr(line, "Name"), attr(line, "offset")) else {
            continue;
        };
        let offset: usize = offset.parse().map_err(|_| bad("a bad offset"))?;
        let components = attr(line, "NumberOfComponents").unwrap_or_default();
        let triples = |b: &[u8]| -> Vec<[f64; 3]> {
            floats(b)
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect()
        };
        if name == "position" {
            out.position = triples(block(offset)?);
        } else if components == "3" {
            out.vectors.push((name, triples(block(offset)?)));
        } else if components == "1" {
            out.scalars.push((name, floats(block(offset)?)));
        }
    }
    Ok(out)
}

/// von Mises equivalent stress √(3/2 dev σ : dev σ) [Pa].
pub fn von_mises(s: &nalgebra::Matrix3<f64>) -> f64 {
    let dev = s - nalgebra::Matrix3::identity() * (s.trace() / 3.0);
    (1.5 * dev.dot(&dev)).sqrt()
}
