//! Time-step size: the CFL estimate of eq. 7.22-7.23,
//! Δt_cr = l_cr / max_MP (c_MP + |v_MP|), c = √((Λ+2G)/ρ), l_cr the smallest cell size,
//! times a safety factor, also bounded by the stability of the stiffest penalty or
//! boundary spring k on the lightest particle m: Δt ≤ safety · 2 √(m/k) (a spring-mass
//! oscillator under the central difference rule is stable for ω Δt ≤ 2).

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
        };
    }
    let mut best = TimeStep {
        dt: cfl_dt,
        criterion: Criterion::Cfl {
            speed: max_speed,
            cell,
        },
        cfl_dt,
    };
    if let Some((stiffness, mass)) = stiffest_spring {
        let dt = safety * 2.0 * (mass / stiffness).sqrt();
        if dt < best.dt {
            best = TimeStep {
                dt,
                criterion: Criterion::Spring { stiffness, mass },
                cfl_dt,
            };
        }
    }
    best
}
