//! Time-step size: the CFL estimate of eq. 7.22-7.23,
//! Δt_cr = l_cr / max_MP (c_MP + |v_MP|), c = √((Λ+2G)/ρ), l_cr the smallest cell size,
//! times a safety factor, also bounded by the stability of the stiffest penalty or
//! boundary spring k on the lightest particle m: Δt ≤ safety · 2 √(m/k) (a spring-mass
//! oscillator under the central difference rule is stable for ω Δt ≤ 2).
//!
//! The same limit bounds the lightest node that may be accelerated. A node I that takes
//! only the share N of a point's mass m (the point near the far face of the cell) has
//! m_I = N m but a stiffness that does not shrink with N: f_I = −σ V ∇N_I with
//! |∇N_I| ≈ 1/h, so K_II ≈ ρ c² V / h² and ω² = K_II / m_I ≈ c² / (h² N). The leapfrog
//! needs ω Δt ≤ 2, i.e. N ≥ (c Δt / (2 h))²: lighter nodes must not be accelerated. N is
//! the node's mass over that of the heaviest point reaching it (the stiffness comes from
//! the points, and in an axisymmetric model their masses differ by R/r).

use std::fmt;

/// What limits the chosen Δt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Criterion {
    /// Eq. 7.22 with the largest c + |v| [m/s] over particles and the cell size [m].
    Cfl { speed: f64, cell: f64 },
    /// Spring stability with stiffness [N/m] on the lightest particle mass [kg].
    Spring { stiffness: f64, mass: f64 },
    /// Set by the user.
    Given,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeStep {
    /// Chosen Δt [s].
    pub dt: f64,
    pub criterion: Criterion,
    /// Δt allowed by the CFL estimate alone (with the safety factor) [s].
    pub cfl_dt: f64,
    /// The safety factor of the estimate [-].
    pub safety: f64,
}

impl TimeStep {
    /// Why this Δt is likely to be unstable, if it is: above the bare CFL limit
    /// h/(c + |v|) (safety > 1, or a given Δt beyond it).
    pub fn risk(&self) -> Option<String> {
        let limit = self.cfl_dt / self.safety;
        if self.dt <= limit {
            return None;
        }
        Some(match self.criterion {
            Criterion::Given => format!(
                "time.dt = {:.4e} s exceeds the CFL limit h/(c+|v|) = {limit:.4e} s ({:.2}x): explicit MPM is unstable there; leave dt out and set time.safety (0.2-0.5)",
                self.dt,
                self.dt / limit
            ),
            _ => format!(
                "time.safety = {} exceeds 1: dt = {:.4e} s is above the CFL limit h/(c+|v|) = {limit:.4e} s, where explicit MPM is unstable; use 0.2-0.5",
                self.safety, self.dt
            ),
        })
    }
}

impl fmt::Display for TimeStep {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "dt = {:.4e} s limited by ", self.dt)?;
        match self.criterion {
            Criterion::Cfl { speed, cell } => write!(
                f,
                "CFL (eq. 7.22): cell {cell:.3e} m, max c+|v| = {speed:.4e} m/s"
            ),
            Criterion::Spring { stiffness, mass } => {
                write!(f, "penalty/spring stability: k = {stiffness:.3e} N/m on particle mass {mass:.3e} kg")
            }
            Criterion::Given => write!(f, "the scene (CFL estimate {:.4e} s)", self.cfl_dt),
        }
    }
}

/// Choose Δt from the CFL estimate and the stiffest spring; `given` overrides both.
pub fn choose(
    cell: f64,
    max_speed: f64,
    stiffest_spring: Option<(f64, f64)>,
    safety: f64,
    given: Option<f64>,
) -> TimeStep {
    let cfl_dt = safety * cell / max_speed;
    if let Some(dt) = given {
        return TimeStep {
            dt,
            criterion: Criterion::Given,
            cfl_dt,
            safety,
        };
    }
    let mut best = TimeStep {
        dt: cfl_dt,
        criterion: Criterion::Cfl {
            speed: max_speed,
            cell,
        },
        cfl_dt,
        safety,
    };
    if let Some((stiffness, mass)) = stiffest_spring {
        let dt = safety * 2.0 * (mass / stiffness).sqrt();
        if dt < best.dt {
            best = TimeStep {
                dt,
                criterion: Criterion::Spring { stiffness, mass },
                cfl_dt,
                safety,
            };
        }
    }
    best
}

/// Smallest node mass, as a fraction of a point's mass, that the leapfrog may accelerate
/// stably with `dt` [s] on cells of size `cell` [m] and the largest speed c + |v| [m/s]:
/// (c Δt / (2 h))² (see the module notes).
pub fn node_mass_cutoff(cell: f64, max_speed: f64, dt: f64) -> f64 {
    (max_speed * dt / (2.0 * cell)).powi(2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_time_step_above_the_cfl_limit_is_named_with_its_setting() {
        // h = 0.05 m, c + |v| = 1 m/s: the bare CFL limit is 0.05 s.
        assert_eq!(choose(0.05, 1.0, None, 0.3, None).risk(), None);
        let risky = choose(0.05, 1.0, None, 1.5, None).risk().unwrap();
        assert!(risky.starts_with("time.safety = 1.5 exceeds 1"), "{risky}");
        assert!(risky.contains("5.0000e-2 s"), "{risky}");
        assert_eq!(choose(0.05, 1.0, None, 0.3, Some(0.04)).risk(), None);
        let given = choose(0.05, 1.0, None, 0.3, Some(0.1)).risk().unwrap();
        assert!(
            given.starts_with("time.dt = 1.0000e-1 s exceeds the CFL limit"),
            "{given}"
        );
        assert!(given.contains("(2.00x)"), "{given}");
    }

    /// Leapfrog on the node oscillator ü = −ω² u with ω² = c²/(h² N): amplitude after
    /// 10³ steps relative to the start.
    fn growth(n: f64, c: f64, h: f64, dt: f64) -> f64 {
        let w2 = c * c / (h * h * n);
        let (mut u, mut v) = (1.0, 0.0);
        for _ in 0..1_000 {
            v -= w2 * u * dt;
            u += v * dt;
        }
        u.abs().max(v.abs() / w2.sqrt())
    }

    #[test]
    fn nodes_above_the_mass_cutoff_are_stable_and_below_it_are_not() {
        let (c, h, dt) = (2833.0, 2e-3, 2.1e-7);
        let cutoff = node_mass_cutoff(h, c, dt);
        // ω Δt = 2 exactly at the cutoff
        assert!(((c / h) * dt / cutoff.sqrt() - 2.0).abs() < 1e-12);
        assert!(growth(1.01 * cutoff, c, h, dt) < 20.0);
        assert!(growth(0.99 * cutoff, c, h, dt) > 1e6);
    }
}
