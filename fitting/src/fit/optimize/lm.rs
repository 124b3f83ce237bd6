//! Levenberg-Marquardt on the residuals r(u) of an `Objective` (argmin 0.11 has none).
//!
//! Step: (JᵀJ + λ D) δ = −Jᵀr with Marquardt's scaling D = diag(JᵀJ) (kept at its running
//! maximum, Moré 1978), gain ratio ρ = (S(u) − S(u+δ)) / (S(u) − ‖r + Jδ‖²); accept if
//! ρ > 0 and update λ ← λ max(1/3, 1 − (2ρ − 1)³), else λ ← λν, ν ← 2ν (Nielsen 1999).
//!
//! Stops when the relative decrease of S over an accepted step is below `ftol`, the step
//! is below `xtol` (relative to ‖u‖), the scaled gradient ‖Jᵀr‖∞ is below `gtol`, λ
//! exceeds 1e16, or after `max_iterations`; or when the progress callback asks it to stop
//! (then at the best point evaluated so far, `interrupted`).

use crate::fit::objective::{cost, JacobianKind, Objective};
use crate::fit::optimize::trace::{OptimResult, Progress, Recorder, INTERRUPTED};
use anyhow::Result;
use nalgebra::{DMatrix, DVector};

#[derive(Debug, Clone, Copy)]
pub struct LmOptions {
    pub max_iterations: usize,
    pub ftol: f64,
    pub xtol: f64,
    pub gtol: f64,
    pub lambda0: f64,
}

impl Default for LmOptions {
    fn default() -> Self {
        LmOptions {
            max_iterations: 100,
            ftol: 1e-9,
            xtol: 1e-9,
            gtol: 1e-12,
            lambda0: 1e-3,
        }
    }
}

pub fn levenberg_marquardt(
    objective: &Objective,
    u0: &[f64],
    kind: JacobianKind,
    options: &LmOptions,
    progress: Progress,
) -> Result<OptimResult> {
    let mut rec = Recorder::new(progress);
    rec.begin_iteration(0);
    // A cheap Jacobian comes with every trial point; else only with accepted ones.
    let with_trials = objective.jacobian_is_cheap(kind);
    let (r0, j0) = objective.residuals_and_jacobian(u0, kind)?;
    let mut u = DVector::from_column_slice(u0);
    let mut r = DVector::from_vec(r0);
    let mut jac: DMatrix<f64> = j0;
    let mut s = cost(r.as_slice());
    rec.record(objective.counts(), s, u0);
    let p = u.len();
    let mut lambda = options.lambda0;
    let mut nu = 2.0;
    let mut scale = DVector::<f64>::zeros(p);
    let mut termination = format!("maximum iterations ({})", options.max_iterations);
    let mut converged = false;
    let mut iterations = 0;
    while iterations < options.max_iterations && !rec.stopped() {
        iterations += 1;
        rec.begin_iteration(iterations);
        let a = jac.transpose() * &jac;
        let g = jac.transpose() * &r;
        if g.amax() < options.gtol {
            termination = format!(
                "gradient ‖Jᵀr‖∞ = {:.2e} below {:.0e}",
                g.amax(),
                options.gtol
            );
            converged = true;
            break;
        }
        for k in 0..p {
            scale[k] = scale[k].max(a[(k, k)]).max(1e-30);
        }
        let mut lhs = a.clone();
        for k in 0..p {
            lhs[(k, k)] += lambda * scale[k];
        }
        let step = lhs.cholesky().map(|c| c.solve(&(-&g)));
        let Some(delta) = step else {
            lambda *= nu;
            nu *= 2.0;
            continue;
        };
        if delta.norm() <= options.xtol * (u.norm() + options.xtol) {
            termination = format!("step ‖δu‖ = {:.2e} below tolerance", delta.norm());
            converged = true;
            break;
        }
        let predicted = s - (&r + &jac * &delta).norm_squared();
        let u_new = &u + &delta;
        let trial = if with_trials {
            objective
                .residuals_and_jacobian(u_new.as_slice(), kind)
                .map(|(r, j)| (r, Some(j)))
        } else {
            objective.residuals(u_new.as_slice()).map(|r| (r, None))
        };
        let accepted = match trial {
            Ok((r_new, j_new)) => {
                let s_new = cost(&r_new);
                rec.record(objective.counts(), s_new, u_new.as_slice());
                if rec.stopped() {
                    break;
                }
                let rho = (s - s_new) / predicted;
                if rho > 0.0 && s_new.is_finite() {
                    let decrease = s - s_new;
                    u = u_new;
                    r = DVector::from_vec(r_new);
                    jac = match j_new {
                        Some(j) => j,
                        None => objective.residuals_and_jacobian(u.as_slice(), kind)?.1,
                    };
                    s = s_new;
                    lambda *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
                    nu = 2.0;
                    if decrease <= options.ftol * s {
                        termination = format!(
                            "relative decrease of S {:.2e} below {:.0e}",
                            decrease / s,
                            options.ftol
                        );
                        converged = true;
                        break;
                    }
                    true
                } else {
                    false
                }
            }
            // A failed model run (e.g. an extreme trial point) counts as a rejected step.
            Err(_) => false,
        };
        if !accepted {
            lambda *= nu;
            nu *= 2.0;
            if lambda > 1e16 {
                termination = "damping λ exceeded 1e16 (no further decrease)".into();
                converged = true;
                break;
            }
        }
    }
    let interrupted = rec.stopped();
    if interrupted {
        let (best, s_best) = rec.best();
        (u, s) = (DVector::from_column_slice(best), s_best);
        (termination, converged) = (INTERRUPTED.to_string(), false);
    }
    let name = match kind {
        _ if with_trials => "Levenberg-Marquardt (exact AD Jacobian)",
        JacobianKind::Exact => {
            "Levenberg-Marquardt (each model's Jacobian: AD, or finite differences of an MPM level)"
        }
        JacobianKind::FiniteDifference => "Levenberg-Marquardt (finite-difference Jacobian)",
    };
    Ok(OptimResult {
        optimizer: name.into(),
        u: u.as_slice().to_vec(),
        cost: s,
        iterations,
        termination,
        converged,
        interrupted,
        wall_s: rec.elapsed(),
        history: rec.history,
    })
}
