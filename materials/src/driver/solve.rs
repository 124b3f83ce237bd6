//! The driver's step loop: Newton on the stress-controlled components of F.

use super::load_path::{Control, LoadPath, Temperature};
use super::output::Record;
use crate::ad;
use crate::error::MaterialError;
use crate::material::{Model, State};
use crate::scalar::{c, Scalar};
use crate::tensor::M3;
use nalgebra::{DMatrix, DVector};
use thiserror::Error;

#[derive(Debug, Error)]
pub enum DriverError {
    #[error("load path: {0}")]
    Path(String),
    /// The material's own error is the source (printed after this message by `{:#}`).
    #[error("step {step} (t = {time:e} s): material update failed")]
    Material {
        step: usize,
        time: f64,
        source: MaterialError,
    },
    #[error("step {step} (t = {time:e} s): Newton on the stress-controlled components did not converge in {iterations} iterations (residual {residual:e} Pa)")]
    NotConverged {
        step: usize,
        time: f64,
        iterations: usize,
        residual: f64,
    },
}

const MAX_ITERATIONS: usize = 30;
/// Stress residual tolerance relative to the P-wave modulus (≈ 30 Pa for steel).
const REL_TOL: f64 = 1e-10;

fn validate(path: &LoadPath) -> Result<Vec<(usize, usize)>, DriverError> {
    if path.times.len() < 2 {
        return Err(DriverError::Path("needs at least two times".into()));
    }
    if path
        .times
        .windows(2)
        .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
    {
        return Err(DriverError::Path(
            "times must be strictly increasing".into(),
        ));
    }
    let mut unknown = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            if let Control::Stress(_) = path.controls[i][j] {
                if i != j {
                    if let Control::Stress(_) = path.controls[j][i] {
                        return Err(DriverError::Path(format!(
                            "σ_{i}{j} and σ_{j}{i} are the same equation (σ is symmetric): prescribe F_{j}{i} instead"
                        )));
                    }
                }
                unknown.push((i, j));
            }
        }
    }
    Ok(unknown)
}

fn target(control: &Control, t: f64) -> f64 {
    match control {
        Control::Kinematic(r) | Control::Stress(r) => r.at(t),
    }
}

/// Run the load path with `model` (any scalar type); one record per time in `path.times`.
pub fn run<D: Scalar, M: Model<D>>(
    model: &M,
    path: &LoadPath,
) -> Result<Vec<Record<D>>, DriverError> {
    let unknown = validate(path)?;
    let model_re = model.map_params(|_, v| v.re());
    let tol = REL_TOL * model_re.p_wave_modulus();
    let kinematic_f = |t: f64, f: &mut M3<f64>| {
        for i in 0..3 {
            for j in 0..3 {
                if let Control::Kinematic(r) = &path.controls[i][j] {
                    f[(i, j)] = r.at(t);
                }
            }
        }
    };
    let set_temperature = |state: &mut State<D>, t: f64| {
        if let Temperature::Prescribed(r) = &path.temperature {
            state.theta = c(r.at(t));
        }
    };

    let mut f = M3::<f64>::identity();
    let mut state = model.initial_state();
    let mut records = Vec::with_capacity(path.times.len());
    let mut du_last = vec![0.0; unknown.len()];

    // Step 0 solves the stress controls at the initial time too (e.g. free thermal
    // expansion at a prescribed temperature); its time step is that of step 1.
    for step in 0..path.times.len() {
        let t = path.times[step];
        let dt = path.times[step.max(1)] - path.times[step.max(1) - 1];
        set_temperature(&mut state, t);
        let state_re = state.re();
        let material = |source| DriverError::Material {
            step,
            time: t,
            source,
        };
        let f_before = f;
        kinematic_f(t, &mut f);
        for (k, &(i, j)) in unknown.iter().enumerate() {
            f[(i, j)] += du_last[k];
        }
        // Newton in f64 on σ_u(F) = target.
        let mut jac = DMatrix::<f64>::zeros(unknown.len(), unknown.len());
        let mut converged = unknown.is_empty();
        let mut residual = 0.0;
        for _ in 0..MAX_ITERATIONS {
            if unknown.is_empty() {
                break;
            }
            let (sigma, tangent, _) =
                ad::tangent(&model_re, &f, dt, &state_re).map_err(material)?;
            let r = DVector::from_iterator(
                unknown.len(),
                unknown
                    .iter()
                    .map(|&(i, j)| sigma[(i, j)] - target(&path.controls[i][j], t)),
            );
            residual = r.amax();
            for (a, &(i, j)) in unknown.iter().enumerate() {
                for (b, &(k, l)) in unknown.iter().enumerate() {
                    jac[(a, b)] = tangent[(3 * i + j, 3 * k + l)];
                }
            }
            if residual < tol {
                converged = true;
                break;
            }
            let du = jac
                .clone()
                .lu()
                .solve(&(-r))
                .ok_or(DriverError::NotConverged {
                    step,
                    time: t,
                    iterations: 0,
                    residual,
                })?;
            for (k, &(i, j)) in unknown.iter().enumerate() {
                f[(i, j)] += du[k];
            }
        }
        if !converged {
            return Err(DriverError::NotConverged {
                step,
                time: t,
                iterations: MAX_ITERATIONS,
                residual,
            });
        }
        for (k, &(i, j)) in unknown.iter().enumerate() {
            du_last[k] = f[(i, j)] - f_before[(i, j)];
        }
        let mut f_d: M3<D> = f.map(c);
        if D::NDERIV > 0 && !unknown.is_empty() {
            // Implicit-function step: du/dp = −J⁻¹ ∂σ_u/∂p.
            let jac_inv = jac.clone().try_inverse().ok_or(DriverError::NotConverged {
                step,
                time: t,
                iterations: 0,
                residual,
            })?;
            let (sigma_d, _) = model.update(&f_d, dt, &state).map_err(material)?;
            let r_d: Vec<D> = unknown
                .iter()
                .map(|&(i, j)| sigma_d[(i, j)] - c::<D>(target(&path.controls[i][j], t)))
                .collect();
            for (a, &(i, j)) in unknown.iter().enumerate() {
                for (b, r_b) in r_d.iter().enumerate() {
                    f_d[(i, j)] -= *r_b * jac_inv[(a, b)];
                }
            }
        }
        let (sigma, new_state) = model.update(&f_d, dt, &state).map_err(material)?;
        state = new_state;
        // A held temperature stays held: the plastic heating of the step is taken away.
        set_temperature(&mut state, t);
        records.push(Record {
            time: t,
            f: f_d,
            sigma,
            state,
        });
    }
    Ok(records)
}
