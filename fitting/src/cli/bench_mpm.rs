//! `mpw bench-mpm`: MPM throughput in particle-steps per second with 1 and 2 threads for
//! (a) a 3D Neo-Hooke block set spinning and (b) a 3D Johnson-Cook (OFHC copper) cylinder
//! compressed between two rigid platens with friction (≈ 64 000 points), plus the memory
//! per particle and where the time goes: the material updates are timed alone on the
//! final deformation gradients, the rest of a step is transfers (scatter, grid solve,
//! gather, contact).

use anyhow::Result;
use materials::Material;
use mpm_core::discretize::{fill, Shape};
use mpm_core::rigid::Table;
use mpm_core::{Kinematics, RigidBody, Settings, Solver};
use nalgebra::{SVector, Vector3};
use rayon::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Steps per measurement.
    #[arg(long, default_value_t = 100)]
    pub steps: usize,
    /// Material file of the compression case.
    #[arg(long, default_value = "data/materials/ofhc_copper.toml")]
    pub material: PathBuf,
}

/// (a): a 40 × 40 × 40 point Neo-Hooke block (steel-like) spinning about z.
fn block() -> Solver<3> {
    let mut s = Solver::new(Settings::<3>::new(Kinematics::Solid, 0.01));
    let points = fill(
        &Shape::Box {
            min: Vector3::zeros(),
            max: Vector3::repeat(0.2),
        },
        Vector3::repeat(0.005),
        Vector3::zeros(),
        Kinematics::Solid,
    );
    s.add_body(
        "block",
        Arc::new(materials::NeoHooke::new(200e9, 0.3, 7850.0)),
        &points,
        SVector::zeros(),
    );
    for i in 0..s.particles.len() {
        let x = s.particles.position[i] - Vector3::repeat(0.1);
        s.particles.velocity[i] = Vector3::new(-x[1], x[0], 0.0) * 200.0;
    }
    s
}

/// (b): a Ø10 × 10 mm cylinder between platens closing at 2 × 10 m/s, μ = 0.1.
fn compression(material: Arc<dyn Material>) -> Solver<3> {
    let (r, h) = (0.005, 0.01);
    let mut s = Solver::new(Settings::<3>::new(Kinematics::Solid, 0.000_461));
    let shape = Shape::Cylinder {
        start: Vector3::zeros(),
        end: Vector3::new(0.0, 0.0, h),
        radius: r,
    };
    let points = fill(
        &shape,
        Vector3::repeat(0.000_230_5),
        Vector3::zeros(),
        Kinematics::Solid,
    );
    s.add_body("cylinder", material, &points, SVector::zeros());
    let (kappa, mu) = (1e7, 0.1);
    let mut lower = RigidBody::half_space("lower", Vector3::zeros(), Vector3::z(), kappa, mu);
    lower.motion.translation = Some(Table {
        knots: vec![(0.0, Vector3::zeros()), (1.0, Vector3::new(0.0, 0.0, 10.0))],
    });
    let mut upper =
        RigidBody::half_space("upper", Vector3::new(0.0, 0.0, h), -Vector3::z(), kappa, mu);
    upper.motion.translation = Some(Table {
        knots: vec![
            (0.0, Vector3::zeros()),
            (1.0, Vector3::new(0.0, 0.0, -10.0)),
        ],
    });
    s.add_rigid_body(lower);
    s.add_rigid_body(upper);
    s
}

struct Measured {
    rate: f64,
    material_share: f64,
}

fn measure(
    make: &dyn Fn() -> Solver<3>,
    threads: usize,
    steps: usize,
) -> Result<(Measured, usize, String)> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let mut s = make();
    pool.install(move || {
        let ts = s.initialize();
        s.step()?; // warm-up (allocations)
        let start = Instant::now();
        for _ in 0..steps {
            s.step()?;
        }
        let total = start.elapsed().as_secs_f64();
        let n = s.particles.len();
        // the material updates alone, on the final F and history, same threads
        let block = &s.blocks[0];
        let start = Instant::now();
        for _ in 0..steps {
            let _: Vec<_> = s
                .particles
                .deformation
                .par_iter()
                .zip(block.state.par_iter())
                .map(|(f, st)| block.material.update(f, s.dt, st).map(|r| r.0[(0, 0)]))
                .collect();
        }
        let material = start.elapsed().as_secs_f64();
        Ok((
            Measured {
                rate: (n * steps) as f64 / total,
                material_share: material / total,
            },
            n,
            ts.to_string(),
        ))
    })
}

pub fn run(args: Args) -> Result<()> {
    let copper: Arc<dyn Material> = Arc::new(materials::load_material(&args.material)?.model);
    let cases: [(&str, Box<dyn Fn() -> Solver<3>>, f64); 2] = [
        ("(a) Neo-Hooke block", Box::new(block), 5e6),
        (
            "(b) JC cylinder between platens",
            Box::new(move || compression(copper.clone())),
            1.5e6,
        ),
    ];
    let bytes = mpm_core::Particles::<3>::BYTES_PER_PARTICLE
        + std::mem::size_of::<materials::State<f64>>()
        + mpm_core::solver::SCRATCH_BYTES_PER_PARTICLE;
    println!(
        "memory: {bytes} bytes per particle (particles, history, step scratch; grid not counted)"
    );
    println!(
        "{:<34} {:>9} {:>8} {:>16} {:>10} {:>10}",
        "case", "particles", "threads", "particle-steps/s", "material", "transfers"
    );
    for (name, make, target) in &cases {
        for threads in [1, 2] {
            let (m, n, ts) = measure(make.as_ref(), threads, args.steps)?;
            println!(
                "{name:<34} {n:>9} {threads:>8} {:>16.3e} {:>9.0}% {:>9.0}%{}",
                m.rate,
                100.0 * m.material_share,
                100.0 * (1.0 - m.material_share),
                if threads == 2 {
                    format!(
                        "  (target {target:.1e}: {})",
                        if m.rate >= *target { "met" } else { "NOT met" }
                    )
                } else {
                    String::new()
                }
            );
            if threads == 1 {
                println!("    {ts}");
            }
        }
    }
    Ok(())
}
