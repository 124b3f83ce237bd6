//! Taylor bar impact (Johnson & Cook 1983; DESIGN section 10): an OFHC copper bar
//! (Johnson-Cook, `data/materials/ofhc_copper.toml`), L0 = 25.4 mm long, D0 = 7.62 mm in
//! diameter, hits a frictionless rigid wall at 190 m/s. The wall is the grid plane z = 0
//! with a one-sided zero normal grid velocity (eq. 7.28): the bar slides freely along it
//! and may rebound from it (the length measured in the experiment is after the elastic
//! recovery).
//!
//! Two discretizations of the same problem, both with linear shape functions and MUSL:
//! - axisymmetric (r, z) with the hoop term (kinematics `Axisymmetric`);
//! - 3D quarter model: the quarter x > 0, y > 0 of the bar with the symmetry planes x = 0
//!   and y = 0 as grid planes with zero normal velocity. Both planes are grid lines, so
//!   the mirror symmetry is exact: the quarter gives the full bar's answer at a quarter of
//!   the cost.
//!
//! Measured when the bar has come to rest:
//! - final length L_f [m]: the top control point (the particle nearest the top of the
//!   axis) plus half its deformed extent along the axis, z + ½ s F_zz (s is the particle
//!   spacing), since the wall is at z = 0;
//! - footprint diameter D_f [m]: twice the largest radius r + ½ s (e_r · F e_r) over the
//!   particles of the bottom layer (those that started within one particle spacing of the
//!   wall), i.e. the outer edge of the impact face.
//!
//! Experiment (190 m/s, 295 K): L_f = 16.205 mm, D_f = 13.564 mm as tabulated from
//! Zerilli & Armstrong (1987, J. Appl. Phys. 61, 1816) in B. Banerjee's collection
//! github.com/bbanerjee/HighRateExptData, `TaylorData/DAT/CuZerilli.dat`. SI units.

use crate::verify::row::Row;
use materials::scalar::{c, Scalar};
use materials::Material;
use mpm_core::discretize::{fill, Geometry};
use mpm_core::failure::SimulationError;
use mpm_core::kinematics::Kinematics;
use mpm_core::results::largest;
use mpm_core::shape::ShapeFunction;
use mpm_core::solver::{Scheme, Settings, Solver};
use mpm_core::NodeSet;
use mpm_core::VelocityBc;
use nalgebra::{Matrix3, SVector};
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

/// Initial bar length [m].
pub const LENGTH: f64 = 0.0254;
/// Initial bar radius [m].
pub const RADIUS: f64 = 0.00381;
/// Impact velocity [m/s].
pub const VELOCITY: f64 = 190.0;
/// Experimental final length [m] (Zerilli & Armstrong 1987, see module docs).
pub const EXPERIMENT_LENGTH: f64 = 16.205e-3;
/// Experimental impact-face diameter [m] (same source).
pub const EXPERIMENT_FOOTPRINT: f64 = 13.564e-3;

/// Grid spacings whose particle spacing (dx/2) divides both R and L (R/3 = 1.27 mm), so the
/// discretized bar has exactly the bar's size: dx = 2.54 mm / k.
pub fn commensurate_spacing(k: usize) -> f64 {
    2.0 * RADIUS / 3.0 / k as f64
}

/// Spacing of the reduced test (k = 4: 12 particles across the radius) [m]. At k = 3
/// (0.847 mm) the impact-face diameters of the two models still differ by 1.6 %; from
/// k = 4 on they agree within 0.4 % (refinement table in the issue note).
pub const COARSE: f64 = 2.0 * RADIUS / 12.0;

/// Which discretization of the bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    Axisymmetric,
    QuarterSolid,
}

/// Final shape of one run and its history.
#[derive(Debug, Clone)]
pub struct TaylorResult {
    pub model: Model,
    /// Grid spacing [m].
    pub spacing: f64,
    pub particles: usize,
    pub steps: usize,
    /// Final length L_f [m].
    pub length: f64,
    /// Impact-face diameter D_f [m] (outer edge).
    pub footprint: f64,
    /// Diameter of the circle with the impact face's area [m].
    pub footprint_area: f64,
    /// |L(end) − L(end − 10 µs)| / L(end): how much the length still changes [-].
    pub length_change: f64,
    /// Largest α [-] and θ [K] over the bar at the end.
    pub max_alpha: f64,
    pub max_theta: f64,
    /// (t [s], L, D_f, D_A [m]) every microsecond.
    pub history: Vec<(f64, f64, f64, f64)>,
    /// Wall-clock time of the run [s].
    pub wall_time: f64,
}

/// What hits the wall: a material file of `data/materials/` and the impact speed [m/s].
#[derive(Debug, Clone, Copy)]
pub struct Impact {
    pub material: &'static str,
    pub velocity: f64,
}

/// The Taylor test of the module docs.
pub const COPPER: Impact = Impact {
    material: "ofhc_copper.toml",
    velocity: VELOCITY,
};

/// AISI 4340 at 12 m/s: the impact stress ρ c v ≈ 480 MPa is below the yield stress A =
/// 792 MPa, so the bar must stay elastic everywhere. It does not yet: the column next to
/// the axis yields (`refinement_rows`).
pub const ELASTIC_4340: Impact = Impact {
    material: "aisi_4340.toml",
    velocity: 12.0,
};

/// Run the bar to `end` [s] on a grid of `spacing` [m] with `per_cell` particles per cell
/// and direction, with shape functions `kernel` (points' domains the lattice cells).
pub fn taylor_bar(
    materials: &Path,
    (model, kernel): (Model, ShapeFunction),
    impact: Impact,
    spacing: f64,
    per_cell: usize,
    end: f64,
) -> Result<TaylorResult, SimulationError> {
    let s = spacing / per_cell as f64;
    match model {
        Model::Axisymmetric => {
            let material = super::material(materials, impact.material);
            let solver = axisymmetric_bar(material, kernel, impact.velocity, (spacing, s));
            run(model, solver, s, end)
        }
        Model::QuarterSolid => {
            let mut settings = Settings::<3>::new(Kinematics::Solid, spacing);
            settings.scheme = Scheme::Musl;
            settings.safety = 0.3;
            settings.shape_function = kernel;
            let mut solver = Solver::new(settings);
            let points: Vec<_> = fill(
                &Geometry::Cylinder {
                    start: SVector::<f64, 3>::zeros(),
                    end: SVector::<f64, 3>::new(0.0, 0.0, LENGTH),
                    radius: RADIUS,
                },
                SVector::repeat(s),
                Kinematics::Solid,
            )
            .into_iter()
            .filter(|(x, _)| x[0] > 0.0 && x[1] > 0.0)
            .collect();
            let bar = solver.add_body(
                "bar",
                super::material(materials, impact.material),
                &points,
                SVector::<f64, 3>::new(0.0, 0.0, -impact.velocity),
            );
            if kernel.needs_domains() {
                solver.set_half_size(bar, SVector::repeat(0.5 * s));
            }
            solver.velocity_bcs.push(VelocityBc::wall(2, 0.0, true));
            for axis in [0, 1] {
                solver
                    .velocity_bcs
                    .push(VelocityBc::normal(NodeSet::Below { axis, at: 0.0 }, axis));
            }
            run(model, solver, s, end)
        }
    }
}

/// The axisymmetric bar of `material` at `velocity` [m/s] towards the wall z = 0, on a
/// grid of `spacing` [m] with particles `s` [m] apart (the axis and the one-sided wall as
/// velocity conditions), ready to initialize.
pub fn axisymmetric_bar(
    material: Arc<dyn Material>,
    kernel: ShapeFunction,
    velocity: f64,
    (spacing, s): (f64, f64),
) -> Solver<2> {
    let mut settings = Settings::<2>::new(Kinematics::Axisymmetric, spacing);
    settings.scheme = Scheme::Musl;
    settings.safety = 0.3;
    settings.shape_function = kernel;
    let mut solver = Solver::new(settings);
    solver.velocity_bcs.push(VelocityBc::axis());
    let points = fill(
        &Geometry::Box {
            min: SVector::<f64, 2>::new(0.0, 0.0),
            max: SVector::<f64, 2>::new(RADIUS, LENGTH),
        },
        SVector::repeat(s),
        Kinematics::Axisymmetric,
    );
    let bar = solver.add_body(
        "bar",
        material,
        &points,
        SVector::<f64, 2>::new(0.0, -velocity),
    );
    if kernel.needs_domains() {
        solver.set_half_size(bar, SVector::repeat(0.5 * s));
    }
    solver.velocity_bcs.push(VelocityBc::wall(1, 0.0, true));
    solver
}

/// The particles that mark the bar's shape: the control particle nearest the top of the
/// axis and the bottom layer (those that start within one particle spacing `s` [m] of
/// the wall).
pub fn markers<const D: usize>(solver: &Solver<D>, s: f64) -> (usize, Vec<usize>) {
    let mut axis_top = SVector::<f64, D>::zeros();
    axis_top[D - 1] = LENGTH;
    let top = solver.nearest_particle(&axis_top);
    let bottom = (0..solver.particles.len())
        .filter(|&i| solver.particles.position[i][D - 1] < s)
        .collect();
    (top, bottom)
}

/// A point's position, F and volume, in any scalar (dual with the derivative pass).
pub type PointShape<T, const D: usize> = (SVector<T, D>, Matrix3<T>, T);

/// Final length, footprint diameter and area-equivalent footprint diameter of the current
/// state whose point i is `point(i)`; `bottom` are the particles of the bottom layer,
/// `top` the control particle, `s` the particle spacing, `copies` how many copies of the
/// model make the bar (1 or 4).
pub fn measure<T: Scalar, const D: usize>(
    point: impl Fn(usize) -> PointShape<T, D>,
    (top, bottom): (usize, &[usize]),
    s: f64,
    copies: f64,
) -> (T, T, T) {
    let axial = D - 1;
    let half = c::<T>(0.5 * s);
    let (x_top, f_top, _) = point(top);
    let length = x_top[axial] + half * f_top[(axial, axial)];
    let mut radius = T::zero();
    let mut area = T::zero();
    for &i in bottom {
        let (x, f, volume) = point(i);
        let r = (0..axial)
            .map(|k| x[k] * x[k])
            .fold(T::zero(), |a, b| a + b)
            .sqrt();
        // radial unit vector in the first D − 1 coordinates (the 3×3 F's indices)
        let e: [T; 2] = std::array::from_fn(|k| if k < axial { x[k] / r } else { T::zero() });
        let stretch = (0..axial)
            .flat_map(|a| (0..axial).map(move |b| (a, b)))
            .map(|(a, b)| e[a] * f[(a, b)] * e[b])
            .fold(T::zero(), |a, b| a + b);
        let edge = r + half * stretch;
        if edge.re() > radius.re() {
            radius = edge;
        }
        // the particle's share of the wall: its volume over its height s F_zz
        area += volume / (c::<T>(s) * f[(axial, axial)]);
    }
    (
        length,
        c::<T>(2.0) * radius,
        c::<T>(2.0) * (c::<T>(copies) * area / c::<T>(std::f64::consts::PI)).sqrt(),
    )
}

/// `measure` of the run's own state.
pub fn measure_real<const D: usize>(
    solver: &Solver<D>,
    marked: (usize, &[usize]),
    s: f64,
    copies: f64,
) -> (f64, f64, f64) {
    let p = &solver.particles;
    measure(
        |i| (p.position[i], p.deformation[i], p.volume[i]),
        marked,
        s,
        copies,
    )
}

fn run<const D: usize>(
    model: Model,
    mut solver: Solver<D>,
    s: f64,
    end: f64,
) -> Result<TaylorResult, SimulationError> {
    let started = Instant::now();
    let (top, bottom) = markers(&solver, s);
    solver.initialize();
    let sample = 1e-6;
    let mut history = vec![(0.0, 0.0, 0.0, 0.0)];
    let copies = if model == Model::QuarterSolid {
        4.0
    } else {
        1.0
    };
    let (l0, d0, a0) = measure_real(&solver, (top, &bottom), s, copies);
    history[0] = (0.0, l0, d0, a0);
    while solver.time < end - 0.5 * solver.dt {
        solver.step()?;
        if solver.time >= history.len() as f64 * sample - 0.5 * solver.dt {
            let (l, d, a) = measure_real(&solver, (top, &bottom), s, copies);
            history.push((solver.time, l, d, a));
        }
    }
    let (length, footprint, footprint_area) = measure_real(&solver, (top, &bottom), s, copies);
    let earlier = history
        .iter()
        .rev()
        .find(|h| h.0 <= solver.time - 10e-6 + 0.5 * sample)
        .map_or(l0, |h| h.1);
    Ok(TaylorResult {
        model,
        spacing: solver.settings.spacing[0],
        particles: solver.particles.len(),
        steps: solver.step,
        length,
        footprint,
        footprint_area,
        length_change: (length - earlier).abs() / length,
        max_alpha: largest(&solver.blocks[0], |st| st.alpha),
        max_theta: largest(&solver.blocks[0], |st| st.theta),
        history,
        wall_time: started.elapsed().as_secs_f64(),
    })
}

/// `mpw verify` rows: both models at dx = 0.635 mm (reduced) or 0.423 mm (full), to 80 µs.
/// The footprint compared is the area-equivalent diameter D_A; the outer-edge diameter D_f
/// is reported (in 3D it is set by single particles at the rim).
pub fn cases(materials: &Path, full: bool, out: &mut Vec<Row>) {
    let dx = if full {
        commensurate_spacing(6)
    } else {
        COARSE
    };
    let name = format!("mpm/taylor/dx{:.3}mm", dx * 1e3);
    let (axi, solid) = match (
        taylor_bar(
            materials,
            (Model::Axisymmetric, ShapeFunction::Linear),
            COPPER,
            dx,
            2,
            80e-6,
        ),
        taylor_bar(
            materials,
            (Model::QuarterSolid, ShapeFunction::Linear),
            COPPER,
            dx,
            2,
            80e-6,
        ),
    ) {
        (Ok(a), Ok(s)) => (a, s),
        (a, s) => {
            for e in [a.err(), s.err()].into_iter().flatten() {
                out.push(Row::holds(format!("{name}: {e}"), false));
            }
            return;
        }
    };
    for (label, r) in [("axi", &axi), ("3d-quarter", &solid)] {
        out.push(Row::relative(
            format!("{name}/final-length-{label} vs experiment 16.205 mm"),
            r.length,
            EXPERIMENT_LENGTH,
            0.1,
        ));
        out.push(Row::at_most(
            format!("{name}/{label}/length-change-last-10us (at rest)"),
            r.length_change,
            0.01,
        ));
        out.push(Row::info(
            format!(
                "{name}/footprint-D_A-{label} vs experiment (D_f {:.2} mm)",
                r.footprint * 1e3
            ),
            r.footprint_area,
            EXPERIMENT_FOOTPRINT,
        ));
    }
    out.push(Row::relative(
        format!("{name}/final-length 3d vs axi"),
        solid.length,
        axi.length,
        0.01,
    ));
    // 0.35 % apart with the fixed wall of eq. 7.28, 1.05 % with the one-sided wall and the
    // sub-cell-centre fill (3D cylinder +3.45 % mass), 0.57 % with the exact fill
    out.push(Row::relative(
        format!("{name}/footprint-D_A 3d vs axi"),
        solid.footprint_area,
        axi.footprint_area,
        0.01,
    ));
    refinement_rows(materials, out);
    kernel_rows(materials, out);
}

/// The axisymmetric copper bar with every domain kernel at 6 cells across the
/// radius against the experiment (the same 10 % as the linear rows), CPDI's final length
/// under refinement (3, 6, 12 cells: the second step at most half the first), and the
/// elastic 4340 bar's spurious yield on the axis column with CPDI at 12 cells (linear:
/// 2.3e-3).
fn kernel_rows(materials: &Path, out: &mut Vec<Row>) {
    let name = "mpm/taylor/kernels-axi";
    let bar = |kernel, n: usize, impact, end| {
        taylor_bar(
            materials,
            (Model::Axisymmetric, kernel),
            impact,
            RADIUS / n as f64,
            2,
            end,
        )
    };
    let at_six = |kernel: ShapeFunction, length: f64| {
        Row::relative(
            format!(
                "{name}/{}/n6/final-length vs experiment 16.205 mm",
                kernel.name()
            ),
            length,
            EXPERIMENT_LENGTH,
            0.1,
        )
    };
    for kernel in [
        ShapeFunction::UGimp,
        ShapeFunction::CpGimp,
        ShapeFunction::CpGimpAnalytic,
    ] {
        match bar(kernel, 6, COPPER, 80e-6) {
            Ok(r) => out.push(at_six(kernel, r.length)),
            Err(e) => out.push(Row::holds(
                format!("{name}/{}/n6: {e}", kernel.name()),
                false,
            )),
        }
    }
    let lengths: Result<Vec<f64>, _> = [3, 6, 12]
        .iter()
        .map(|&n| bar(ShapeFunction::Cpdi, n, COPPER, 80e-6).map(|r| r.length))
        .collect();
    match lengths {
        Ok(l) => {
            out.push(at_six(ShapeFunction::Cpdi, l[1]));
            out.extend(Row::convergence(
                &format!("{name}/cpdi/n3-6-12/final-length"),
                [l[0], l[1], l[2]],
                0.5,
            ));
            out.push(Row::relative(
                format!("{name}/cpdi/n12/final-length vs experiment 16.205 mm"),
                l[2],
                EXPERIMENT_LENGTH,
                0.1,
            ));
        }
        Err(e) => out.push(Row::holds(format!("{name}/cpdi refinement: {e}"), false)),
    }
    match bar(ShapeFunction::Cpdi, 12, ELASTIC_4340, 40e-6) {
        Ok(r) => out.push(Row::info(
            format!("{name}/cpdi/elastic-4340-12m_s/max-alpha at 12 cells across R (must be 0)"),
            r.max_alpha,
            0.0,
        )),
        Err(e) => out.push(Row::holds(format!("{name}/cpdi/elastic: {e}"), false)),
    }
}

/// Reported, not asserted (both open questions: docs/verification.md): the copper bar's final length at 3, 6
/// and 12 cells across the radius with its successive differences, and the largest α of
/// the elastic 4340 bar (must be 0) at 6 and 12 cells.
fn refinement_rows(materials: &Path, out: &mut Vec<Row>) {
    let name = "mpm/taylor/refinement-axi";
    let lengths: Result<Vec<f64>, _> = [3, 6, 12]
        .iter()
        .map(|&n| {
            taylor_bar(
                materials,
                (Model::Axisymmetric, ShapeFunction::Linear),
                COPPER,
                RADIUS / n as f64,
                2,
                80e-6,
            )
            .map(|r| r.length)
        })
        .collect();
    match lengths {
        Ok(l) => out.push(
            Row::info(
                format!("{name}/L_f at 12 against 6 cells across R (gap: the differences grow again at 18 and 24 cells, docs/verification.md)"),
                l[2],
                l[1],
            )
            .with_note(format!(
                "L_f at 3, 6, 12 cells: {:.3}, {:.3}, {:.3} mm, differences {:+.3}, {:+.3} mm",
                l[0] * 1e3,
                l[1] * 1e3,
                l[2] * 1e3,
                (l[1] - l[0]) * 1e3,
                (l[2] - l[1]) * 1e3,
            )),
        ),
        Err(e) => out.push(Row::holds(format!("{name}: {e}"), false)),
    }
    for n in [6, 12] {
        match taylor_bar(materials, (Model::Axisymmetric, ShapeFunction::Linear), ELASTIC_4340, RADIUS / n as f64, 2, 40e-6) {
            Ok(r) => out.push(Row::info(
                format!("{name}/elastic-4340-12m_s/max-alpha at {n} cells across R (must be 0: gap, on the axis column)"),
                r.max_alpha,
                0.0,
            )),
            Err(e) => out.push(Row::holds(format!("{name}/elastic n={n}: {e}"), false)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verify::mpm::test_materials;

    /// Coarse bars (dx = 0.635 mm, 12 particles across the radius) to 80 µs: both models
    /// come to rest and agree with each other; the measurement at t = 0 is the bar.
    #[test]
    fn coarse_axisymmetric_and_quarter_bars_agree() {
        let axi = taylor_bar(
            &test_materials(),
            (Model::Axisymmetric, ShapeFunction::Linear),
            COPPER,
            COARSE,
            2,
            80e-6,
        )
        .unwrap();
        let solid = taylor_bar(
            &test_materials(),
            (Model::QuarterSolid, ShapeFunction::Linear),
            COPPER,
            COARSE,
            2,
            80e-6,
        )
        .unwrap();
        for r in [&axi, &solid] {
            eprintln!(
                "{:?}: {} particles, L_f = {:.3} mm, D_f = {:.3} mm, D_A = {:.3} mm, change {:.2e}, {:.1} s",
                r.model,
                r.particles,
                r.length * 1e3,
                r.footprint * 1e3,
                r.footprint_area * 1e3,
                r.length_change,
                r.wall_time
            );
            // the measurement at t = 0 is the bar itself (exact for L0; D0 to the lattice)
            assert!((r.history[0].1 - LENGTH).abs() < 1e-9 * LENGTH);
            assert!((r.history[0].2 - 2.0 * RADIUS).abs() < 0.05 * 2.0 * RADIUS);
            assert!(r.length_change < 1e-2, "{}", r.length_change);
        }
        let diff = |a: f64, b: f64| (a - b).abs() / b;
        eprintln!(
            "difference: length {:.4}, footprint {:.4}, area footprint {:.4}",
            diff(solid.length, axi.length),
            diff(solid.footprint, axi.footprint),
            diff(solid.footprint_area, axi.footprint_area)
        );
        assert!(diff(solid.length, axi.length) <= 0.01);
        // 0.57 % with the exact fill (1.05 % with the sub-cell-centre fill)
        assert!(diff(solid.footprint_area, axi.footprint_area) <= 0.01);
    }
}

/// The refinement tables of the issue note: `cargo test --profile ci -p mpm-core
/// taylor_refinement -- --ignored --nocapture` (several minutes).
#[cfg(test)]
mod refinement {
    use super::*;
    use crate::verify::mpm::test_materials;

    #[test]
    #[ignore]
    fn taylor_refinement() {
        let ks: &[(Model, &[usize])] = &[
            (Model::Axisymmetric, &[3, 4, 6, 8, 10]),
            (Model::QuarterSolid, &[3, 4, 5, 6]),
        ];
        println!("model | dx mm | particles | L_f mm | D_f mm | D_A mm | change | wall s");
        for (model, ks) in ks {
            for &k in *ks {
                let r = taylor_bar(
                    &test_materials(),
                    (*model, ShapeFunction::Linear),
                    COPPER,
                    commensurate_spacing(k),
                    2,
                    80e-6,
                )
                .unwrap();
                println!(
                    "{:?} | {:.4} | {} | {:.3} | {:.3} | {:.3} | {:.1e} | {:.1}",
                    r.model,
                    r.spacing * 1e3,
                    r.particles,
                    r.length * 1e3,
                    r.footprint * 1e3,
                    r.footprint_area * 1e3,
                    r.length_change,
                    r.wall_time
                );
            }
        }
    }
}
