//! Single-point tensile test: uniaxial stress along x under the measured engineering
//! strain history ε(t), observed as engineering stress.
//!
//! The specimen geometry (gauge length, area A0) is the one at the test's start
//! temperature θ_s; with the free thermal stretch λ_θ there (see `preheated`), the path is
//! F_xx(t) = λ_θ (1 + ε(t)), σ_yy = σ_zz = 0, and the engineering stress is
//! P = force / A0 = σ_xx F_yy F_zz / λ_θ² [Pa] (= σ_xx J / F_xx at θ_s = θ0).
//!
//! Quasi-static tests are isothermal at θ_s; high-rate tests are adiabatic (Taylor-Quinney
//! heating). The path follows the record's own strain-time history from its first sample
//! (so the strain rate ε̇ = dε/dt and the adiabatic temperature at a compared sample are
//! those of the test, also when the compared window starts late), stepping at every
//! record point up to the last compared sample, subdivided so that no step exceeds
//! `MAX_STRAIN_STEP`; noisy strains are made monotone by a running maximum.

use crate::fit::levels::model::Material;
use crate::fit::levels::single_point::Observable;
use anyhow::{bail, Result};
use materials::driver::{LoadPath, Ramp, Record, Temperature};
use materials::limits::LOAD_PATH_STEPS;
use materials::preheated::thermal_stretch;
use materials::scalar::{c, Scalar};

/// Largest engineering-strain increment of one driver step.
pub const MAX_STRAIN_STEP: f64 = 2.5e-3;

/// Thermal condition of a tensile test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Thermal {
    /// Temperature held at θ_s (quasi-static).
    Isothermal,
    /// Adiabatic heating from θ_s (high rate).
    Adiabatic,
}

#[derive(Debug, Clone)]
pub struct Tensile {
    path: LoadPath,
    /// Driver record index of each sample.
    samples: Vec<usize>,
    theta_start: f64,
    inv_stretch2: f64,
}

impl Tensile {
    /// The record's history `times` [s] and engineering `strain` [-] (strictly increasing
    /// times, the first at or after the start of loading), the indices `samples` of the
    /// history points to predict (strictly increasing), the start temperature `theta` [K].
    pub fn new(
        material: &Material,
        times: &[f64],
        strain: &[f64],
        samples: &[usize],
        thermal: Thermal,
        theta: f64,
    ) -> Result<Self> {
        if times.len() < 2 || times.len() != strain.len() {
            bail!(
                "tensile model needs at least two history points with one strain each (got {} times, {} strains)",
                times.len(),
                strain.len()
            );
        }
        if samples.is_empty() || samples.windows(2).any(|w| w[1] <= w[0]) {
            bail!("tensile model: sample indices must be strictly increasing");
        }
        let last = *samples.last().unwrap();
        if last >= times.len() {
            bail!("tensile model: sample index {last} beyond the history");
        }
        let lambda = thermal_stretch(material, theta);
        let steps = substeps(&strain[..=last]);
        LOAD_PATH_STEPS.check(steps.iter().map(|&n| n as f64).sum(), || {
            let (k, n) = steps.iter().enumerate().max_by_key(|(_, n)| **n).unwrap();
            format!(
                "the strain history rises to {:e} at history point {k} ({n} steps of {MAX_STRAIN_STEP} there)",
                strain[k]
            )
        })?;
        // Start at zero strain one sample interval before the first sample.
        let mut path_t = vec![times[0] - (times[1] - times[0])];
        let mut path_e = vec![0.0];
        let mut records = Vec::with_capacity(times.len());
        let mut e_max: f64 = 0.0;
        for ((&t, &e), &n) in times[..=last].iter().zip(strain).zip(&steps) {
            let (t_prev, e_prev) = (*path_t.last().unwrap(), *path_e.last().unwrap());
            if !(t > t_prev) {
                bail!("tensile model: time {t} s is not after {t_prev} s");
            }
            e_max = e_max.max(e);
            for k in 1..=n {
                let w = k as f64 / n as f64;
                path_t.push(t_prev + w * (t - t_prev));
                path_e.push(e_prev + w * (e_max - e_prev));
            }
            records.push(path_t.len() - 1);
        }
        let samples = samples.iter().map(|&k| records[k]).collect();
        let stretch = path_e.iter().map(|e| lambda * (1.0 + e)).collect();
        let temperature = match thermal {
            Thermal::Isothermal => Temperature::Prescribed(Ramp::constant(theta)),
            Thermal::Adiabatic => Temperature::Adiabatic,
        };
        Ok(Tensile {
            path: LoadPath::uniaxial_stretch(path_t, stretch, temperature)?,
            samples,
            theta_start: theta,
            inv_stretch2: 1.0 / (lambda * lambda),
        })
    }
}

/// Driver steps from each history point to the next: the rise of the running maximum of
/// `strain` in steps of at most `MAX_STRAIN_STEP`, at least one (the cast saturates, so a
/// corrupt sample gives a count the size check refuses rather than an overflow).
fn substeps(strain: &[f64]) -> Vec<usize> {
    let (mut e_prev, mut e_max) = (0.0, 0.0f64);
    strain
        .iter()
        .map(|&e| {
            e_max = e_max.max(e);
            let n = ((e_max - e_prev) / MAX_STRAIN_STEP).ceil().max(1.0);
            e_prev = e_max;
            n as usize
        })
        .collect()
}

impl Observable for Tensile {
    fn level(&self) -> &'static str {
        "single-point tensile"
    }
    fn path(&self) -> &LoadPath {
        &self.path
    }
    fn theta_start(&self) -> f64 {
        self.theta_start
    }
    fn len(&self) -> usize {
        self.samples.len()
    }
    fn observe<D: Scalar>(&self, records: &[Record<D>]) -> Vec<D> {
        self.samples
            .iter()
            .map(|&i| {
                let f = &records[i].f;
                records[i].sigma[(0, 0)] * f[(1, 1)] * f[(2, 2)] * c::<D>(self.inv_stretch2)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn material() -> Material {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/materials");
        materials::load_elasto_plastic(std::path::Path::new(dir).join("42crmo4_qt660.toml"))
            .unwrap()
    }

    /// A history of 4 points to 1.25 % strain takes 1 + 2 + 3 + 1 steps (at most 0.25 % per
    /// step, one where the strain falls); one corrupt strain of 1e20 asks for 4e22 steps
    /// and is refused before any of them is allocated, naming the point.
    #[test]
    fn a_corrupt_strain_is_refused_before_the_path_is_built() {
        let times = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(substeps(&[0.001, 0.0055, 0.0125, 0.0100]), vec![1, 2, 3, 1]);
        let build = |strain: &[f64]| {
            Tensile::new(
                &material(),
                &times,
                strain,
                &[0, 1, 2, 3],
                Thermal::Isothermal,
                293.15,
            )
        };
        let ok = build(&[0.001, 0.0055, 0.0125, 0.0100]).unwrap();
        assert_eq!(ok.path.times.len(), 1 + 7);
        let e = build(&[0.001, 1e20, 0.0125, 0.0100])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("load-path steps") && e.contains("history point 1"),
            "{e}"
        );
    }
}
