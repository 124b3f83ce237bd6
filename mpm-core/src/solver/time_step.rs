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
//!
//! The time step re-checked after every step: the CFL estimate Δt_cr = safety · h /
//! max(c + |v|) (eq. 7.22-7.23) with the current velocities. A chosen Δt more than
//! `SLACK` above the current estimate is reduced to it (the safety factor, 0.3 by default,
//! leaves a 3x margin to the bare limit, so a point moving at a few per cent of the wave
//! speed does not change Δt); it is never raised again (spring stability does not
//! improve, and a run that slowed once is near its limit). A fixed Δt (`time.dt`) is
//! kept, and the first step at which it exceeds the bare limit h / (c + |v|) is recorded.
//! Every change is kept in `Solver::time_step_changes` for the run log.

use super::Solver;
use crate::parallel;
use nalgebra::SVector;
use rayon::prelude::*;
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
    /// The stiffest penalty or spring [N/m] and the lightest particle mass [kg], if any.
    pub stiffest_spring: Option<(f64, f64)>,
}

impl TimeStep {
    /// Why this Δt is likely to be unstable, if it is: above the bare CFL limit
    /// h/(c + |v|) or the bare spring limit 2 √(m/k) (safety > 1, or a given Δt beyond
    /// either).
    pub fn risk(&self) -> Option<String> {
        let cfl = self.cfl_dt / self.safety;
        let spring = self
            .stiffest_spring
            .map(|(k, m)| (2.0 * (m / k).sqrt(), k, m));
        let setting = match self.criterion {
            Criterion::Given => "leave time.dt out",
            _ => "set time.safety to 0.2-0.5",
        };
        let what = match self.criterion {
            Criterion::Given => format!("time.dt = {:.4e} s", self.dt),
            _ => format!("time.safety = {}: dt = {:.4e} s", self.safety, self.dt),
        };
        if let Some((limit, k, m)) = spring.filter(|(limit, _, _)| self.dt > *limit) {
            return Some(format!(
                "{what} exceeds the penalty/spring limit 2√(m/k) = {limit:.4e} s ({:.2}x; k = {k:.3e} N/m on the lightest particle, {m:.3e} kg): contact and spring forces are not integrated stably there; {setting}",
                self.dt / limit
            ));
        }
        (self.dt > cfl).then(|| format!(
            "{what} exceeds the CFL limit h/(c+|v|) = {cfl:.4e} s ({:.2}x): explicit MPM is unstable there; {setting}",
            self.dt / cfl
        ))
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
            stiffest_spring,
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
        stiffest_spring,
    };
    if let Some((stiffness, mass)) = stiffest_spring {
        let dt = safety * 2.0 * (mass / stiffness).sqrt();
        if dt < best.dt {
            best = TimeStep {
                dt,
                criterion: Criterion::Spring { stiffness, mass },
                cfl_dt,
                safety,
                stiffest_spring,
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

/// A change of Δt during a run, or a fixed Δt found beyond the CFL limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeStepChange {
    pub step: usize,
    /// Time of the change [s].
    pub time: f64,
    /// Δt before and after [s] (equal when a fixed Δt was kept).
    pub from: f64,
    pub to: f64,
    /// The largest c + |v| that set the limit [m/s].
    pub speed: f64,
}

impl std::fmt::Display for TimeStepChange {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.from == self.to {
            write!(
                f,
                "step {}, t = {:.4e} s: the fixed dt = {:.4e} s exceeds the CFL limit h/(c+|v|) at max c+|v| = {:.4e} m/s",
                self.step, self.time, self.from, self.speed
            )
        } else {
            write!(
                f,
                "step {}, t = {:.4e} s: dt reduced from {:.4e} to {:.4e} s (CFL, max c+|v| = {:.4e} m/s)",
                self.step, self.time, self.from, self.to, self.speed
            )
        }
    }
}

/// How far Δt may exceed the current estimate before it is reduced [-].
pub const SLACK: f64 = 0.1;

impl<const D: usize> Solver<D> {
    /// The largest dilatational wave speed plus point speed, max (c + |v|) [m/s].
    pub fn max_signal_speed(&self) -> f64 {
        let v = &self.particles.velocity;
        self.blocks
            .iter()
            .map(|b| {
                let c = b.wave_speed();
                let fastest = |most: f64, v: &SVector<f64, D>| most.max(c + v.norm());
                let points = v[b.range.clone()].par_iter();
                parallel::fold(points, parallel::light(v.len()), 0.0, fastest, f64::max)
            })
            .fold(0.0, f64::max)
    }

    /// Reduce Δt to the current CFL estimate where that is below it (module notes).
    pub(super) fn recheck_time_step(&mut self) {
        let speed = self.max_signal_speed();
        let h = self.grid.min_spacing();
        let change = |to| TimeStepChange {
            step: self.step,
            time: self.time,
            from: self.dt,
            to,
            speed,
        };
        if self.settings.dt.is_some() {
            let warned = !self.time_step_changes.is_empty();
            if !warned && self.dt > h / speed {
                self.time_step_changes.push(change(self.dt));
            }
            return;
        }
        let cfl = self.settings.safety * h / speed;
        if self.dt > (1.0 + SLACK) * cfl {
            self.time_step_changes.push(change(cfl));
            self.set_time_step(cfl, speed);
        }
    }

    /// Δt [s] and what follows from it: the node mass cutoff, the larger of
    /// `Settings::mass_cutoff` and the stability limit `node_mass_cutoff` at the largest
    /// signal speed `speed` [m/s].
    pub(super) fn set_time_step(&mut self, dt: f64, speed: f64) {
        self.dt = dt;
        let stable = node_mass_cutoff(self.grid.min_spacing(), speed, dt);
        self.mass_cutoff = self.settings.mass_cutoff.max(stable);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretize::{fill, Geometry};
    use crate::kinematics::Kinematics;
    use crate::solver::Settings;
    use materials::NeoHooke;
    use nalgebra::Vector2;
    use std::sync::Arc;

    #[test]
    fn a_time_step_above_the_cfl_limit_is_named_with_its_setting() {
        // h = 0.05 m, c + |v| = 1 m/s: the bare CFL limit is 0.05 s.
        assert_eq!(choose(0.05, 1.0, None, 0.3, None).risk(), None);
        let risky = choose(0.05, 1.0, None, 1.5, None).risk().unwrap();
        assert!(
            risky.starts_with("time.safety = 1.5: dt = 7.5000e-2 s exceeds the CFL limit"),
            "{risky}"
        );
        assert!(
            risky.contains("5.0000e-2 s") && risky.contains("set time.safety"),
            "{risky}"
        );
        assert_eq!(choose(0.05, 1.0, None, 0.3, Some(0.04)).risk(), None);
        let given = choose(0.05, 1.0, None, 0.3, Some(0.1)).risk().unwrap();
        assert!(
            given.starts_with("time.dt = 1.0000e-1 s exceeds the CFL limit"),
            "{given}"
        );
        assert!(given.contains("(2.00x)"), "{given}");
    }

    /// A penalty k = 100 N/m on a 1 kg particle: the bare limit 2√(m/k) = 0.2 s; the
    /// solver's own step (safety 0.3) is within it, a given step of 0.3 s is not, though
    /// the CFL limit (10 s) allows it.
    #[test]
    fn a_time_step_above_the_penalty_limit_is_named() {
        let spring = Some((100.0, 1.0));
        let own = choose(10.0, 1.0, spring, 0.3, None);
        assert!(
            (own.dt - 0.06).abs() < 1e-15 && own.risk().is_none(),
            "{own}"
        );
        assert_eq!(choose(10.0, 1.0, spring, 0.3, Some(0.19)).risk(), None);
        let given = choose(10.0, 1.0, spring, 0.3, Some(0.3)).risk().unwrap();
        assert!(
            given.starts_with("time.dt = 3.0000e-1 s exceeds the penalty/spring limit 2√(m/k) = 2.0000e-1 s (1.50x"),
            "{given}"
        );
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

    /// A soft block (c = 1 m/s) falling from rest under b = 1 m/s² for 0.9 s: c + |v|
    /// grows from 1 to 1.9 m/s (within the watchdog's speed limit c), so Δt must fall
    /// from 0.3 h / c with 0.3 h / (c + |v|).
    fn falling(dt: Option<f64>) -> Solver<2> {
        let mut settings = Settings::<2>::new(Kinematics::PlaneStrain, 0.1);
        settings.dt = dt;
        settings.body_force = Vector2::new(0.0, -1.0);
        let mut s = Solver::new(settings);
        let block = fill(
            &Geometry::Box {
                min: Vector2::zeros(),
                max: Vector2::repeat(0.4),
            },
            Vector2::repeat(0.05),
            Kinematics::PlaneStrain,
        );
        // a P-wave speed c = √((Λ+2G)/ρ) of 1 m/s with ν = 0
        s.add_body(
            "block",
            Arc::new(NeoHooke::new(1.0, 0.0, 1.0)),
            &block,
            Vector2::zeros(),
        );
        s.initialize();
        while s.time < 0.9 {
            s.step().unwrap();
        }
        s
    }

    #[test]
    fn dt_follows_the_current_speed_and_a_fixed_dt_is_flagged_once() {
        let s = falling(None);
        let changes = &s.time_step_changes;
        // one change per 10 % growth of c + |v| from 1 to 1.9 m/s
        assert!((5..=7).contains(&changes.len()), "{changes:?}");
        assert!(changes
            .windows(2)
            .all(|w| w[1].to < w[0].to && w[1].from == w[0].to));
        assert_eq!(changes[0].from, 0.3 * 0.1 / 1.0);
        let last = changes.last().unwrap();
        assert_eq!(s.dt, last.to);
        assert_eq!(s.dt, 0.3 * 0.1 / last.speed);
        // free fall: |v| = b t, so c + |v| ≈ 1 + t (within a step); at the end Δt is
        // within the slack of the estimate
        assert!((last.speed - (1.0 + last.time)).abs() < 0.05, "{last}");
        assert!(s.dt <= (1.0 + SLACK) * 0.3 * 0.1 / s.max_signal_speed());
        // a fixed Δt of 0.08 s is within h / c = 0.1 s at rest and beyond h / (c + |v|)
        // from |v| = 0.25 m/s (t ≈ 0.25 s): flagged once, kept
        let fixed = falling(Some(0.08));
        assert_eq!(fixed.dt, 0.08);
        assert_eq!(fixed.time_step_changes.len(), 1);
        let flagged = fixed.time_step_changes[0];
        assert!(
            flagged.from == flagged.to && (flagged.time - 0.25).abs() < 0.1,
            "{flagged}"
        );
    }
}
