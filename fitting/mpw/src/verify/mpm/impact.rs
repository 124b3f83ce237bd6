//! Plastic impact of a steel disk into an aluminium target (thesis section 9.2, tables
//! 9.1-9.3; Sulsky et al. 1995, Coetzee 2004; experiments Trucano & Grady 1985), plane
//! strain, standard MPM contact through the shared grid velocity (section 9.1), no damping.
//!
//! Stated in the thesis and used here:
//! - bullet: AISI 52-100 steel, Neo-Hooke E = 200 GPa, ν = 0.3, ρ = 7850 kg/m³ (table 9.1,
//!   `data/materials/aisi_52100.toml`), a disk of 2836 material points in the thesis (the
//!   exact fill adds the rim's cut cells: 2928);
//! - target: 6061-T6 aluminium, perfectly plastic J2, E = 78.2 GPa, ν = 0.3,
//!   ρ = 2700 kg/m³, τ0 = 300 MPa, η = 0 (table 9.3, h = 0.9 Pa taken as 0,
//!   `data/materials/al6061_t6.toml`), four material points per cell initially;
//! - rolling (zero normal velocity) conditions on the target's sides and bottom;
//! - grid dx = 60 mm / n with n = 50, 80, 150, 200 (table 9.2: n × dx = 0.06 m for every
//!   row, so the target is 60 mm wide); the NoMP of table 9.2 minus the 2836 disk points
//!   give 4 × n × m target points with m = 33, 53, 100, 133 = ⌊40 mm / dx⌋ cells, so the
//!   target is ⌊40 mm / dx⌋ cells deep;
//! - run to 80 µs, penetration depth stops changing after 40 µs.
//!
//! Not in the thesis text (figure 9.5 is an image), chosen here:
//! - disk radius R = 3.175 mm (the 6.35 mm spheres of Trucano & Grady); with 2836 points
//!   this is a point spacing of R √(π/2836) = 0.106 mm;
//! - impact velocity 1160 m/s, straight down the target's centre line;
//! - the disk starts touching the target surface (t = 0 is the impact);
//! - the target's points are on the regular 2 × 2 sub-cell lattice (not Gauss points).
//!
//! Measured: penetration depth d(t) = y_tip(0) − y_tip(t) [m] with the bullet tip
//! y_tip = min y of the disk's points − s/2 (y_tip(0) is the target surface), and the bullet's kinetic energy ½ Σ m v² [J per metre of
//! thickness]. SI units.

use crate::verify::row::Row;
use mpm_core::discretize::{fill, Geometry};
use mpm_core::failure::SimulationError;
use mpm_core::kinematics::Kinematics;
use mpm_core::parallel::fixed_sum;
use mpm_core::solver::{Scheme, Settings, Solver};
use mpm_core::{NodeSet, VelocityBc};
use nalgebra::SVector;
use std::path::Path;
use std::time::Instant;

/// Target width [m] (n × dx of table 9.2).
pub const WIDTH: f64 = 0.06;
/// Nominal target depth [m]; the model uses ⌊DEPTH / dx⌋ whole cells.
pub const DEPTH: f64 = 0.04;
/// Disk radius [m] (chosen, see module docs).
pub const RADIUS: f64 = 3.175e-3;
/// Disk material points (section 9.2).
pub const DISK_POINTS: usize = 2836;
/// Impact velocity [m/s] (chosen, see module docs).
pub const VELOCITY: f64 = 1160.0;

#[derive(Debug, Clone)]
pub struct ImpactResult {
    /// Grid spacing [m].
    pub spacing: f64,
    pub disk_points: usize,
    pub particles: usize,
    /// (t [s], penetration depth [m], bullet kinetic energy [J/m]) every microsecond.
    pub history: Vec<(f64, f64, f64)>,
    pub wall_time: f64,
}

impl ImpactResult {
    /// The history sample nearest to `t` [s].
    pub fn at(&self, t: f64) -> (f64, f64, f64) {
        *self
            .history
            .iter()
            .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
            .unwrap()
    }
}

/// Run the impact to `end` [s] on a grid of `n` cells across the 60 mm target.
pub fn plastic_impact(
    materials: &Path,
    n: usize,
    end: f64,
) -> Result<ImpactResult, SimulationError> {
    let started = Instant::now();
    let dx = WIDTH / n as f64;
    let surface = (DEPTH / dx + 1e-9).floor() * dx;
    let mut settings = Settings::<2>::new(Kinematics::PlaneStrain, dx);
    settings.scheme = Scheme::Musl;
    settings.safety = 0.3;
    let mut solver = Solver::new(settings);
    let target = fill(
        &Geometry::Box {
            min: SVector::<f64, 2>::zeros(),
            max: SVector::<f64, 2>::new(WIDTH, surface),
        },
        SVector::repeat(dx / 2.0),
        Kinematics::PlaneStrain,
    );
    solver.add_body(
        "target",
        super::material(materials, "al6061_t6.toml"),
        &target,
        SVector::zeros(),
    );
    let s = RADIUS * (std::f64::consts::PI / DISK_POINTS as f64).sqrt();
    let center = SVector::<f64, 2>::new(WIDTH / 2.0, surface + RADIUS);
    let disk = fill(
        &Geometry::Ball {
            center,
            radius: RADIUS,
        },
        SVector::repeat(s),
        Kinematics::PlaneStrain,
    );
    let bullet = solver.add_body(
        "bullet",
        super::material(materials, "aisi_52100.toml"),
        &disk,
        SVector::<f64, 2>::new(0.0, -VELOCITY),
    );
    for (axis, at, below) in [(0, 0.0, true), (0, WIDTH, false), (1, 0.0, true)] {
        let nodes = if below {
            NodeSet::Below { axis, at }
        } else {
            NodeSet::Above { axis, at }
        };
        solver.velocity_bcs.push(VelocityBc::normal(nodes, axis));
    }
    solver.initialize();
    let range = solver.blocks[bullet].range.clone();
    let sample = |solver: &Solver<2>| {
        let p = &solver.particles;
        let tip = range
            .clone()
            .map(|i| p.position[i][1])
            .fold(f64::INFINITY, f64::min)
            - 0.5 * s;
        let kinetic = fixed_sum(range.len(), 0.0, |k| {
            let i = range.start + k;
            0.5 * p.mass[i] * p.velocity[i].norm_squared()
        });
        (solver.time, tip, kinetic)
    };
    let mut history = vec![sample(&solver)];
    let tip0 = history[0].1;
    while solver.time < end - 0.5 * solver.dt {
        solver.step()?;
        if solver.time >= history.len() as f64 * 1e-6 - 0.5 * solver.dt {
            history.push(sample(&solver));
        }
    }
    for h in &mut history {
        h.1 = tip0 - h.1;
    }
    Ok(ImpactResult {
        spacing: dx,
        disk_points: disk.len(),
        particles: solver.particles.len(),
        history,
        wall_time: started.elapsed().as_secs_f64(),
    })
}

/// `mpw verify` rows: n = 50 (reduced) or n = 80 (full), to 80 µs.
pub fn cases(materials: &Path, full: bool, out: &mut Vec<Row>) {
    let n = if full { 80 } else { 50 };
    let name = format!("mpm/plastic-impact/n{n}");
    match plastic_impact(materials, n, 80e-6) {
        Ok(r) => {
            let k0 = r.history[0].2;
            // the thesis shows these only in its figure: reported, not asserted
            for t in [10e-6, 20e-6, 40e-6, 80e-6] {
                let (_, d, k) = r.at(t);
                let us = t * 1e6;
                out.push(Row::reported(format!("{name}/depth at {us:.0} µs [m]"), d));
                out.push(Row::reported(
                    format!("{name}/bullet K/K0 at {us:.0} µs"),
                    k / k0,
                ));
            }
            let (d40, d_end) = (r.at(40e-6).1, r.history.last().unwrap().1);
            out.push(Row::at_most(
                format!("{name}/depth-change-40us-to-end (thesis: none)"),
                (d_end - d40).abs() / d_end,
                0.02,
            ));
            out.push(Row::at_most(
                format!("{name}/bullet-K-at-40us/K0 (thesis: almost all transferred)"),
                r.at(40e-6).2 / k0,
                0.05,
            ));
        }
        Err(e) => out.push(Row::holds(format!("{name}: {e}"), false)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// n = 50 (dx = 1.2 mm, the coarsest row of table 9.2) to 80 µs: the target has the
    /// table's point count, the depth changes by less than 2 % after 40 µs and the bullet
    /// has lost more than 95 % of its kinetic energy by then.
    #[test]
    fn coarse_impact_depth_settles_by_40_us() {
        let r = plastic_impact(&crate::verify::mpm::test_materials(), 50, 80e-6).unwrap();
        for t in [0.0, 10e-6, 20e-6, 40e-6, 60e-6, 80e-6] {
            let (t, d, k) = r.at(t);
            eprintln!(
                "t = {:.0} µs: depth {:.3} mm, K = {:.4e} J/m",
                t * 1e6,
                d * 1e3,
                k
            );
        }
        eprintln!("{} disk points, {:.1} s", r.disk_points, r.wall_time);
        // table 9.2, n = 50: 9436 points in all, 2836 of them in the disk
        assert_eq!(r.particles - r.disk_points, 9436 - 2836);
        // the 2836 sub-cells of spacing s = R √(π/2836) whose centres lie inside, plus the
        // cut cells of the rim whose centres lie outside (the fill keeps every piece of
        // the disk): at most the 2πR/s = 189 cells the rim crosses
        let rim = 2.0 * std::f64::consts::PI * (2836.0 / std::f64::consts::PI).sqrt();
        assert!(r.disk_points >= 2836 && r.disk_points as f64 <= 2836.0 + rim);
        let (d40, d_end) = (r.at(40e-6).1, r.history.last().unwrap().1);
        assert!((d_end - d40).abs() <= 0.02 * d_end, "{d40} -> {d_end}");
        let k0 = r.history[0].2;
        assert!(r.at(40e-6).2 <= 0.05 * k0, "{}", r.at(40e-6).2 / k0);
    }
}
