//! Scene files (TOML): grid, time, materials by file or inline, bodies from primitives, rigid
//! bodies, boundary conditions, control points and outputs. Unknown keys and wrong types
//! are rejected by the parser with the key named; every value is then checked and an
//! error names the field (e.g. `bodies[1].shape.radius`). Paths are relative to the scene
//! file. Units SI.
//!
//! ```toml
//! kinematics = "plane-strain"      # "plane-strain" | "axisymmetric" | "3d"
//! traction_history = [[t, factor], ...]   # optional: every traction scaled over time
//! [grid]                           # spacing [m], origin [m], shift amplitudes [m], seed
//! [time]                           # end [s], dt [s] (optional), safety, scheme = "musl" (default)|"usl"|"usf"
//! [solver]                         # damping [1/s], mass_cutoff, body_force [m/s²], domain, blowup_factor,
//!                                  # bulk_viscosity = [C1, C2] (default [0.06, 1.5]; [0, 0] for none),
//!                                  # shape_function = "cpdi" (default) | "linear" | "ugimp" | "cpgimp" | ...,
//!                                  # pic_fraction = 0 (default, FLIP) .. 1 (PIC)
//! [[materials]]                    # name, file = "../materials/x.toml", neo_hooke = {E, nu, rho},
//!                                  # or parameters = { the contents of a parameter file }
//! [[bodies]]                       # name, material, shape = {type = "box"|"disk"|"sphere"|"cylinder"|"polygon", ...},
//!                                  # particles_per_cell, velocity
//! [[rigid_bodies]]                 # name, shape = {type = "half-space"|"box"|"polygon"|"triangles", ...},
//!                                  # penalty, friction, search_interval, translation = [[t, u...]], rotation
//! [[velocity_bcs]]                 # nodes = {plane|below|above = "x", at}, fixed = ["x", ...], value = [...],
//!                                  # one_sided = true (a wall the body may leave; below/above nodes),
//!                                  # history = [[t, factor], ...] (value scaled over time)
//!                                  # (axisymmetric scenes get v_r = 0 on r <= 0 first, listed in the run log)
//! [[springs]]                      # region = {min, max}, directions, stiffness
//! [[tractions]]                    # region = {min, max}, force [N]
//! [[control_points]]               # name, position
//! [output]                         # history_every (steps), snapshots (count)
//! ```

//!
//! The description (module `spec`) is built into a solver by one function per part:
//! `settings`, `materials`, `bodies`, `rigid`, `conditions`.

mod bodies;
mod check;
mod conditions;
mod materials;
mod rigid;
mod settings;
pub mod spec;

pub use spec::*;

use crate::boundary::VelocityBc;
use crate::kinematics::Kinematics;
use crate::solver::Solver;
use ::materials::AnyModel;
use check::Check;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use thiserror::Error;

#[derive(Debug, Error)]
pub enum SceneError {
    #[error("{file}: cannot read: {reason}")]
    Io {
        file: PathBuf,
        reason: std::io::Error,
    },
    /// TOML syntax, an unknown key or a wrong type, placed by `::materials::toml_place`.
    #[error("{0}")]
    Syntax(String),
    /// A value that does not hold, at the line of its key when the file's text is known
    /// (`load`), else in the file.
    #[error("{}: `{field}`: {problem}", at.as_ref().map_or_else(|| file.display().to_string(), |a| a.to_string()))]
    Field {
        file: PathBuf,
        at: Option<::materials::toml_place::Location>,
        field: String,
        problem: String,
    },
    /// A mesh body's file (module `mesh`), with its line.
    #[error("{0}")]
    Mesh(crate::mesh::MeshError),
}

/// A built scene: a solver of the right dimension and the run settings.
pub enum Simulation {
    Planar(Solver<2>),
    Solid(Solver<3>),
}

pub struct Scene {
    pub simulation: Simulation,
    /// The material model of each body, in the order of the solver's blocks.
    pub models: Vec<AnyModel>,
    pub end: f64,
    pub output: OutputSpec,
}

impl Scene {
    /// What the run will do, one line each: the scheme's stages, the shape functions (the
    /// scene's and any body's own), every velocity condition (the axis condition of an
    /// axisymmetric scene included), rigid bodies.
    pub fn describe(&self) -> Vec<String> {
        match &self.simulation {
            Simulation::Planar(s) => describe(s),
            Simulation::Solid(s) => describe(s),
        }
    }
}

fn describe<const D: usize>(s: &Solver<D>) -> Vec<String> {
    let scene = s.settings.shape_function;
    let own = s.blocks.iter().filter_map(|b| {
        let kernel = b.kernel(scene);
        (kernel != scene).then(|| format!(", body {}: {}", b.name, kernel.name()))
    });
    let kernels = format!(
        "shape functions {}{}",
        scene.name(),
        own.collect::<String>()
    );
    let mut lines = vec![format!("scheme {}", s.settings.scheme), kernels];
    lines.extend(
        s.velocity_bcs
            .iter()
            .map(|bc| format!("velocity condition: {bc}")),
    );
    lines.extend(
        s.conditions
            .iter()
            .map(|c| format!("point condition: {}", c.describe())),
    );
    lines.extend(s.rigid.iter().map(|r| {
        format!(
            "rigid body {}: penalty {:e} N/m, friction {}",
            r.body.name, r.body.penalty, r.body.friction
        )
    }));
    lines
}

/// Read and validate a scene file.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    from_description(&read(path)?, path).map_err(|e| match e {
        SceneError::Field {
            file,
            at: None,
            field,
            problem,
        } => {
            let at = std::fs::read_to_string(path)
                .ok()
                .map(|text| field_location(path, &text, &field));
            SceneError::Field {
                file,
                at,
                field,
                problem,
            }
        }
        other => other,
    })
}

/// Where the field `field` of a scene's description (`bodies[1].shape.radius`,
/// `grid.spacing`, `kinematics`) is written in `text`: the line that sets its first key
/// inside its table (the table's header when the key is not written there).
fn field_location(path: &Path, text: &str, field: &str) -> ::materials::toml_place::Location {
    let mut parts = field.split('.');
    let first = parts.next().unwrap_or_default();
    let (table, index) = match first.split_once('[') {
        Some((t, rest)) => (t, rest.trim_end_matches(']').parse().unwrap_or(0)),
        None => (first, 0),
    };
    let span = match parts.next() {
        Some(key) => ::materials::toml_place::find_key(text, Some((table, index)), key),
        None => ::materials::toml_place::find_key(text, None, table),
    };
    ::materials::toml_place::Location::in_text(path, text, span.start)
}

/// Read a scene file's description, to change it in code before `from_description`.
pub fn read(path: &Path) -> Result<SceneFile, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|reason| SceneError::Io {
        file: path.into(),
        reason,
    })?;
    toml::from_str(&text)
        .map_err(|e| SceneError::Syntax(::materials::toml_place::describe(path, &text, &e)))
}

/// Check and discretize a scene description, read from a file or made in code; `file`
/// names it in errors, and material files are relative to its folder.
pub fn from_description(spec: &SceneFile, file: &Path) -> Result<Scene, SceneError> {
    let check = Check { file };
    let kinematics = match spec.kinematics.as_str() {
        "plane-strain" => Kinematics::PlaneStrain,
        "axisymmetric" => Kinematics::Axisymmetric,
        "3d" => Kinematics::Solid,
        other => {
            return Err(check.err(
                "kinematics",
                format!("`{other}` is not one of plane-strain, axisymmetric, 3d"),
            ))
        }
    };
    let dir = file.parent().unwrap_or(Path::new("."));
    let materials = materials::materials(spec, &check, dir)?;
    let simulation = match kinematics {
        Kinematics::Solid => Simulation::Solid(build::<3>(spec, kinematics, &check, &materials)?),
        _ => Simulation::Planar(build::<2>(spec, kinematics, &check, &materials)?),
    };
    let models = (spec.bodies.iter())
        .map(|b| materials[b.material.as_str()])
        .collect();
    let end = check.positive("time.end", spec.time.end)?;
    if spec.output.history_every == 0 {
        return Err(check.err("output.history_every", "must be at least 1"));
    }
    Ok(Scene {
        simulation,
        models,
        end,
        output: spec.output.clone(),
    })
}

fn build<const D: usize>(
    spec: &SceneFile,
    kinematics: Kinematics,
    check: &Check,
    materials: &HashMap<&str, AnyModel>,
) -> Result<Solver<D>, SceneError> {
    let mut solver = Solver::new(settings::settings::<D>(spec, kinematics, check)?);
    if kinematics == Kinematics::Axisymmetric {
        // stated, not silent: the run log lists it with the other conditions
        solver.velocity_bcs.push(VelocityBc::axis());
    }
    bodies::add_bodies(&mut solver, spec, check, materials)?;
    rigid::add_rigid_bodies(&mut solver, spec, check)?;
    conditions::add_velocity_bcs(&mut solver, spec, check)?;
    conditions::add_springs_and_tractions(&mut solver, spec, check)?;
    conditions::add_control_points(&mut solver, spec, check)?;
    if solver.particles.is_empty() {
        return Err(check.err("bodies", "the scene has no particles"));
    }
    Ok(solver)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenes() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/scenes")
    }

    #[test]
    fn every_shipped_scene_loads() {
        let mut count = 0;
        for entry in std::fs::read_dir(scenes()).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                load(&path).unwrap_or_else(|e| panic!("{e}"));
                count += 1;
            }
        }
        assert!(count >= 9, "{count} scenes");
    }

    #[test]
    fn errors_name_the_field() {
        let dir = std::env::temp_dir().join(format!("mpw_scene_test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.toml");
        let text = std::fs::read_to_string(scenes().join("colliding_disks.toml")).unwrap();
        std::fs::write(
            &path,
            text.replace(
                "radius = 0.2 }\nvelocity = [-0.1",
                "radius = -0.2 }\nvelocity = [-0.1",
            ),
        )
        .unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(e.contains("bodies[1].shape.radius"), "{e}");
        std::fs::write(
            &path,
            text.replace("spacing = 0.05", "spacing = 0.05\nspaceing = 1"),
        )
        .unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(e.contains("spaceing"), "{e}");
        std::fs::write(
            &path,
            text.replace(
                "shape_function = \"linear\"",
                "shape_function = \"linear\"\npic_fraction = 1.5",
            ),
        )
        .unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(
            e.contains("solver.pic_fraction") && e.contains("1.5"),
            "{e}"
        );
    }

    /// The shipped axisymmetric Taylor scene with its material path made absolute, to be
    /// written elsewhere with a change.
    fn axisymmetric_taylor_text() -> String {
        std::fs::read_to_string(scenes().join("taylor_bar_axisymmetric.toml"))
            .unwrap()
            .replace(
                "../materials/",
                &format!("{}/", scenes().join("../materials").display()),
            )
    }

    /// `output.derivatives` writes the control point's sensitivity p ∂x/∂p: the shipped
    /// Taylor bar to 10 µs (the elastic precursor, whose height A sets, has reached the
    /// top), against central differences of plain runs with A set in the solver, the
    /// closer of h/p = 1e-6 and 1e-8 (as in `tests/tangent.rs`).
    #[test]
    fn derivatives_of_a_scene_go_to_their_file() {
        let dir =
            std::env::temp_dir().join(format!("mpw_scene_derivatives-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("taylor.toml");
        let text = axisymmetric_taylor_text()
            .replace("end = 80e-6", "end = 10e-6")
            .replace(
                "history_every = 20",
                "history_every = 20\nderivatives = [\"A\"]",
            );
        std::fs::write(&path, &text).unwrap();
        let scene = load(&path).unwrap();
        let a = ::materials::Model::param(&scene.models[0], "A").unwrap();
        crate::run::run_scene(
            scene,
            &dir,
            |_| {},
            |_, _| std::ops::ControlFlow::Continue(()),
        )
        .unwrap();
        let table = std::fs::read_to_string(dir.join("derivatives.csv")).unwrap();
        let header: Vec<&str> = table.lines().next().unwrap().split(',').collect();
        assert_eq!(header, ["time_s", "top_x_A_m", "top_y_A_m"]);
        let last: Vec<f64> = (table.lines().last().unwrap().split(','))
            .map(|v| v.parse().unwrap())
            .collect();
        let top_y = |a_value: f64| {
            let scene = load(&path).unwrap();
            let model = ::materials::Model::map_params(&scene.models[0], |n, v| {
                if n == "A" {
                    a_value
                } else {
                    v
                }
            });
            let Simulation::Planar(mut s) = scene.simulation else {
                panic!("a planar scene")
            };
            s.set_material(0, std::sync::Arc::new(model));
            s.initialize();
            // to the last row written (a row every history_every steps, as history.csv)
            while s.time < last[0] - 0.5 * s.dt {
                s.step().unwrap();
            }
            s.particles.position[s.control_points[0].1][1]
        };
        let central = |rel: f64| (top_y(a * (1.0 + rel)) - top_y(a * (1.0 - rel))) / (2.0 * rel);
        let error = [1e-6, 1e-8].map(|rel| (central(rel) / last[2] - 1.0).abs());
        assert!(last[2].abs() > 1e-7, "the top has felt A: {} m", last[2]);
        assert!(error[0].min(error[1]) < 1e-4, "{last:?} against {error:?}");
    }

    /// Springs of a scene file are registered as point conditions and named in the run
    /// log with their points, directions and stiffness.
    #[test]
    fn springs_are_registered_and_described() {
        let dir = std::env::temp_dir().join(format!("mpw_scene_springs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("springs.toml");
        let springs = "\n[[springs]]\nregion = { min = [0.0, 0.0], max = [1.0, 1e-3] }\n\
                       directions = [\"y\"]\nstiffness = 1e9\n";
        std::fs::write(&path, axisymmetric_taylor_text() + springs).unwrap();
        let scene = load(&path).unwrap();
        let Simulation::Planar(s) = &scene.simulation else {
            panic!("the Taylor scene is axisymmetric")
        };
        assert_eq!(s.conditions.len(), 1);
        assert_eq!(s.conditions[0].stiffness(), 1e9);
        let log = scene.describe();
        let line = log
            .iter()
            .find(|l| l.starts_with("point condition: springs on "));
        assert!(
            line.is_some_and(|l| l.ends_with("points along y, κ = 1e9 N/m")),
            "{log:?}"
        );
    }

    #[test]
    fn walls_need_a_side_and_do_not_move_with_the_grid_shift() {
        let dir = std::env::temp_dir().join(format!("mpw_scene_wall_test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.toml");
        let text = axisymmetric_taylor_text();
        std::fs::write(&path, text.replace("below = \"y\"", "plane = \"y\"")).unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(e.contains("velocity_bcs[0].one_sided"), "{e}");
        let shifted = text.replace("[time]", "shift = [0.0, 1e-5]\n\n[time]");
        std::fs::write(&path, shifted).unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(
            e.contains("velocity_bcs[0]") && e.contains("springs"),
            "{e}"
        );
    }

    /// The shipped Taylor bars carry exactly the bar's mass ρ π R² L (the 3D cylinder's
    /// lattice fill had +3.45 % at 4 cells across the radius), and an
    /// axisymmetric body across the axis is rejected.
    #[test]
    fn bodies_carry_exactly_their_mass_and_stay_off_the_negative_radius() {
        let (radius, length) = (0.00381, 0.0254);
        let bar = 8960.0 * std::f64::consts::PI * radius * radius * length;
        let axi = load(&scenes().join("taylor_bar_axisymmetric.toml")).unwrap();
        let solid = load(&scenes().join("taylor_bar_3d.toml")).unwrap();
        for m in [axi, solid].map(|scene| match scene.simulation {
            Simulation::Planar(s) => s.particles.mass.iter().sum::<f64>(),
            Simulation::Solid(s) => s.particles.mass.iter().sum::<f64>(),
        }) {
            assert!((m / bar - 1.0).abs() < 1e-10, "{m} vs {bar}");
        }
        let dir = std::env::temp_dir().join(format!("mpw_scene_axis_test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.toml");
        let text = axisymmetric_taylor_text();
        std::fs::write(
            &path,
            text.replace("min = [0.0, 0.0]", "min = [-0.001, 0.0]"),
        )
        .unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(e.contains("bodies[0].shape") && e.contains("r ≥ 0"), "{e}");
    }

    #[test]
    fn a_scene_runs_and_writes_history_and_snapshots() {
        let dir = std::env::temp_dir().join(format!("mpw_run_test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut scene = load(&scenes().join("single_particle.toml")).unwrap();
        scene.end = 1.0;
        let summary = crate::run::run_scene(
            scene,
            &dir,
            |_| {},
            |_, _| std::ops::ControlFlow::Continue(()),
        )
        .unwrap();
        assert!(summary.failure.is_none());
        // the run ends at the step nearest to t_end = 1 s, and the history has a header,
        // the initial state and one row per step (history_every = 1)
        let steps = (1.0 / summary.time_step.dt).round() as usize;
        assert!(summary.time_step_changes.is_empty());
        assert_eq!(summary.steps, steps);
        let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
        assert_eq!(history.lines().count(), 1 + 1 + steps);
        assert!(
            history.starts_with("time_s,kinetic_j,"),
            "{}",
            &history[..40]
        );
        let snapshot = std::fs::read(dir.join("snapshot_00010.vtp")).unwrap();
        assert!(snapshot.starts_with(b"<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\""));
    }

    /// A snapshot's appended arrays are where its XML says (offsets and UInt64 byte
    /// counts), hold the solver's values, and the collection lists every snapshot with its
    /// time.
    #[test]
    fn snapshots_hold_the_state_and_the_collection_their_times() {
        let dir = std::env::temp_dir().join(format!("mpw_vtp_test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let scene = load(&scenes().join("colliding_disks.toml")).unwrap();
        let Simulation::Planar(mut solver) = scene.simulation else {
            unreachable!()
        };
        solver.initialize();
        let mut writer = crate::output::SnapshotWriter::new(&dir, 1e-3, 4);
        writer.write_next(&solver).unwrap();
        for _ in 0..3 {
            solver.step().unwrap();
        }
        writer.write_next(&solver).unwrap();
        let bytes = std::fs::read(dir.join("snapshot_00001.vtp")).unwrap();
        let raw = b"<AppendedData encoding=\"raw\">\n   _";
        let start = bytes.windows(raw.len()).position(|w| w == raw).unwrap() + raw.len();
        let xml = String::from_utf8_lossy(&bytes[..start]);
        // every declared array, in order: its name and offset
        let arrays: Vec<(String, usize)> = xml
            .lines()
            .filter(|l| l.contains("format=\"appended\""))
            .map(|l| {
                let attr = |key: &str| {
                    let from = l.find(&format!("{key}=\"")).unwrap() + key.len() + 2;
                    l[from..from + l[from..].find('"').unwrap()].to_string()
                };
                (attr("Name"), attr("offset").parse().unwrap())
            })
            .collect();
        let read = |offset: usize| {
            let at = start + offset;
            let len = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
            &bytes[at + 8..at + 8 + len]
        };
        let f32s = |b: &[u8]| -> Vec<f64> {
            b.chunks(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()) as f64)
                .collect()
        };
        let n = solver.particles.len();
        let find = |name: &str| arrays.iter().find(|(a, _)| a == name).unwrap().1;
        let position = f32s(read(find("position")));
        assert_eq!(position.len(), 3 * n);
        for (k, x) in solver.particles.position.iter().enumerate() {
            assert_eq!(position[3 * k] as f32, x[0] as f32);
            assert_eq!(position[3 * k + 1] as f32, x[1] as f32);
            assert_eq!(position[3 * k + 2], 0.0);
        }
        let velocity = f32s(read(find("velocity")));
        assert_eq!(
            velocity[3 * (n - 1) + 1] as f32,
            solver.particles.velocity[n - 1][1] as f32
        );
        // the last array ends where the appended section closes
        let (_, last) = arrays.last().unwrap();
        let end = start + last + 8 + read(*last).len();
        assert!(bytes[end..].starts_with(b"\n  </AppendedData>\n</VTKFile>"));
        let offsets = read(find("offsets"));
        assert_eq!(
            i64::from_le_bytes(offsets[offsets.len() - 8..].try_into().unwrap()),
            n as i64
        );
        // read back: positions, time and the scalar arrays, as written (in f32)
        let back = crate::output::read_snapshot(&dir.join("snapshot_00001.vtp")).unwrap();
        assert_eq!(back.time, solver.time);
        assert_eq!(back.position.len(), n);
        assert_eq!(
            back.position[7][1],
            solver.particles.position[7][1] as f32 as f64
        );
        let theta = back.scalar("theta").unwrap();
        assert_eq!(
            theta[n - 1],
            solver.blocks[1].state.last().unwrap().theta as f32 as f64
        );
        assert_eq!(back.scalar("alpha_rate").unwrap().len(), n);
        let v = back.vector("velocity").unwrap();
        assert_eq!(v[3][0], solver.particles.velocity[3][0] as f32 as f64);
        let collection = std::fs::read_to_string(dir.join(crate::output::COLLECTION)).unwrap();
        let times: Vec<f64> = collection
            .lines()
            .filter_map(|l| l.split("timestep=\"").nth(1))
            .map(|t| t[..t.find('"').unwrap()].parse().unwrap())
            .collect();
        assert_eq!(times, [0.0, solver.time]);
        assert!(collection.contains("file=\"snapshot_00001.vtp\""));
    }

    /// A run its caller stops (Ctrl-C in `mpw simulate`) ends at that step with cause
    /// `Interrupted`, its last state in the history and its results written.
    #[test]
    fn a_stopped_run_keeps_its_last_state_and_results() {
        let dir = std::env::temp_dir().join(format!("mpw_stop_test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let scene = load(&scenes().join("single_particle.toml")).unwrap();
        let mut calls = 0;
        let summary = crate::run::run_scene(
            scene,
            &dir,
            |_| {},
            |_, _| {
                calls += 1;
                match calls > 7 {
                    true => std::ops::ControlFlow::Break(()),
                    false => std::ops::ControlFlow::Continue(()),
                }
            },
        )
        .unwrap();
        let failure = summary.failure.unwrap();
        assert_eq!(failure.cause, crate::Cause::Interrupted);
        assert_eq!(failure.cause.kind(), crate::failure::FailureKind::Stopped);
        // the initial state is observed once, then steps 1..=7 pass and step 8 stops
        assert_eq!(summary.steps, 8);
        let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
        let last: f64 = history
            .lines()
            .last()
            .unwrap()
            .split(',')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(
            (last - failure.time).abs() <= 1e-12 * failure.time,
            "{last} vs {}",
            failure.time
        );
        assert!(dir.join("results.csv").exists());
    }

    /// Sizes derived from a scene are bounded before anything of that size is allocated
    ///: a spacing of 1 nm on the colliding disks (4e17 points) is an error that
    /// names the body; an end time of 1e30 s stops at step 0 naming `time.end`; a point
    /// thrown 1e12 m away (2e13 cells) stops the run instead of allocating the grid.
    #[test]
    fn sizes_from_a_scene_are_bounded_before_allocation() {
        let dir =
            std::env::temp_dir().join(format!("mpw_scene_limits_test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bad.toml");
        let text = std::fs::read_to_string(scenes().join("colliding_disks.toml")).unwrap();
        std::fs::write(&path, text.replace("spacing = 0.05", "spacing = 1e-9")).unwrap();
        let e = load(&path).err().unwrap().to_string();
        assert!(
            e.contains("bodies[0].shape") && e.contains("material points"),
            "{e}"
        );
        std::fs::write(&path, text.replace("end = 3.5", "end = 1e30")).unwrap();
        let summary = crate::run::run_scene(
            load(&path).unwrap(),
            &dir,
            |_| {},
            |_, _| std::ops::ControlFlow::Continue(()),
        )
        .unwrap();
        let failure = summary.failure.unwrap();
        assert_eq!(summary.steps, 0);
        assert!(
            matches!(failure.cause, crate::Cause::TooManySteps(_)),
            "{failure}"
        );
        assert!(failure.to_string().contains("time.end = 1e30"), "{failure}");
        // the failure keeps its output, as any other (mpw simulate charts the history)
        let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
        assert_eq!(history.lines().count(), 1 + 2);
        let mut scene = load(&scenes().join("colliding_disks.toml")).unwrap();
        let Simulation::Planar(solver) = &mut scene.simulation else {
            unreachable!()
        };
        solver.initialize();
        solver.particles.position[0][1] = 1e12;
        let e = solver.step().unwrap_err();
        assert!(matches!(e.cause, crate::Cause::GridTooLarge(_)), "{e}");
    }

    /// Every shipped scene's description goes to TOML and back unchanged.
    #[test]
    fn descriptions_serialize_and_parse_back_unchanged() {
        for entry in std::fs::read_dir(scenes()).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "toml") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            let spec: SceneFile = toml::from_str(&text).unwrap();
            let again: SceneFile = toml::from_str(&toml::to_string(&spec).unwrap()).unwrap();
            assert_eq!(spec, again, "{}", path.display());
        }
    }

    /// A material given inline builds the same model as the file it copies, and the
    /// axisymmetric axis condition is listed in the run log.
    #[test]
    fn an_inline_material_equals_its_file() {
        let path = scenes().join("taylor_bar_axisymmetric.toml");
        let mut spec: SceneFile = toml::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let by_file = from_description(&spec, &path).unwrap();
        let material = scenes().join(spec.materials[0].file.take().unwrap());
        let table: toml::Table = std::fs::read_to_string(material).unwrap().parse().unwrap();
        spec.materials[0].parameters = Some(table);
        let inline = from_description(&spec, &path).unwrap();
        let (Simulation::Planar(a), Simulation::Planar(b)) =
            (&by_file.simulation, &inline.simulation)
        else {
            unreachable!()
        };
        assert_eq!(a.particles.mass, b.particles.mass);
        let (m, n) = (&a.blocks[0].material, &b.blocks[0].material);
        assert_eq!(m.p_wave_modulus(), n.p_wave_modulus());
        let f = nalgebra::Matrix3::new(0.9, 0.05, 0.0, 0.0, 1.05, 0.0, 0.0, 0.0, 1.02);
        let state = m.initial_state();
        assert_eq!(
            m.update(&f, 1e-6, &state).unwrap().0,
            n.update(&f, 1e-6, &state).unwrap().0
        );
        let log = inline.describe();
        assert!(
            log.iter()
                .any(|l| l == "velocity condition: v_x = 0 m/s on nodes at x <= 0 m"),
            "{log:?}"
        );
        // a bad inline value is named by its field
        spec.materials[0].parameters.as_mut().unwrap()["elastic"]["E"] = toml::Value::Float(-1.0);
        let e = from_description(&spec, &path).err().unwrap().to_string();
        assert!(
            e.contains("materials[0].parameters") && e.contains("E"),
            "{e}"
        );
    }

    /// Two trusses side by side (`truss.toml` and a copy 3 m to the right, apart on the
    /// grid), the scene's kernel `scene` and each body's `bodies` (`None`: the scene's),
    /// after 30 steps of 1 ms (both stretching under g): the points' positions.
    fn two_trusses(scene: Option<&str>, bodies: [Option<&str>; 2]) -> Vec<nalgebra::Vector2<f64>> {
        let line =
            |k: Option<&str>| k.map_or(String::new(), |k| format!("shape_function = \"{k}\"\n"));
        let text = std::fs::read_to_string(scenes().join("truss.toml")).unwrap();
        // a fixed Δt (0.36 of the CFL limit): an estimated one follows the fastest point of
        // either body, so one body's kernel would change the other's steps
        let text = text
            .replacen("[time]\n", "[time]\ndt = 1e-3\n", 1)
            .replacen("shape_function = \"cpdi\"\n", &line(scene), 1)
            .replacen(
                "particles_per_cell = 3\n",
                &format!(
                "particles_per_cell = 3\n{}\n[[bodies]]\nname = \"right\"\nmaterial = \"rubber\"\n\
                 shape = {{ type = \"box\", min = [2.5, 0.0], max = [3.5, 1.0] }}\n\
                 particles_per_cell = 3\n{}",
                line(bodies[0]),
                line(bodies[1])
            ),
                1,
            );
        let spec: SceneFile = toml::from_str(&text).unwrap();
        let Simulation::Planar(mut s) = from_description(&spec, &scenes().join("x.toml"))
            .unwrap()
            .simulation
        else {
            panic!("a plane scene");
        };
        s.initialize();
        for _ in 0..30 {
            s.step().unwrap();
        }
        s.particles.position
    }

    /// A scene that names no kernel runs `ShapeFunction::SCENE_DEFAULT`, and the run log
    /// says which kernel runs, and any body's own.
    #[test]
    fn a_scene_without_a_kernel_runs_the_default_and_says_so() {
        let text = std::fs::read_to_string(scenes().join("truss.toml")).unwrap();
        let unnamed = text.replacen("shape_function = \"cpdi\"\n", "", 1);
        assert_ne!(unnamed, text);
        let build = |text: &str| {
            let spec: SceneFile = toml::from_str(text).unwrap();
            from_description(&spec, &scenes().join("x.toml")).unwrap()
        };
        let scene = build(&unnamed);
        let Simulation::Planar(s) = &scene.simulation else {
            panic!("a plane scene");
        };
        assert_eq!(
            s.settings.shape_function,
            crate::shape::ShapeFunction::SCENE_DEFAULT
        );
        assert_eq!(scene.describe()[1], "shape functions cpdi");
        let own = unnamed.replacen(
            "particles_per_cell = 3\n",
            "particles_per_cell = 3\nshape_function = \"linear\"\n",
            1,
        );
        assert_eq!(
            build(&own).describe()[1],
            "shape functions cpdi, body truss: linear"
        );
    }

    /// A body's own kernel is the scene's kernel for that body: both trusses CPDI by their
    /// own tables give the scene-wide CPDI run to the bit; with one linear and one CPDI
    /// truss each moves as in the uniform run of its own kernel, while the kernels differ by
    /// far more.
    #[test]
    fn per_body_kernels_equal_the_scene_kernel_where_they_agree() {
        let scene_wide = two_trusses(Some("cpdi"), [None, None]);
        let per_body = two_trusses(None, [Some("cpdi"), Some("cpdi")]);
        assert!(
            scene_wide == per_body,
            "per-body CPDI differs from scene-wide CPDI"
        );
        let linear = two_trusses(Some("linear"), [None, None]);
        let mixed = two_trusses(Some("linear"), [None, Some("cpdi")]);
        let (left, right) = (0..mixed.len() / 2, mixed.len() / 2..mixed.len());
        let gap = |a: &[nalgebra::Vector2<f64>], b: &[nalgebra::Vector2<f64>]| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y).norm())
                .fold(0.0, f64::max)
        };
        let own = [
            gap(&mixed[left.clone()], &linear[left.clone()]),
            gap(&mixed[right.clone()], &scene_wide[right.clone()]),
        ];
        let between = [
            gap(&scene_wide[left.clone()], &linear[left]),
            gap(&scene_wide[right.clone()], &linear[right]),
        ];
        eprintln!(
            "each truss against its own kernel's run {own:?} m, between the kernels {between:?} m"
        );
        assert!(
            own[0] < 1e-12 && own[1] < 1e-12,
            "a truss changed with the other's kernel"
        );
        assert!(
            between[0] > 1e-6 && between[1] > 1e-6,
            "the kernels give the same run"
        );
        let text = std::fs::read_to_string(scenes().join("colliding_disks.toml")).unwrap();
        let text = text.replacen(
            "name = \"upper\"",
            "name = \"upper\"\nshape_function = \"gimp\"",
            1,
        );
        let spec: SceneFile = toml::from_str(&text).unwrap();
        let e = from_description(&spec, Path::new("disks.toml"))
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("bodies[1].shape_function") && e.contains("\"cpdi\""),
            "{e}"
        );
    }
}
