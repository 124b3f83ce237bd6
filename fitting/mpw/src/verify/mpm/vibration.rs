//! Vibration benchmarks of section 8.3 and Bardenhagen (2002).
//!
//! - Single material point (table 8.1): one point of volume 1 m³ in a 1 m cell, E = 4π² Pa,
//!   ν = 0, ρ = 1 kg/m³, v0 = 0.1 m/s, nodes at x = 0 fixed. Reference frequency
//!   ω = √(E/ρ)/L = 2π rad/s (eq. 8.1). Placed at the cell centre the motion is uniaxial; on
//!   the cell edge (y = z = 0) the empty nodes shear the cell and σ_xy appears (figure 8.5).
//! - Continuum bar: L = 25 m, E = 100 Pa, ρ = 1 kg/m³, fixed at x = 0, initial velocity
//!   v0 sin(πx/2L), v0 = 0.1 m/s; first mode ω1 = π/(2L) √(E/ρ) (plane strain, ν = 0, one
//!   row of points at the centre line of one row of cells).

use materials::NeoHooke;
use mpm_core::boundary::{NodeSet, VelocityBc};
use mpm_core::discretize::{fill, Geometry};
use mpm_core::kinematics::Kinematics;
use mpm_core::solver::{Scheme, Settings, Solver};
use nalgebra::{SVector, Vector2, Vector3};
use std::f64::consts::PI;
use std::sync::Arc;

/// Angular frequency from the upward zero crossings of a sampled signal [rad/s].
pub fn frequency(t: &[f64], y: &[f64]) -> Option<f64> {
    let mut crossings = Vec::new();
    for k in 1..y.len() {
        if y[k - 1] < 0.0 && y[k] >= 0.0 {
            crossings.push(t[k - 1] + (t[k] - t[k - 1]) * (-y[k - 1]) / (y[k] - y[k - 1]));
        }
    }
    (crossings.len() >= 2).then(|| {
        let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
        2.0 * PI / period
    })
}

#[derive(Debug, Clone)]
pub struct SingleParticle {
    /// Measured angular frequency of v_x [rad/s].
    pub omega: f64,
    /// Energy K + W_int at the end over the initial energy.
    pub energy_ratio: f64,
    /// max |σ_xy| / max |σ_xx| over the run.
    pub shear_ratio: f64,
    /// The failure that ended the run early, if any (the off-centre point's cell shears
    /// until F inverts).
    pub failure: Option<mpm_core::SimulationError>,
}

/// Table 8.1 in 3D; `centered` places the point at (0.5, 0.5, 0.5), otherwise at
/// (0.5, 0, 0); `dt` [s], run to 10 s.
pub fn single_particle(centered: bool, dt: f64) -> SingleParticle {
    let e = 4.0 * PI * PI;
    let mut settings = Settings::<3>::new(Kinematics::Solid, 1.0);
    settings.thesis_scheme();
    settings.dt = Some(dt);
    let mut s = Solver::new(settings);
    let x = if centered {
        Vector3::new(0.5, 0.5, 0.5)
    } else {
        Vector3::new(0.5, 0.0, 0.0)
    };
    s.add_body(
        "point",
        Arc::new(NeoHooke::new(e, 0.0, 1.0)),
        &[(x, 1.0)],
        Vector3::new(0.1, 0.0, 0.0),
    );
    s.velocity_bcs
        .push(VelocityBc::fixed(NodeSet::Plane { axis: 0, at: 0.0 }));
    s.initialize();
    let (mut t, mut v) = (vec![0.0], vec![0.1]);
    let (mut sxx, mut sxy) = (0.0f64, 0.0f64);
    let e0 = s.energies.kinetic;
    let mut failure = None;
    while s.time < 10.0 - 0.5 * dt {
        if let Err(e) = s.step() {
            failure = Some(e);
            break;
        }
        t.push(s.time);
        v.push(s.particles.velocity[0][0]);
        sxx = sxx.max(s.particles.stress[0][(0, 0)].abs());
        sxy = sxy.max(s.particles.stress[0][(0, 1)].abs());
    }
    SingleParticle {
        omega: frequency(&t, &v).unwrap_or(f64::NAN),
        energy_ratio: (s.energies.kinetic + s.energies.internal) / e0,
        shear_ratio: sxy / sxx,
        failure,
    }
}

/// Energy history sample: t, kinetic, internal (stress work).
pub type EnergySample = (f64, f64, f64);

#[derive(Debug, Clone)]
pub struct BarResult {
    pub omega: f64,
    pub reference: f64,
    pub energy: Vec<EnergySample>,
}

/// Bardenhagen's bar with `cells` cells along its length and 2 points per cell, run for
/// three periods with Δt = 0.1 h/c.
pub fn bar(scheme: Scheme, cells: usize) -> BarResult {
    let (length, e, rho, v0) = (25.0, 100.0, 1.0, 0.1);
    let h = length / cells as f64;
    let mut settings = Settings::<2>::new(Kinematics::PlaneStrain, h);
    settings.scheme = scheme;
    settings.bulk_viscosity = None;
    settings.safety = 0.1;
    let mut s = Solver::new(settings);
    let shape = Geometry::Box {
        min: Vector2::new(0.0, 0.0),
        max: Vector2::new(length, h),
    };
    let points = fill(&shape, Vector2::new(h / 2.0, h), Kinematics::PlaneStrain);
    s.add_body(
        "bar",
        Arc::new(NeoHooke::new(e, 0.0, rho)),
        &points,
        SVector::zeros(),
    );
    for i in 0..s.particles.len() {
        let x = s.particles.position[i][0];
        s.particles.velocity[i][0] = v0 * (PI * x / (2.0 * length)).sin();
    }
    s.velocity_bcs
        .push(VelocityBc::fixed(NodeSet::Plane { axis: 0, at: 0.0 }));
    s.initialize();
    let reference = PI / (2.0 * length) * (e / rho).sqrt();
    let t_end = 3.0 * 2.0 * PI / reference;
    let (mut t, mut p) = (vec![0.0], vec![s.momentum()[0]]);
    let mut energy = vec![(0.0, s.energies.kinetic, 0.0)];
    while s.time < t_end {
        s.step().expect("bar run");
        t.push(s.time);
        p.push(s.momentum()[0]);
        energy.push((s.time, s.energies.kinetic, s.energies.internal));
    }
    BarResult {
        omega: frequency(&t, &p).unwrap_or(f64::NAN),
        reference,
        energy,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_particle_vibrates_at_the_analytic_frequency() {
        let dt = 0.01591;
        let r = single_particle(true, dt);
        assert!(r.failure.is_none(), "{:?}", r.failure);
        let omega = 2.0 * PI;
        assert!(
            (r.omega / omega - 1.0).abs() < 0.005,
            "omega {} vs {omega}",
            r.omega
        );
        assert!(
            r.shear_ratio < 1e-12,
            "centred point shows shear {}",
            r.shear_ratio
        );
        // USL dissipates, less with a smaller step
        let fine = single_particle(true, dt / 10.0);
        assert!(r.energy_ratio < 0.9, "USL energy ratio {}", r.energy_ratio);
        assert!(
            fine.energy_ratio > r.energy_ratio,
            "dt/10: {} vs {}",
            fine.energy_ratio,
            r.energy_ratio
        );
        // off-centre placement: spurious shear
        let off = single_particle(false, dt);
        assert!(
            off.shear_ratio > 0.01,
            "off-centre shear ratio {}",
            off.shear_ratio
        );
        eprintln!("centred: {r:?}\ndt/10: {fine:?}\noff-centre: {off:?}");
    }

    #[test]
    fn bar_first_mode_within_one_percent_for_every_scheme() {
        for scheme in [Scheme::Usl, Scheme::Usf, Scheme::Musl] {
            let r = bar(scheme, 25);
            let err = r.omega / r.reference - 1.0;
            assert!(
                err.abs() < 0.01,
                "{scheme:?}: omega {} vs {} ({err:+.2e})",
                r.omega,
                r.reference
            );
        }
    }
}
