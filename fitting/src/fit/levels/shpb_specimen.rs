//! Single-point SHPB specimen: uniaxial stress along the bar axis x under the measured
//! relative face velocity v(t) = v1 − v2 [m/s] (compression positive), adiabatic heating
//! from the start temperature θ_s, observed as the specimen force compared with both bar
//! forces F1 (incident face) and F2 (transmitted face) [N, compression positive].
//!
//! Length: L(t) = L0 − ∫ v dt (trapezoidal rule on the measured samples), with L0 and the
//! area A0 measured at θ_s. With the free thermal stretch λ_θ (see `preheated`):
//! F_xx = λ_θ L/L0, force = −σ_xx A0 F_yy F_zz / λ_θ². A single point is in equilibrium,
//! so its force predicts F1 and F2 alike; the two channels are stacked [F1 samples, F2
//! samples] so that a model with two contact forces (MPM) fits the same objective.

use crate::fit::levels::model::Material;
use crate::fit::levels::single_point::Observable;
use anyhow::{bail, Result};
use materials::driver::{LoadPath, Record};
use materials::preheated::thermal_stretch;
use materials::scalar::{c, Scalar};

#[derive(Debug, Clone)]
pub struct ShpbSpecimen {
    path: LoadPath,
    samples: Vec<usize>,
    channels: usize,
    theta_start: f64,
    /// A0 / λ_θ² [m²], with the sign that makes compression positive.
    force_factor: f64,
}

impl ShpbSpecimen {
    /// `times` [s] and relative face velocity `velocity` [m/s] from the start of loading
    /// (the first time has L = L0), the `samples` (indices into `times`, strictly
    /// increasing, the first > 0) at which the force is predicted, specimen length
    /// `length0` [m] and area `area0` [m²] at `theta` [K], and the number of force
    /// `channels` compared (1: F1 only, 2: F1 and F2).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        material: &Material,
        times: &[f64],
        velocity: &[f64],
        samples: &[usize],
        length0: f64,
        area0: f64,
        theta: f64,
        channels: usize,
    ) -> Result<Self> {
        if times.len() != velocity.len() || times.len() < 2 {
            bail!("SHPB model needs as many velocities as times (at least two)");
        }
        if samples.is_empty() || samples[0] == 0 || samples.windows(2).any(|w| w[1] <= w[0]) {
            bail!(
                "SHPB model: sample indices must be strictly increasing and after the first time"
            );
        }
        if *samples.last().unwrap() >= times.len() {
            bail!("SHPB model: sample index beyond the record");
        }
        if !(length0 > 0.0 && area0 > 0.0) || !(1..=2).contains(&channels) {
            bail!(
                "SHPB model: length {length0} m, area {area0} m² must be positive, channels 1 or 2"
            );
        }
        let lambda = thermal_stretch(material, theta);
        let mut displacement = vec![0.0; times.len()];
        for k in 1..times.len() {
            displacement[k] = displacement[k - 1]
                + 0.5 * (velocity[k] + velocity[k - 1]) * (times[k] - times[k - 1]);
        }
        // Path steps: every `stride`-th record point before the samples (the sampling
        // stride of the window), then the samples themselves.
        let stride = samples.windows(2).map(|w| w[1] - w[0]).min().unwrap_or(1);
        let mut steps: Vec<usize> = (1..samples[0]).filter(|k| k % stride == 0).collect();
        let first_sample = steps.len() + 1;
        steps.extend_from_slice(samples);
        let mut path_t = vec![times[0]];
        let mut stretch = vec![lambda];
        for &k in &steps {
            let ratio = 1.0 - displacement[k] / length0;
            if ratio <= 0.05 {
                bail!(
                    "SHPB model: specimen compressed to {ratio} of its length at t = {} s",
                    times[k]
                );
            }
            path_t.push(times[k]);
            stretch.push(lambda * ratio);
        }
        Ok(ShpbSpecimen {
            path: LoadPath::shpb_specimen(path_t, stretch)?,
            samples: (first_sample..first_sample + samples.len()).collect(),
            channels,
            theta_start: theta,
            force_factor: -area0 / (lambda * lambda),
        })
    }
}

impl Observable for ShpbSpecimen {
    fn level(&self) -> &'static str {
        "single-point SHPB specimen"
    }
    fn path(&self) -> &LoadPath {
        &self.path
    }
    fn theta_start(&self) -> f64 {
        self.theta_start
    }
    fn len(&self) -> usize {
        self.channels * self.samples.len()
    }
    fn observe<D: Scalar>(&self, records: &[Record<D>]) -> Vec<D> {
        let force: Vec<D> = self
            .samples
            .iter()
            .map(|&i| {
                let f = &records[i].f;
                records[i].sigma[(0, 0)] * f[(1, 1)] * f[(2, 2)] * c::<D>(self.force_factor)
            })
            .collect();
        let mut out = force.clone();
        if self.channels == 2 {
            out.extend(force);
        }
        out
    }
}
