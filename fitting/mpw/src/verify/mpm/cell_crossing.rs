//! Homogeneous compression across cell faces, one run per kernel (thesis
//! chapter 10): the error linear MPM makes when a layer of points crosses a cell face,
//! and what uGIMP, cpGIMP and CPDI make of the same motion, against the single-point
//! driver.
//!
//! # Setup
//! A plane-strain column of 42CrMo4 QT660 (Johnson-Cook, adiabatic,
//! `materials/42crmo4_qt660.toml`), 1 mm wide and 12 mm high, 2 × 2 points per 1 mm
//! cell, compressed along y in uniaxial strain at a constant true rate ε̇ = 1000 1/s to a
//! true strain of 0.1: v_x = 0 on the node planes x = 0 and x = 1 mm (confined), v_y = 0
//! on y = 0, and every node plane y = k h at or above `FREE_TOP` = 8 mm gets
//! v_y = −ε̇ k h. That is the field v_y = −ε̇ y, fixed in space, through which the column
//! flows. Points start on it, so no wave is launched.
//!
//! The node planes y = 1 … 7 mm are free. Every point that starts below 8 mm (the test
//! points) stays below it, and the column's top face stays above 10 mm, two cells past
//! the free nodes' reach for every kernel here: no free surface is inside a free node's
//! support. (A single prescribed node plane over the top face, as in
//! `tests/mpm_vs_driver.rs`, leaves the face inside the supports of the nodes below it
//! for a domain kernel, which then sees the face's traction the point quadrature of
//! linear MPM does not see.) The layers at y = k + 0.25 mm cross the faces y = k at a
//! true strain ln(1 + 1/(4k)): 0.035 for k = 7 down to 0.080 for k = 3.
//!
//! A kernel that integrates ∫ ∇N_I over the body exactly gives zero force on a free node
//! under uniform stress, whatever the points' positions; linear MPM's one-point rule
//! gives V σ (n_below − n_above)/h when the counts of points in the two cells next to
//! the node differ, which a crossing layer makes them do. The force accelerates the
//! node, the strain rates of the points around it split, and the stress with them.
//!
//! # Measured quantities (over the test points)
//! - spread: RMS of (σ_yy − mean σ_yy) over |mean σ_yy|, largest before the first crossing
//!   (true strain < 0.03: the elastic part and yield, where the points yield a step or
//!   two apart) and largest from there on (the crossings);
//! - error: |mean σ_yy − σ_yy of the driver| over |σ_yy of the driver|, largest over the
//!   run; the driver runs the same model through F = diag(1, (1 − ε̇ Δt)ⁿ, 1), the exact
//!   discrete history of the prescribed field, one step per MPM step;
//! - crossings: how many test points ended in another cell than they started in.
//!
//! # Measured (MUSL, 2 threads; the table `mpw verify` prints)
//! | kernel | spread before / while crossing | error vs driver |
//! |---|---|---|
//! | linear | 4.2e-4 / 2.6e-1 | 1.1e-1 |
//! | uGIMP | 1.5e-3 / 1.7e-2 | 2.6e-3 |
//! | cpGIMP, CPDI | 4.7e-4 / 1.5e-5 | 2.6e-6 |
//! | cpGIMP-analytic | 4.3e-4 / 1.4e-5 | 2.4e-6 |
//!
//! All ten predicted crossings happen with every kernel. The end stress, −21.7 GPa, is
//! mostly the pressure of uniaxial strain at J = 0.905: the case is numerical, the JC
//! flow stress (≈ 1.3 GPa) a small part of it. Linear MPM ends 11 % short of it; uGIMP's
//! spread grows with each crossing layer (fixed domains overlap more as the column
//! shortens); cpGIMP and CPDI keep the spread they had after yield.
//!
//! The time step is fixed (`DT`, 0.3 of the P-wave CFL limit h/c ≈ 1.6e-7 s) so that
//! every kernel and the driver step alike.

use crate::verify::row::Row;
use materials::driver::{self, Control, LoadPath, Ramp, Temperature};
use materials::{load_material, AnyModel};
use mpm_core::discretize::{fill, Geometry};
use mpm_core::shape::ShapeFunction;
use mpm_core::{Kinematics, NodeSet, Scheme, Settings, SimulationError, Solver, VelocityBc};
use nalgebra::Vector2;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

/// Cell size [m].
const CELL: f64 = 1e-3;
/// Column width and height [m].
const WIDTH: f64 = CELL;
const HEIGHT: f64 = 12.0 * CELL;
/// The lowest node plane with prescribed v_y [m].
const FREE_TOP: f64 = 8.0 * CELL;
/// True strain rate [1/s] and final true strain [-] (compression).
const RATE: f64 = 1000.0;
const STRAIN: f64 = 0.1;
/// True strain from which on layers cross faces (the first at 0.035) [-].
const CROSSINGS_FROM: f64 = 0.03;
/// Time step [s].
const DT: f64 = 5e-8;

/// One kernel's run.
#[derive(Debug, Clone)]
pub struct Crossing {
    pub kernel: ShapeFunction,
    /// Largest RMS spread of σ_yy over the test points, relative [-], before the first
    /// crossing and from there on.
    pub spread: [f64; 2],
    /// Largest error of the mean σ_yy against the driver, relative [-].
    pub error: f64,
    /// Test points that ended in another cell.
    pub crossings: usize,
    /// Mean σ_yy at the end [Pa] and the driver's.
    pub sigma_end: f64,
    pub driver_end: f64,
    pub failure: Option<SimulationError>,
    pub wall_time: f64,
}

/// Compress the column with `kernel` (module notes).
pub fn compress(model: &AnyModel<f64>, kernel: ShapeFunction) -> Crossing {
    let started = Instant::now();
    let mut solver = column(model, kernel);
    let test: Vec<usize> = (0..solver.particles.len())
        .filter(|&i| solver.particles.reference_position[i][1] < FREE_TOP)
        .collect();
    let steps = (STRAIN / RATE / DT).round() as usize;
    let mut mean_sigma = vec![mean_and_spread(&solver, &test).0];
    let (mut spread, mut failure) = ([0.0f64; 2], None);
    for _ in 0..steps {
        if let Err(e) = solver.step() {
            failure = Some(e);
            break;
        }
        let (mean, rms) = mean_and_spread(&solver, &test);
        mean_sigma.push(mean);
        let crossing = usize::from(RATE * solver.time >= CROSSINGS_FROM);
        spread[crossing] = spread[crossing].max(rms / mean.abs());
    }
    let driver = drive(model, mean_sigma.len());
    let error = mean_sigma
        .iter()
        .zip(&driver)
        .skip(1)
        .map(|(s, d)| (s - d).abs() / d.abs())
        .fold(0.0, f64::max);
    let p = &solver.particles;
    let cell = |x: f64| (x / CELL).floor();
    Crossing {
        kernel,
        spread,
        error,
        crossings: test
            .iter()
            .filter(|&&i| cell(p.position[i][1]) != cell(p.reference_position[i][1]))
            .count(),
        sigma_end: *mean_sigma.last().unwrap(),
        driver_end: driver[mean_sigma.len() - 1],
        failure,
        wall_time: started.elapsed().as_secs_f64(),
    }
}

/// The column on its grid, with the prescribed node planes (module notes).
fn column(model: &AnyModel<f64>, kernel: ShapeFunction) -> Solver<2> {
    let mut settings = Settings::<2>::new(Kinematics::PlaneStrain, CELL);
    settings.scheme = Scheme::Musl;
    settings.shape_function = kernel;
    settings.bulk_viscosity = None;
    settings.dt = Some(DT);
    let mut solver = Solver::new(settings);
    let points = fill(
        &Geometry::Box {
            min: Vector2::zeros(),
            max: Vector2::new(WIDTH, HEIGHT),
        },
        Vector2::repeat(CELL / 2.0),
        Kinematics::PlaneStrain,
    );
    let block = solver.add_body("column", Arc::new(*model), &points, Vector2::zeros());
    if kernel.needs_domains() {
        solver.set_half_size(block, Vector2::repeat(CELL / 4.0));
    }
    for (x, v) in solver
        .particles
        .position
        .iter()
        .zip(solver.particles.velocity.iter_mut())
    {
        *v = Vector2::new(0.0, -RATE * x[1]);
    }
    for at in [0.0, WIDTH] {
        let nodes = NodeSet::Plane { axis: 0, at };
        solver.velocity_bcs.push(VelocityBc::normal(nodes, 0));
    }
    solver
        .velocity_bcs
        .push(VelocityBc::normal(NodeSet::Plane { axis: 1, at: 0.0 }, 1));
    let planes = ((HEIGHT + 2.0 * CELL - FREE_TOP) / CELL).round() as usize;
    for k in 0..=planes {
        let at = FREE_TOP + k as f64 * CELL;
        solver.velocity_bcs.push(VelocityBc {
            nodes: NodeSet::Plane { axis: 1, at },
            velocity: [None, Some(-RATE * at)],
            one_sided: false,
            history: None,
        });
    }
    solver.initialize();
    solver
}

/// Volume-weighted mean σ_yy of the points `test` and the RMS deviation from it [Pa].
fn mean_and_spread(solver: &Solver<2>, test: &[usize]) -> (f64, f64) {
    let p = &solver.particles;
    let volume: f64 = test.iter().map(|&i| p.volume[i]).sum();
    let mean =
        |g: &dyn Fn(usize) -> f64| test.iter().map(|&i| g(i) * p.volume[i]).sum::<f64>() / volume;
    let sigma = mean(&|i| p.stress[i][(1, 1)]);
    let rms = mean(&|i| (p.stress[i][(1, 1)] - sigma).powi(2)).sqrt();
    (sigma, rms)
}

/// σ_yy of the driver after each of `records` − 1 steps of the exact discrete history.
fn drive(model: &AnyModel<f64>, records: usize) -> Vec<f64> {
    let times: Vec<f64> = (0..records).map(|n| n as f64 * DT).collect();
    let f_yy = (0..records)
        .map(|n| (1.0 - RATE * DT).powi(n as i32))
        .collect();
    let fixed = |v| Control::Kinematic(Ramp::constant(v));
    let path = LoadPath {
        controls: [
            [fixed(1.0), fixed(0.0), fixed(0.0)],
            [
                fixed(0.0),
                Control::Kinematic(Ramp::new(times.clone(), f_yy).unwrap()),
                fixed(0.0),
            ],
            [fixed(0.0), fixed(0.0), fixed(1.0)],
        ],
        times,
        temperature: Temperature::Adiabatic,
    };
    let records = driver::run(model, &path).unwrap_or_else(|e| panic!("driver: {e}"));
    records.iter().map(|r| r.sigma[(1, 1)]).collect()
}

/// The table of `runs`, one line per kernel.
pub fn table(runs: &[Crossing]) -> String {
    let mut s = String::from(
        "kernel            spread σ_yy: before / while crossing   error vs driver   \
         crossings   σ_yy end [MPa] (driver)   wall [s]\n",
    );
    for r in runs {
        let stop = match &r.failure {
            Some(e) => format!("   stopped: {e}"),
            None => String::new(),
        };
        s += &format!(
            "{:<16}  {:>17.2e} / {:<16.2e}   {:>15.2e}   {:>9}   {:>9.1} ({:.1})   {:>11.2}{stop}\n",
            r.kernel.name(),
            r.spread[0],
            r.spread[1],
            r.error,
            r.crossings,
            r.sigma_end / 1e6,
            r.driver_end / 1e6,
            r.wall_time
        );
    }
    s
}

/// Layers that cross a face y = k h below `FREE_TOP` by the end: those at
/// (k + 1/4) h with ln(1 + 1/(4k)) ≤ `STRAIN`, two points each.
fn expected_crossings() -> usize {
    let top = (FREE_TOP / CELL).round() as usize;
    let layers = (1..top)
        .filter(|&k| (1.0 + 0.25 / k as f64).ln() <= STRAIN)
        .count();
    2 * layers
}

/// Spread while crossing, and error against the driver, for a kernel free of the
/// cell-crossing error: 0.1 % and 1e-4. The first is far below any measured stress's
/// resolution (SHPB ±2-5 %) and 100 × below what linear MPM makes; the second is the
/// same-path bound of `tests/mpm_vs_driver.rs` (the driver's Newton tolerance and a
/// second-order averaging effect).
const CONSISTENT_SPREAD: f64 = 1e-3;
const CONSISTENT_ERROR: f64 = 1e-4;
/// The spread linear MPM must show while crossing: the error this case exists to show
/// (47 % in the 3-D block of `tests/mpm_vs_driver.rs`'s notes).
const LINEAR_SPREAD: f64 = 0.05;

/// The verify rows: the table printed; per kernel the crossings counted, the run
/// through, the spread and the error (asserted for linear, cpGIMP and CPDI, reported for
/// uGIMP, whose fixed domains overlap under compression and leave part of the error).
pub fn cases(materials: &Path, out: &mut Vec<Row>) {
    use ShapeFunction::{Linear, UGimp};
    let path = materials.join("42crmo4_qt660.toml");
    let model = load_material(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .model;
    let runs: Vec<Crossing> = ShapeFunction::ALL
        .iter()
        .map(|&k| compress(&model, k))
        .collect();
    eprint!(
        "Homogeneous compression across cell faces:\n{}",
        table(&runs)
    );
    for r in &runs {
        let name = |what: &str| format!("mpm/cell-crossing/{}-{what}", r.kernel.name());
        out.push(Row::holds(name("runs-through"), r.failure.is_none()));
        out.push(Row::absolute(
            name("points-crossed"),
            r.crossings as f64,
            expected_crossings() as f64,
            0.0,
        ));
        let spread = name("spread-while-crossing");
        let error = name("error-vs-driver");
        out.push(match r.kernel {
            Linear => Row::at_least(spread, r.spread[1], LINEAR_SPREAD),
            UGimp => Row::reported(spread, r.spread[1]),
            _ => Row::at_most(spread, r.spread[1], CONSISTENT_SPREAD),
        });
        out.push(match r.kernel {
            Linear | UGimp => Row::reported(error, r.error),
            _ => Row::at_most(error, r.error, CONSISTENT_ERROR),
        });
    }
}
