//! Named results of a run, the numbers a reader of a scene asks for first (`mpw simulate`
//! prints them and writes `results.csv`, columns name, value, unit, next to the history):
//!
//! - per body: the largest α [-] and θ [K] over its points; the extent of its point
//!   centres along each axis, min and max [m] (a Taylor bar's final length is its z_max,
//!   its footprint radius its r_max, both to within half a point spacing); its kinetic
//!   energy at the end [J]; the time it came to rest [s], the first history sample from
//!   which its kinetic energy stayed below 1 % of its peak (NaN if it never did);
//! - per control point: its final position [m].

use crate::material_block::MaterialBlock;
use crate::output::AXES;
use crate::solver::observer::{Observer, Verdict, CONTINUE};
use crate::solver::Solver;
use materials::State;
use std::io::{self, Write};
use std::path::Path;

/// A body is at rest once its kinetic energy stays below this fraction of its peak.
pub const REST_FRACTION: f64 = 0.01;

#[derive(Debug, Clone, PartialEq)]
pub struct NamedResult {
    pub name: String,
    pub value: f64,
    pub unit: &'static str,
}

/// Each body's peak kinetic energy and the time since which it has stayed below
/// `REST_FRACTION` of it, sampled with the history.
#[derive(Debug, Clone, Default)]
pub struct RestTracker {
    peak: Vec<f64>,
    since: Vec<Option<f64>>,
}

impl RestTracker {
    /// Take the kinetic energy of every body at the current state.
    pub fn sample<const D: usize>(&mut self, s: &Solver<D>) {
        self.peak.resize(s.blocks.len(), 0.0);
        self.since.resize(s.blocks.len(), None);
        for b in 0..s.blocks.len() {
            let k = s.body_kinetic_energy(b);
            self.peak[b] = self.peak[b].max(k);
            let resting = k < REST_FRACTION * self.peak[b];
            self.since[b] = match (resting, self.since[b]) {
                (true, None) => Some(s.time),
                (true, t) => t,
                (false, _) => None,
            };
        }
    }
}

impl<const D: usize> Observer<D> for RestTracker {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        self.sample(s);
        CONTINUE
    }
}

/// The largest value of `f` over the history of a block's points.
pub fn largest(block: &MaterialBlock, f: impl Fn(&State<f64>) -> f64) -> f64 {
    block.state.iter().map(f).fold(f64::NEG_INFINITY, f64::max)
}

/// The named results of the solver's current state.
pub fn collect<const D: usize>(s: &Solver<D>, rest: &RestTracker) -> Vec<NamedResult> {
    let mut out = Vec::new();
    let mut push = |name: String, value: f64, unit| out.push(NamedResult { name, value, unit });
    for (b, block) in s.blocks.iter().enumerate() {
        let name = &block.name;
        push(
            format!("{name}.max_alpha"),
            largest(block, |st| st.alpha),
            "-",
        );
        push(
            format!("{name}.max_theta"),
            largest(block, |st| st.theta),
            "K",
        );
        let x = &s.particles.position[block.range.clone()];
        for (i, axis) in AXES.iter().enumerate().take(D) {
            let lo = x.iter().map(|p| p[i]).fold(f64::INFINITY, f64::min);
            let hi = x.iter().map(|p| p[i]).fold(f64::NEG_INFINITY, f64::max);
            push(format!("{name}.{axis}_min"), lo, "m");
            push(format!("{name}.{axis}_max"), hi, "m");
        }
        push(
            format!("{name}.kinetic_energy"),
            s.body_kinetic_energy(b),
            "J",
        );
        let rest_time = rest.since.get(b).copied().flatten().unwrap_or(f64::NAN);
        push(format!("{name}.rest_time"), rest_time, "s");
    }
    for (name, p) in &s.control_points {
        for (i, axis) in AXES.iter().enumerate().take(D) {
            push(format!("{name}.{axis}"), s.particles.position[*p][i], "m");
        }
    }
    out
}

/// Write `results` as CSV (name, value, unit).
pub fn write_csv(path: &Path, results: &[NamedResult]) -> io::Result<()> {
    let mut out = io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "name,value,unit")?;
    for r in results {
        writeln!(out, "{},{:.9e},{}", r.name, r.value, r.unit)?;
    }
    out.flush()
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

    /// A free block slowed by the artificial damping α_d (eq. 7.24) keeps its shape and
    /// moves as one: dv/dt = −α_d v, so each step multiplies v by (1 − α_d Δt) and the
    /// block comes to rest (K below 1 % of K0) after ln 100 / (2 α_d) in the continuum
    /// limit; its extent follows x(t) = x0 + Σ v_n Δt.
    #[test]
    fn a_damped_block_comes_to_rest_when_the_exponential_says() {
        let mut settings = Settings::<2>::new(Kinematics::PlaneStrain, 0.1);
        settings.bulk_viscosity = None;
        settings.damping = 50.0;
        settings.dt = Some(1e-4);
        let mut s = Solver::new(settings);
        let min = Vector2::new(0.2, 0.2);
        let points = fill(
            &Geometry::Box {
                min,
                max: Vector2::new(0.6, 0.4),
            },
            Vector2::repeat(0.05),
            Kinematics::PlaneStrain,
        );
        let v0 = 1.0;
        s.add_body(
            "block",
            Arc::new(NeoHooke::new(1e6, 0.3, 1000.0)),
            &points,
            Vector2::new(v0, 0.0),
        );
        s.initialize();
        let mut rest = RestTracker::default();
        rest.sample(&s);
        let (dt, steps) = (1e-4, 600);
        let mut travel = 0.0;
        for n in 0..steps {
            travel += v0 * (1.0f64 - 50.0 * dt).powi(n + 1) * dt;
            s.step().unwrap();
            rest.sample(&s);
        }
        let r = collect(&s, &rest);
        let get = |name: &str| r.iter().find(|x| x.name == name).unwrap().value;
        let rest_time = get("block.rest_time");
        let expected = 100f64.ln() / (2.0 * 50.0);
        assert!(
            (rest_time / expected - 1.0).abs() < 0.01,
            "{rest_time} vs {expected}"
        );
        assert!((get("block.x_min") - (0.225 + travel)).abs() < 1e-9);
        assert!((get("block.y_max") - 0.375).abs() < 1e-12);
        let m: f64 = s.particles.mass.iter().sum();
        let v = v0 * (1.0f64 - 50.0 * dt).powi(steps);
        assert!((get("block.kinetic_energy") / (0.5 * m * v * v) - 1.0).abs() < 1e-9);
        assert_eq!(get("block.max_alpha"), 0.0);
    }
}
