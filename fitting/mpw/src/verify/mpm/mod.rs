//! The thesis MPM verification benchmarks (moved out of the mpm-core library: they are
//! the application's catalogue, not the engine), each as a function that runs the case and returns
//! the measured numbers; `rows` turns them into `mpw verify` table rows (reduced
//! sizes unless `full`). The table runs once per CI run, as `mpw verify` (which fails on
//! any failing row); the modules' unit tests keep small checks of their own.

pub mod cell_crossing;
pub mod collision;
pub mod cook;
pub mod impact;
pub mod integrators;
pub mod rigid_contact;
pub mod taylor;
pub mod taylor_derivatives;
pub mod truss;
pub mod vibration;

use crate::verify::data::VerifyData;
use crate::verify::row::Row;
use crate::verify::Inputs;
use integrators::{Integrator, MassSpring};
use materials::{load_material, Material};
use mpm_core::solver::Scheme;
use std::path::Path;
use std::sync::Arc;

/// A material of the parameter folder `materials` (`mpw verify --data DIR`: DIR/materials).
fn material(materials: &Path, file: &str) -> Arc<dyn Material> {
    let path = materials.join(file);
    match load_material(&path) {
        Ok(m) => Arc::new(m.model),
        Err(e) => panic!(
            "{e} (the verification cases read their materials from DIR/materials of --data DIR)"
        ),
    }
}

/// The repository's parameter folder, for the modules' unit tests.
#[cfg(test)]
pub fn test_materials() -> std::path::PathBuf {
    crate::verify::data::VerifyData::repository().materials()
}

/// Run every MPM verification case with the materials and scenes of `data`; `full`
/// uses the thesis sizes where they differ.
pub fn rows(inputs: &Inputs) -> anyhow::Result<Vec<Row>> {
    Ok(cases(inputs.data, inputs.full))
}

fn cases(data: &VerifyData, full: bool) -> Vec<Row> {
    let materials = &data.materials();
    let mut out = Vec::new();

    // chapter 5: mass-spring, Δt = 0.1, t = 50
    let p = MassSpring::thesis();
    let drift = |s| {
        let h = p.integrate(s, 0.1, 500);
        h.last().unwrap().energy / h[0].energy - 1.0
    };
    out.push(Row::relative(
        "mpm/mass-spring/explicit-euler-energy-gain",
        drift(Integrator::ExplicitEuler),
        1.01f64.powi(500) - 1.0,
        1e-9,
    ));
    out.push(Row::relative(
        "mpm/mass-spring/implicit-euler-energy-loss",
        drift(Integrator::ImplicitEuler),
        1.01f64.powi(-500) - 1.0,
        1e-9,
    ));
    let lf = p
        .integrate(Integrator::Leapfrog, 0.1, 500)
        .iter()
        .map(|s| (s.energy / 0.5 - 1.0).abs())
        .fold(0.0, f64::max);
    out.push(Row::relative(
        "mpm/mass-spring/leapfrog-max-energy-deviation",
        lf,
        p.leapfrog_max_energy_deviation(0.1, 500),
        1e-9,
    ));

    // section 8.3: single material point
    let dt = 0.01591;
    let centred = vibration::single_particle(true, dt);
    let fine = vibration::single_particle(true, dt / 10.0);
    let off = vibration::single_particle(false, dt);
    out.push(Row::relative(
        "mpm/single-point/omega",
        centred.omega,
        2.0 * std::f64::consts::PI,
        0.005,
    ));
    let (coarse_ratio, fine_ratio) = (centred.energy_ratio, fine.energy_ratio);
    out.push(
        Row::holds(
            "mpm/single-point/USL-damping-falls-with-dt",
            fine_ratio > coarse_ratio,
        )
        .with_note(format!("energy ratio {coarse_ratio:.3} -> {fine_ratio:.3}")),
    );
    out.push(Row::at_most(
        "mpm/single-point/centred-shear-ratio",
        centred.shear_ratio,
        1e-12,
    ));
    out.push(
        Row::holds(
            "mpm/single-point/off-centre-spurious-shear",
            off.shear_ratio > 0.01,
        )
        .with_note(format!("shear ratio {:.3}", off.shear_ratio)),
    );

    // Bardenhagen's bar
    for (name, scheme) in [
        ("usl", Scheme::Usl),
        ("usf", Scheme::Usf),
        ("musl", Scheme::Musl),
    ] {
        let r = vibration::bar(scheme, 25);
        out.push(Row::relative(
            format!("mpm/bar/{name}/omega1"),
            r.omega,
            r.reference,
            0.01,
        ));
    }

    // section 8.4: Cook's membrane, convergence of u_y(A) with the points per cell
    let levels: &[usize] = if full {
        &cook::FULL_LEVELS
    } else {
        &cook::TEST_LEVELS
    };
    match cook::convergence(levels) {
        Ok(rows) => {
            eprint!("Cook's membrane (section 8.4):\n{}", cook::table(&rows));
            let u: Vec<f64> = rows.iter().map(|r| r.u_y).collect();
            for (k, r) in rows.iter().enumerate() {
                let n = r.level;
                // the wall time is in the table above, not in the row name: names stay
                // the same from run to run
                let name = format!("mpm/cook/n{n}/u_y");
                let note = |fall: f64| {
                    let (u_mm, points) = (r.u_y * 1e3, r.particles);
                    format!("u_y {u_mm:.3} mm ({points} points), falls by {fall:.3} mm")
                };
                if k > 0 {
                    // converges from above: u_y falls, and from the third level on by less
                    // than at the level before (two levels cannot show convergence)
                    let fall = (u[k - 1] - u[k]) * 1e3;
                    if k < 2 {
                        out.push(
                            Row::holds(format!("{name}: falls"), u[k] < u[k - 1])
                                .with_note(note(fall)),
                        );
                    } else {
                        let converging = u[k] < u[k - 1]
                            && (u[k] - u[k - 1]).abs() < (u[k - 1] - u[k - 2]).abs();
                        out.push(
                            Row::holds(format!("{name}: falls, less than before"), converging)
                                .with_note(note(fall)),
                        );
                    }
                }
                if k + 1 == rows.len() {
                    // the finest level against the thesis's own, unconverged run: a report
                    out.push(Row::info(
                        format!("mpm/cook/n{n}/u_y-vs-thesis-10.708mm"),
                        r.u_y,
                        cook::THESIS_U_Y,
                    ));
                }
                if k + 1 == rows.len() && k > 0 {
                    // the limit the two finest levels point to, against the FEM value
                    let (coarse, fine) = (u[k - 1], u[k]);
                    out.push(Row::relative(
                        format!("mpm/cook/n{}-n{n}/u_y-extrapolated-vs-FEM-10.6mm", n / 2),
                        cook::extrapolate(coarse, fine, cook::ORDER),
                        cook::FEM_U_Y,
                        cook::extrapolation_tolerance(coarse, fine),
                    ));
                }
                out.push(Row::at_most(
                    format!("mpm/cook/n{n}/steady-K-over-W_int"),
                    r.kinetic_ratio,
                    cook::STEADY_KINETIC,
                ));
                out.push(Row::at_most(
                    format!("mpm/cook/n{n}/steady-late-du-over-u"),
                    r.late_change,
                    cook::STEADY_CHANGE,
                ));
            }
        }
        Err(e) => out.push(Row::holds(format!("mpm/cook: {e}"), false)),
    }

    cook::mesh_cases(&mut out);

    // section 9.1: colliding disks (and spheres in full)
    for dx in [0.05, 0.0125] {
        let r = collision::collide::<2>(dx);
        if dx < 0.02 {
            out.push(Row::relative(
                format!("mpm/disks/dx{dx}/contact-start"),
                r.contact_time,
                r.geometric_time,
                0.05,
            ));
        } else {
            // the coarse grid shows the grid dependence: shared nodes make contact early
            out.push(
                Row::holds(
                    format!("mpm/disks/dx{dx}/contact-start-early (grid dependence)"),
                    r.contact_time < r.geometric_time,
                )
                .with_note(format!("contact at {:.3} s < t_a", r.contact_time)),
            );
        }
        out.push(Row::at_most(
            format!("mpm/disks/dx{dx}/momentum-drift"),
            r.momentum_drift,
            1e-12,
        ));
        out.push(Row::reported(
            format!("mpm/disks/dx{dx}/energy-ratio"),
            r.energy_ratio,
        ));
    }
    if full {
        for dx in [0.05, 0.025] {
            let r = collision::collide::<3>(dx);
            out.push(Row::relative(
                format!("mpm/spheres/dx{dx}/contact-start (t_a 1.845 s)"),
                r.contact_time,
                r.geometric_time,
                0.05,
            ));
            out.push(Row::at_most(
                format!("mpm/spheres/dx{dx}/momentum-drift"),
                r.momentum_drift,
                1e-12,
            ));
        }
    }

    // section 9.4: libra
    let per_edge = if full { 30 } else { 8 };
    let mut depths = Vec::new();
    for kappa in [1e2, 1e3] {
        match rigid_contact::libra(kappa, per_edge) {
            Ok(r) => {
                out.push(Row::relative(
                    format!("mpm/libra/kappa{kappa:.0e}/force"),
                    r.force,
                    1000.0,
                    0.02,
                ));
                depths.push(r.penetration);
            }
            Err(e) => out.push(Row::holds(
                format!("mpm/libra/kappa{kappa:.0e}: {e}"),
                false,
            )),
        }
    }
    if depths.len() == 2 {
        out.push(
            Row::holds(
                "mpm/libra/penetration-falls-with-kappa",
                depths[1] < depths[0],
            )
            .with_note(format!("{:.4} -> {:.4} m", depths[0], depths[1])),
        );
    }

    // section 9.5: inclined plate
    let (per_edge, t_end, cases): (usize, f64, Vec<(f64, f64)>) = if full {
        (
            10,
            7.0,
            [10.0, 45.0]
                .iter()
                .flat_map(|&g| [0.1, 0.2, 0.4, 1.0, 1.8].map(|m| (g, m)))
                .collect(),
        )
    } else {
        (
            5,
            5.0,
            vec![(10.0, 0.1), (10.0, 0.2), (45.0, 0.4), (45.0, 1.8)],
        )
    };
    for (gamma, mu) in cases {
        let name = format!("mpm/inclined-plate/gamma{gamma}/mu{mu}");
        match rigid_contact::inclined_plate(Scheme::Usl, gamma, mu, per_edge, t_end) {
            Ok(r) => {
                let slides = mu < gamma.to_radians().tan();
                let note = format!("slip {:.4} m, ratio/mu {:.3}", r.slip, r.max_ratio / mu);
                out.push(
                    Row::holds(format!("{name}/slides={slides}"), r.slides() == slides)
                        .with_note(note),
                );
                out.push(Row::at_most(
                    format!("{name}/ratio-minus-mu"),
                    r.max_ratio - mu,
                    1e-9 * mu,
                ));
            }
            Err(e) => out.push(Row::holds(format!("{name}: {e}"), false)),
        }
    }
    // Taylor bar, axisymmetric against a 3D quarter model (symmetry planes)
    taylor::cases(materials, full, &mut out);
    taylor_derivatives::cases(materials, full, &mut out);

    // section 9.2: plastic impact of a steel disk into a 6061-T6 target
    impact::cases(materials, full, &mut out);

    // section 10.2: the truss
    truss::cases(&data.scenes(), full, &mut out);
    // chapter 10: the cell-crossing error per kernel
    cell_crossing::cases(materials, &mut out);
    out
}
