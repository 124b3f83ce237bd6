//! Homogeneous compression across cell faces, per kernel (issue 10): the test that linear
//! MPM fails (tests/mpm_vs_driver.rs notes: with layers of points crossing a cell face at
//! once the σ_zz spread jumps from 0.01 % to 47 %), run with every shape function and
//! compared with the single-point driver.
//!
//! A 6 × 6 × 4 mm block of 42CrMo4 QT660 (Johnson-Cook, adiabatic), 1 mm cells, 2 points
//! per cell and direction (1152 points), free lateral faces, compressed along z at a
//! constant true rate of 1000 1/s to a true strain of 0.25: the nodes at and below z = 0
//! keep v_z = 0, those at and above z = H0 = 4 mm get v_z = −ε̇ H0 (material flows through
//! that fixed node plane, the field v_z = −ε̇ z). The points start with the elastic
//! solution v = ε̇ (ν x, ν y, −z). Layers cross the faces z = 1 and 3 mm and the outer
//! columns x, y = ±3 mm. Wholly node-set conditions (everything beyond a plane), so a
//! domain reaching past the block's bottom meets the same condition as its face.
//!
//! Measured: the RMS deviation of the points' σ_zz from the mean over |mean σ_zz|, largest
//! once the flow has settled (mean α > 0.05), and the mean σ_zz at the end against the
//! uniaxial driver (σ_xx = σ_yy = 0) run on the MPM's own F_zz history, one step per step.

use materials::driver::{self, Control, LoadPath, Ramp, Temperature};
use materials::AnyModel;
use mpm_core::discretize::{fill, Shape};
use mpm_core::shape::ShapeFunction;
use mpm_core::{Kinematics, NodeSet, Settings, SimulationError, Solver, VelocityBc};
use nalgebra::Vector3;
use std::sync::Arc;

const CELL: f64 = 1e-3;
const HALF_WIDTH: f64 = 3e-3;
const HEIGHT: f64 = 4e-3;
const RATE: f64 = 1000.0;
const STRAIN: f64 = 0.25;
const NU: f64 = 0.3;
/// Mean α beyond which the flow has settled (the yield ringing has died out).
const SETTLED_ALPHA: f64 = 0.05;

/// One kernel's run.
#[derive(Debug, Clone)]
pub struct Crossing {
    pub kernel: ShapeFunction,
    /// Largest RMS σ_zz spread over |mean σ_zz| once settled [-].
    pub spread: f64,
    /// Mean σ_zz at the end against the uniaxial driver, relative [-].
    pub driver_error: f64,
    /// Mean σ_zz at the end [Pa].
    pub sigma_zz: f64,
    pub wall_time: f64,
}

/// Compress the block with `kernel` and compare with the driver.
pub fn compress(model: &AnyModel<f64>, kernel: ShapeFunction) -> Result<Crossing, SimulationError> {
    let started = std::time::Instant::now();
    let mut solver = block(model, kernel);
    solver.initialize();
    let (mut times, mut f_zz) = (vec![0.0], vec![1.0]);
    let mut spread: f64 = 0.0;
    let mut sigma_zz = 0.0;
    while solver.time < STRAIN / RATE - 0.5 * solver.dt {
        solver.step()?;
        let (mean_f, mean_sigma, rms, alpha) = means(&solver);
        times.push(solver.time);
        f_zz.push(mean_f);
        sigma_zz = mean_sigma;
        if alpha > SETTLED_ALPHA {
            spread = spread.max(rms / mean_sigma.abs());
        }
    }
    let zero = || Control::Kinematic(Ramp::constant(0.0));
    let free = || Control::Stress(Ramp::constant(0.0));
    let path = LoadPath {
        controls: [
            [free(), zero(), zero()],
            [zero(), free(), zero()],
            [
                zero(),
                zero(),
                Control::Kinematic(Ramp::new(times.clone(), f_zz).expect("increasing times")),
            ],
        ],
        times,
        temperature: Temperature::Adiabatic,
    };
    let records = driver::run(model, &path).expect("the driver follows the MPM's history");
    let reference = records.last().expect("a record per step").sigma[(2, 2)];
    Ok(Crossing {
        kernel,
        spread,
        driver_error: (sigma_zz / reference - 1.0).abs(),
        sigma_zz,
        wall_time: started.elapsed().as_secs_f64(),
    })
}

/// The block, its initial velocity field and the two node-set conditions.
fn block(model: &AnyModel<f64>, kernel: ShapeFunction) -> Solver<3> {
    let mut settings = Settings::<3>::new(Kinematics::Solid, CELL);
    settings.bulk_viscosity = None;
    settings.shape_function = kernel;
    let mut solver = Solver::new(settings);
    let s = 0.5 * CELL;
    let shape = Shape::Box {
        min: Vector3::new(-HALF_WIDTH, -HALF_WIDTH, 0.0),
        max: Vector3::new(HALF_WIDTH, HALF_WIDTH, HEIGHT),
    };
    let points = fill(&shape, Vector3::repeat(s), Kinematics::Solid);
    let body = solver.add_body("block", Arc::new(model.clone()), &points, Vector3::zeros());
    if kernel.needs_domains() {
        solver.set_half_size(body, Vector3::repeat(0.5 * s));
    }
    for (x, v) in solver
        .particles
        .position
        .iter()
        .zip(solver.particles.velocity.iter_mut())
    {
        *v = Vector3::new(NU * x[0], NU * x[1], -x[2]) * RATE;
    }
    for (nodes, v_z) in [
        (NodeSet::Below { axis: 2, at: 0.0 }, 0.0),
        (
            NodeSet::Above {
                axis: 2,
                at: HEIGHT,
            },
            -RATE * HEIGHT,
        ),
    ] {
        solver.velocity_bcs.push(VelocityBc {
            nodes,
            velocity: [None, None, Some(v_z)],
            one_sided: false,
            history: None,
        });
    }
    solver
}

/// Volume-weighted means F_zz, σ_zz, the RMS deviation of σ_zz [Pa] and mean α.
fn means(s: &Solver<3>) -> (f64, f64, f64, f64) {
    let p = &s.particles;
    let volume: f64 = p.volume.iter().sum();
    let mean =
        |g: &dyn Fn(usize) -> f64| (0..p.len()).map(|i| g(i) * p.volume[i]).sum::<f64>() / volume;
    let sigma = mean(&|i| p.stress[i][(2, 2)]);
    let rms = mean(&|i| (p.stress[i][(2, 2)] - sigma).powi(2)).sqrt();
    let alpha = mean(&|i| s.blocks[0].state[i].alpha);
    (mean(&|i| p.deformation[i][(2, 2)]), sigma, rms, alpha)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table per kernel (about a minute; `cargo test --profile ci -p fitting
    /// kernel_table -- --ignored --nocapture`). Not a verify row yet: every kernel fails
    /// it here (issue 10 note: the domain kernels lose homogeneity at the top layer even
    /// in an elastic Neo-Hooke block, 4 % after 1 % strain, with one thread too).
    #[test]
    #[ignore]
    fn kernel_table() {
        let materials = crate::mpm_verify::test_materials();
        let model = materials::load_material(materials.join("42crmo4_qt660.toml"))
            .unwrap()
            .model;
        println!("kernel | RMS spread settled | mean σ_zz vs driver | σ_zz MPa | wall s");
        for kernel in ShapeFunction::NAMES.map(|n| n.parse::<ShapeFunction>().unwrap()) {
            match compress(&model, kernel) {
                Ok(r) => println!(
                    "{} | {:.3e} | {:.3e} | {:.1} | {:.1}",
                    kernel.name(),
                    r.spread,
                    r.driver_error,
                    r.sigma_zz * 1e-6,
                    r.wall_time
                ),
                Err(e) => println!("{}: {e}", kernel.name()),
            }
        }
    }
}
