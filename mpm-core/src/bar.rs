//! A rigid face at the end of a long elastic bar, the Kolsky bar as a 1D waveguide: the
//! bar is not discretized, it acts on the face through its impedance ("drive by
//! the incident pulse alone").
//!
//! With the bar axis e pointing from the bar into the specimen, a wave arriving at the
//! face with strain ε_in(t) (compression positive; the incident pulse shifted to the face,
//! zero for a transmitter bar) and the compressive force f that the specimen exerts on
//! the face, the face moves along e with
//!
//!   v = c0 (2 ε_in − f / (E_b A_b)) = 2 c0 ε_in − f / Z,   Z = E_b A_b / c0 [N s/m],
//!
//! the d'Alembert solution of the bar: a free end moves at 2 c0 ε_in, a fixed end carries
//! f = 2 Z c0 ε_in. The wave sent back into the bar has the strain
//! ε_out = f / (E_b A_b) − ε_in: the reflected pulse on the incident bar, the transmitted
//! pulse (ε_in = 0) on the transmitter bar. Units: SI (m, s, N).
//!
//! The force is taken at the start of the step and extrapolated over it through the
//! penalty springs in contact, of total stiffness k_c, whose points move along the axis
//! at the stiffness-weighted mean velocity v_s: f_{n+1} ≈ f_n + k_c (v − v_s) Δt. Then
//!
//!   v = (2 c0 ε_in − f_n/Z + (k_c Δt/Z) v_s) / (1 + k_c Δt/Z),
//!
//! backward Euler on the face's dashpot: stable for any penalty stiffness (the plain
//! explicit update needs k_c Δt / Z < 2, which a penalty stiff enough for contact
//! breaks), and exact when the face and the points move together (v = v_s).

use materials::signal::TimeSignal;
use nalgebra::SVector;

#[derive(Debug, Clone, PartialEq)]
pub struct BarEnd<const D: usize> {
    /// Unit axis from the bar into the specimen.
    pub axis: SVector<f64, D>,
    /// Axial stiffness E_b A_b of the bar [N].
    pub axial_stiffness: f64,
    /// Bar wave speed c0 [m/s].
    pub wave_speed: f64,
    /// Strain of the wave arriving at the face, compression positive [-]; `None` for a
    /// bar that carries no incoming wave (the transmitter bar).
    pub incoming: Option<TimeSignal<f64>>,
    /// Face displacement along the axis since t = 0 [m].
    pub displacement: f64,
    /// Face velocity along the axis over the last step [m/s].
    pub velocity: f64,
    /// Compressive face force of the last step [N].
    pub force: f64,
}

impl<const D: usize> BarEnd<D> {
    /// A face at rest on a bar of axial stiffness `axial_stiffness` [N] and wave speed
    /// `wave_speed` [m/s]; `axis` is normalized.
    pub fn new(
        axis: SVector<f64, D>,
        axial_stiffness: f64,
        wave_speed: f64,
        incoming: Option<TimeSignal<f64>>,
    ) -> Self {
        BarEnd {
            axis: axis.normalize(),
            axial_stiffness,
            wave_speed,
            incoming,
            displacement: 0.0,
            velocity: 0.0,
            force: 0.0,
        }
    }

    /// Impedance Z = E_b A_b / c0 [N s/m].
    pub fn impedance(&self) -> f64 {
        self.axial_stiffness / self.wave_speed
    }

    /// Incoming strain ε_in(t) [-].
    pub fn incoming_strain(&self, t: f64) -> f64 {
        self.incoming.as_ref().map_or(0.0, |s| s.at(t))
    }

    /// Outgoing strain ε_out = f / (E_b A_b) − ε_in at time `t`, with the last face force.
    pub fn outgoing_strain(&self, t: f64) -> f64 {
        self.force / self.axial_stiffness - self.incoming_strain(t)
    }

    /// One step from t to t + Δt under the compressive face force `force` [N] at t, with
    /// the penalty springs then in contact (module notes), u ← u + v Δt.
    pub fn advance(&mut self, t: f64, dt: f64, force: f64, springs: ContactSprings) {
        let z = self.impedance();
        let implicit = springs.stiffness * dt / z;
        self.force = force;
        self.velocity = (2.0 * self.wave_speed * self.incoming_strain(t + 0.5 * dt) - force / z
            + implicit * springs.velocity)
            / (1.0 + implicit);
        self.displacement += self.velocity * dt;
    }
}

/// The penalty springs between a face and the points pressing on it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactSprings {
    /// Total stiffness k_c [N/m].
    pub stiffness: f64,
    /// Stiffness-weighted mean velocity of the points along the face's axis, v_s [m/s].
    pub velocity: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector1;

    fn bar(incoming: Option<TimeSignal<f64>>) -> BarEnd<1> {
        // steel bar, 14 mm: E A = 210 GPa · 1.539e-4 m², c0 = 5172 m/s
        BarEnd::new(Vector1::new(1.0), 3.233e7, 5172.0, incoming)
    }

    #[test]
    fn a_free_end_moves_at_twice_the_particle_velocity_and_reflects_the_pulse() {
        let pulse = TimeSignal::new(vec![0.0, 1.0], vec![1e-3, 1e-3]).unwrap();
        let mut b = bar(Some(pulse));
        b.advance(0.0, 1e-7, 0.0, ContactSprings::default());
        assert_eq!(b.velocity, 2.0 * 5172.0 * 1e-3);
        assert_eq!(b.outgoing_strain(0.0), -1e-3); // tension comes back
    }

    #[test]
    fn a_face_on_a_spring_settles_where_the_bar_force_doubles() {
        // a specimen behind the face as a spring k: the face stops when k u = 2 Z c0 ε_in
        // (the reflected strain is then +ε_in), for a soft spring and for one so stiff
        // (k Δt / Z = 16) that the plain explicit update would diverge
        for k in [1e10, 1e13] {
            let pulse = TimeSignal::new(vec![0.0, 1.0], vec![1e-3, 1e-3]).unwrap();
            let mut b = bar(Some(pulse));
            let dt = 1e-8;
            for n in 0..20_000 {
                let f = k * b.displacement;
                let springs = ContactSprings {
                    stiffness: k,
                    velocity: 0.0,
                };
                b.advance(n as f64 * dt, dt, f, springs);
            }
            let f = k * b.displacement;
            assert!(
                (f / (2.0 * 3.233e7 * 1e-3) - 1.0).abs() < 1e-9,
                "k = {k:e}: {f}"
            );
            let springs = ContactSprings {
                stiffness: k,
                velocity: 0.0,
            };
            b.advance(0.0, dt, f, springs);
            assert!((b.outgoing_strain(0.0) - 1e-3).abs() < 1e-12);
        }
    }
}
