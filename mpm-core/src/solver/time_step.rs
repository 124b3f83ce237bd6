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
            self.dt = cfl;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretize::{fill, Shape};
    use crate::kinematics::Kinematics;
    use crate::solver::Settings;
    use materials::NeoHooke;
    use nalgebra::Vector2;
    use std::sync::Arc;

    /// A soft block (c = 1 m/s) falling from rest under b = 1 m/s² for 0.9 s: c + |v|
    /// grows from 1 to 1.9 m/s (within the watchdog's speed limit c), so Δt must fall
    /// from 0.3 h / c with 0.3 h / (c + |v|).
    fn falling(dt: Option<f64>) -> Solver<2> {
        let mut settings = Settings::<2>::new(Kinematics::PlaneStrain, 0.1);
        settings.dt = dt;
        settings.body_force = Vector2::new(0.0, -1.0);
        let mut s = Solver::new(settings);
        let block = fill(
            &Shape::Box {
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
