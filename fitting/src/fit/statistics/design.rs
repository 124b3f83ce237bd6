//! The next experiment: which candidate test would shrink the fitted parameters' joint
//! uncertainty most.
//!
//! At the fitted parameters p̂ the set's normalized residuals r (`objective`:
//! r_ek = √(w_e/n_e) (ŷ_ek − y_ek)/s_e) have the Jacobian J = dr/dp from the models'
//! AD sensitivities, and the parameters the covariance
//!
//!   Σ = s² (JᵀJ)⁻¹,  s² = rᵀr/(n − k),
//!
//! the noise of the records already in the set. A candidate test (tensile or SHPB at a rate
//! and temperature) enters as one more experiment of weight 1: its predicted observations
//! at p̂, normalized the same way, add J_cᵀJ_c, and the covariance after it would be
//! Σ_c = s² (JᵀJ + J_cᵀJ_c)⁻¹. The candidates are ranked by the D-criterion, the
//! geometric-mean shrink of the standard errors (det Σ_c/det Σ)^(1/2k) (the volume of the
//! confidence ellipsoid), with each parameter's expected standard error and the largest
//! correlation left after it. This is the linearized expectation at p̂; the refit's
//! scatter over noise seeds checks it (`fitting/tests/design.rs`).

use crate::fit::levels::model::{ExperimentModel, Material};
use crate::fit::levels::shpb_specimen::ShpbSpecimen;
use crate::fit::levels::single_point::SinglePoint;
use crate::fit::levels::tensile::{Tensile, Thermal};
use crate::fit::objective::Block;
use crate::fit::synthetic::synth::THESIS_BARS;
use anyhow::{bail, Context, Result};
use nalgebra::DMatrix;
use std::f64::consts::PI;
use std::str::FromStr;

/// A test that could be run next.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CandidateTest {
    /// Uniaxial tension at a constant engineering strain rate [1/s] to 30 %, from a
    /// temperature [K]; isothermal below 1 1/s, adiabatic above (as `fit_set` reads tests).
    Tensile { rate: f64, temperature: f64 },
    /// An SHPB compression test at a strain rate [1/s] from a temperature [K]: the
    /// synthetic set's bars and specimen (`synth::THESIS_BARS`), the transmitted force F2
    /// over 15-115 µs.
    Shpb { rate: f64, temperature: f64 },
}

impl FromStr for CandidateTest {
    type Err = anyhow::Error;

    /// `tensile:RATE:TEMPERATURE` or `shpb:RATE:TEMPERATURE` (1/s, K).
    fn from_str(text: &str) -> Result<Self> {
        let parts: Vec<&str> = text.split(':').collect();
        let [kind, rate, temperature] = parts[..] else {
            bail!("test \"{text}\": expected KIND:RATE:TEMPERATURE, e.g. tensile:1e-3:293 or shpb:5000:573");
        };
        let number = |what: &str, s: &str| -> Result<f64> {
            let x: f64 = s
                .parse()
                .with_context(|| format!("test \"{text}\": {what} \"{s}\" is not a number"))?;
            if !(x > 0.0 && x.is_finite()) {
                bail!("test \"{text}\": {what} {x} must be positive");
            }
            Ok(x)
        };
        let (rate, temperature) = (number("rate", rate)?, number("temperature", temperature)?);
        match kind {
            "tensile" => Ok(CandidateTest::Tensile { rate, temperature }),
            "shpb" => Ok(CandidateTest::Shpb { rate, temperature }),
            other => bail!("test \"{text}\": kind \"{other}\", expected \"tensile\" or \"shpb\""),
        }
    }
}

impl std::fmt::Display for CandidateTest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CandidateTest::Tensile { rate, temperature } => {
                write!(f, "tensile at {rate:e} 1/s, {temperature} K")
            }
            CandidateTest::Shpb { rate, temperature } => {
                write!(f, "SHPB at {rate:e} 1/s, {temperature} K")
            }
        }
    }
}

/// Samples of a candidate tensile test, and its largest engineering strain.
const TENSILE_SAMPLES: usize = 120;
const TENSILE_STRAIN: f64 = 0.3;
/// The candidate SHPB test's face-velocity ramp, pulse and compared window [s].
const SHPB_RAMP: f64 = 10e-6;
const SHPB_PULSE: f64 = 120e-6;
const SHPB_WINDOW: [f64; 2] = [15e-6, 115e-6];
const SHPB_STEP: f64 = 0.25e-6;

impl CandidateTest {
    /// The test's single-point model at `material`, and the abscissa of its observations
    /// (tensile: engineering strain; SHPB: time [s]).
    fn model(&self, material: &Material) -> Result<(Box<dyn ExperimentModel>, Vec<f64>)> {
        Ok(match *self {
            CandidateTest::Tensile { rate, temperature } => {
                let strain: Vec<f64> = (1..=TENSILE_SAMPLES)
                    .map(|k| TENSILE_STRAIN * k as f64 / TENSILE_SAMPLES as f64)
                    .collect();
                let times: Vec<f64> = strain.iter().map(|e| e / rate).collect();
                let samples: Vec<usize> = (0..strain.len()).collect();
                let thermal = if rate < 1.0 {
                    Thermal::Isothermal
                } else {
                    Thermal::Adiabatic
                };
                let model =
                    Tensile::new(material, &times, &strain, &samples, thermal, temperature)?;
                (Box::new(SinglePoint::new(model)), strain)
            }
            CandidateTest::Shpb { rate, temperature } => {
                let s = &THESIS_BARS;
                let n = (SHPB_PULSE / SHPB_STEP).round() as usize + 1;
                let times: Vec<f64> = (0..n).map(|k| k as f64 * SHPB_STEP).collect();
                let v0 = rate * s.specimen_length;
                let velocity: Vec<f64> = times
                    .iter()
                    .map(|&t| v0 * (t / SHPB_RAMP).min(1.0))
                    .collect();
                let samples: Vec<usize> = (0..n)
                    .filter(|&k| (SHPB_WINDOW[0]..=SHPB_WINDOW[1]).contains(&times[k]))
                    .collect();
                let area0 = PI * s.specimen_diameter.powi(2) / 4.0;
                let model = ShpbSpecimen::new(
                    material,
                    &times,
                    &velocity,
                    &samples,
                    s.specimen_length,
                    area0,
                    temperature,
                    1,
                )?;
                let x = samples.iter().map(|&k| times[k]).collect();
                (Box::new(SinglePoint::new(model)), x)
            }
        })
    }

    /// The test as an experiment of the set, its observations predicted by `material`
    /// (the noise-free expectation at the fitted parameters).
    pub fn block(&self, material: &Material) -> Result<Block> {
        let (model, x) = self.model(material)?;
        let measured = model.predict(material)?;
        let mut block = Block::new(
            &self.to_string(),
            model,
            measured,
            x.clone(),
            x,
            "",
            "",
            1.0,
            1.0,
        )?;
        (block.rate_per_s, block.temperature_k) = match *self {
            CandidateTest::Tensile { rate, temperature }
            | CandidateTest::Shpb { rate, temperature } => (rate, temperature),
        };
        Ok(block)
    }

    /// The Jacobian of the test's normalized observations in `free` at `material`, as
    /// the test would enter the objective with weight 1 (one model run with its
    /// sensitivities).
    fn jacobian(&self, material: &Material, free: &[&str]) -> Result<DMatrix<f64>> {
        let (model, _) = self.model(material)?;
        let (predicted, jacobian) = model.predict_with_jacobian(material, free)?;
        let scale = predicted.iter().map(|y| y.abs()).sum::<f64>() / predicted.len() as f64;
        Ok(jacobian * ((1.0 / predicted.len() as f64).sqrt() / scale))
    }
}

/// The normalized residuals of `block` at `material` and their Jacobian in the `free`
/// parameters (`objective`'s r_ek and dr_ek/dp).
fn normalized(
    block: &Block,
    material: &Material,
    free: &[&str],
) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let (predicted, jacobian) = block.model.predict_with_jacobian(material, free)?;
    let factor = (block.weight / predicted.len() as f64).sqrt() / block.scale;
    let residuals = predicted
        .iter()
        .zip(&block.measured)
        .map(|(p, y)| factor * (p - y))
        .collect();
    Ok((residuals, jacobian * factor))
}

/// What the parameters' uncertainty would be: standard errors in `free` order, the
/// largest |correlation| and its pair, and ln det Σ.
#[derive(Debug, Clone)]
pub struct Uncertainty {
    pub std_errors: Vec<f64>,
    pub worst_pair: (usize, usize, f64),
    pub ln_det: f64,
}

fn uncertainty(information: &DMatrix<f64>, s2: f64) -> Result<Uncertainty> {
    let k = information.nrows();
    let Some(inverse) = information.clone().try_inverse() else {
        bail!("the parameters are not identified: JᵀJ is singular");
    };
    let cov = inverse * s2;
    let std_errors: Vec<f64> = (0..k).map(|i| cov[(i, i)].max(0.0).sqrt()).collect();
    let mut worst_pair = (0, 0, 0.0f64);
    for i in 0..k {
        for j in i + 1..k {
            let r = cov[(i, j)] / (std_errors[i] * std_errors[j]);
            if r.abs() > worst_pair.2.abs() {
                worst_pair = (i, j, r);
            }
        }
    }
    let ln_det = cov.clone().cholesky().map_or(f64::NAN, |c| {
        2.0 * c.l().diagonal().iter().map(|d| d.ln()).sum::<f64>()
    });
    Ok(Uncertainty {
        std_errors,
        worst_pair,
        ln_det,
    })
}

/// One candidate's expected effect.
#[derive(Debug, Clone)]
pub struct Ranked {
    pub test: CandidateTest,
    /// (det Σ_c / det Σ)^(1/2k): the geometric-mean shrink of the standard errors (< 1).
    pub shrink: f64,
    pub after: Uncertainty,
}

/// The uncertainty now and each candidate's after it, best (smallest shrink) first, for
/// the `free` parameters of `blocks` at the fitted `material`.
pub fn rank(
    blocks: &[&Block],
    material: &Material,
    free: &[&str],
    candidates: &[CandidateTest],
) -> Result<(Uncertainty, Vec<Ranked>)> {
    let k = free.len();
    let mut information = DMatrix::<f64>::zeros(k, k);
    let (mut sum_squares, mut n) = (0.0, 0usize);
    for block in blocks {
        let (r, j) = normalized(block, material, free)
            .with_context(|| format!("experiment `{}`", block.name))?;
        sum_squares += r.iter().map(|x| x * x).sum::<f64>();
        n += r.len();
        information += j.transpose() * j;
    }
    let s2 = sum_squares / n.saturating_sub(k).max(1) as f64;
    let now = uncertainty(&information, s2)?;
    let mut ranked = Vec::new();
    for &test in candidates {
        let j = (test.jacobian(material, free)).with_context(|| format!("candidate {test}"))?;
        let after = uncertainty(&(&information + j.transpose() * j), s2)?;
        let shrink = ((after.ln_det - now.ln_det) / (2.0 * k as f64)).exp();
        ranked.push(Ranked {
            test,
            shrink,
            after,
        });
    }
    ranked.sort_by(|a, b| a.shrink.total_cmp(&b.shrink));
    Ok((now, ranked))
}
