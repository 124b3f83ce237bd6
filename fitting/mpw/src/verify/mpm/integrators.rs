//! Time integrators of thesis chapter 5 on the mass-spring problem m ẍ = −k x.
//!
//! - explicit Euler, eq. 5.1-5.2: x = x_n + v_n Δt, v = v_n + a_n Δt;
//! - leapfrog, eq. 5.3-5.4: v_{n+1/2} = v_{n−1/2} + a_n Δt, x = x_n + v_{n+1/2} Δt,
//!   started with v_{−1/2} = v_0 − a_0 Δt/2;
//! - implicit Euler, eq. 5.7: v = (1 + kΔt²/m)⁻¹ (v_n − kΔt/m x_n), x = x_n + v Δt.
//!
//! The energy E = ½ m v² + ½ k x² [J] is conserved by the exact solution. For the leapfrog
//! the full-step velocity is taken as the mean of the neighbouring half steps.

/// A mass on a linear spring: mass m [kg], stiffness k [N/m], start x0 [m], v0 [m/s].
#[derive(Debug, Clone, Copy)]
pub struct MassSpring {
    pub mass: f64,
    pub stiffness: f64,
    pub x0: f64,
    pub v0: f64,
}

/// The three integrators compared in chapter 5.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integrator {
    ExplicitEuler,
    Leapfrog,
    ImplicitEuler,
}

/// Position, velocity and energy at one instant.
#[derive(Debug, Clone, Copy)]
pub struct SpringState {
    pub t: f64,
    pub x: f64,
    pub v: f64,
    pub energy: f64,
}

impl MassSpring {
    /// The chapter 5 problem: m = 1, k = 1, x0 = 1, v0 = 0.
    pub fn thesis() -> Self {
        MassSpring {
            mass: 1.0,
            stiffness: 1.0,
            x0: 1.0,
            v0: 0.0,
        }
    }

    pub fn energy(&self, x: f64, v: f64) -> f64 {
        0.5 * self.mass * v * v + 0.5 * self.stiffness * x * x
    }

    /// The exact largest relative energy deviation |E_n / E_0 − 1| of the leapfrog records
    /// over `steps` steps of size `dt`, for a start from rest. The leapfrog's positions are
    /// x_n = x0 cos(nθ) with cos θ = 1 − (ωΔt)²/2, and its reported velocity
    /// (x_{n+1} − x_{n−1}) / 2Δt = −x0 sin(nθ) sin θ / Δt, so
    /// E_n / E_0 − 1 = −(ωΔt)²/4 · sin²(nθ): a bounded, second-order oscillation.
    pub fn leapfrog_max_energy_deviation(&self, dt: f64, steps: usize) -> f64 {
        let wdt2 = self.stiffness / self.mass * dt * dt;
        let theta = (1.0 - 0.5 * wdt2).acos();
        (0..steps)
            .map(|n| 0.25 * wdt2 * (n as f64 * theta).sin().powi(2))
            .fold(0.0, f64::max)
    }

    /// Integrate `steps` steps of size `dt`; returns the states at t = i Δt, i = 0..steps
    /// (the leapfrog reports its full-step velocity (v_{n−1/2} + v_{n+1/2})/2, so its last
    /// record is at (steps − 1) Δt).
    pub fn integrate(&self, scheme: Integrator, dt: f64, steps: usize) -> Vec<SpringState> {
        let (m, k) = (self.mass, self.stiffness);
        let accel = |x: f64| -k * x / m;
        let record = |n: usize, x: f64, v: f64| SpringState {
            t: n as f64 * dt,
            x,
            v,
            energy: self.energy(x, v),
        };
        let (mut x, mut v) = (self.x0, self.v0);
        let mut out = Vec::with_capacity(steps + 1);
        match scheme {
            Integrator::ExplicitEuler => {
                out.push(record(0, x, v));
                for n in 1..=steps {
                    let a = accel(x);
                    x += v * dt;
                    v += a * dt;
                    out.push(record(n, x, v));
                }
            }
            Integrator::Leapfrog => {
                let mut v_half = v - 0.5 * accel(x) * dt;
                for n in 0..steps {
                    let v_next = v_half + accel(x) * dt;
                    out.push(record(n, x, 0.5 * (v_half + v_next)));
                    x += v_next * dt;
                    v_half = v_next;
                }
            }
            Integrator::ImplicitEuler => {
                out.push(record(0, x, v));
                for n in 1..=steps {
                    v = (v - k * dt / m * x) / (1.0 + k * dt * dt / m);
                    x += v * dt;
                    out.push(record(n, x, v));
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative energy change after t = 50 (the thesis horizon), Δt = 0.1.
    fn drift(scheme: Integrator, dt: f64) -> f64 {
        let p = MassSpring::thesis();
        let steps = (50.0 / dt).round() as usize;
        let h = p.integrate(scheme, dt, steps);
        (h.last().unwrap().energy - h[0].energy) / h[0].energy
    }

    #[test]
    fn explicit_euler_gains_energy_by_the_exact_factor() {
        // |amplification|² = 1 + (ω Δt)² per step: E_n = E_0 (1 + Δt²)^n exactly.
        let dt: f64 = 0.1;
        let n = 500;
        let exact = (1.0 + dt * dt).powi(n) - 1.0;
        let d = drift(Integrator::ExplicitEuler, dt);
        assert!((d - exact).abs() < 1e-9 * exact, "gain {d}, exact {exact}");
        assert!(d > 100.0);
    }

    #[test]
    fn implicit_euler_loses_energy_by_the_exact_factor() {
        // |amplification|² = 1 / (1 + (ω Δt)²) per step.
        let dt: f64 = 0.1;
        let exact = (1.0 + dt * dt).powi(-500) - 1.0;
        let d = drift(Integrator::ImplicitEuler, dt);
        assert!(
            (d - exact).abs() < 1e-9 * exact.abs(),
            "loss {d}, exact {exact}"
        );
        assert!(d < -0.99);
    }

    #[test]
    fn leapfrog_conserves_energy_to_second_order() {
        // Bounded oscillation of amplitude O(Δt²): the maximum deviation falls 4x when Δt halves.
        let max_dev = |dt: f64| {
            let p = MassSpring::thesis();
            let h = p.integrate(Integrator::Leapfrog, dt, (50.0 / dt).round() as usize);
            h.iter().map(|s| (s.energy - 0.5).abs()).fold(0.0, f64::max) / 0.5
        };
        let (e1, e2) = (max_dev(0.1), max_dev(0.05));
        let exact = MassSpring::thesis().leapfrog_max_energy_deviation(0.1, 500);
        assert!(
            (e1 - exact).abs() < 1e-9 * exact,
            "deviation {e1}, exact {exact}"
        );
        let order = (e1 / e2).log2();
        assert!((order - 2.0).abs() < 0.1, "observed order {order}");
        // and the position stays on the exact solution cos t to O(Δt²) phase error
        let p = MassSpring::thesis();
        let h = p.integrate(Integrator::Leapfrog, 0.01, 5000);
        let err = h
            .iter()
            .map(|s| (s.x - s.t.cos()).abs())
            .fold(0.0, f64::max);
        assert!(err < 5e-4, "position error {err}");
    }
}
