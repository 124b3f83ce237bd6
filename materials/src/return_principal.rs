//! Fast return mapping in principal logarithmic stretches (isotropy, thesis 4.3.6).
//!
//! At the converged state N is coaxial with the trial be = Fe Fe^T, so eq. 4.48 becomes,
//! in the eigenbasis v_a of the trial be with logarithmic stretches ε_a = ½ ln λ_a²,
//!   ε_a = ε_a^tr − √(3/2) Δα n_a,   n_a = s_a / ‖s‖,   s_a = G (e^{2ε_a} − mean e^{2ε}),
//!   φ = √(3/2) ‖s‖ − τ_y(α_n + Δα, Δα/Δt, θ_n) = 0,
//! 4 unknowns (ε_1..3, ln Δα) instead of 10 (ln Δα as in `return_reference`). Then Fe = exp(−√(3/2) Δα N) Fe^tr with
//! exp(−√(3/2) Δα N) = Σ_a exp(−√(3/2) Δα n_a) v_a v_aᵀ and Fp⁻¹ = F⁻¹ Fe.
//! The volumetric part ln J^e is unchanged (tr N = 0), so det Fp = 1 holds exactly.

use crate::error::MaterialError;
use crate::local_newton;
use crate::material::State;
use crate::plasticity::ElastoPlastic;
use crate::tensor::{inverse, M3};
use nalgebra::{SMatrix, SVector, SymmetricEigen, Vector3};

/// Most scalar Newton steps of the first guess for ln Δα, and the step that ends them
/// (the error left is then O(step²), which the 4×4 Newton removes in one step).
const SCALAR_GUESS_STEPS: usize = 12;
const SCALAR_GUESS_TOL: f64 = 1e-5;

/// The fixed data of one local problem.
struct Problem<T: Fn(f64) -> (f64, f64)> {
    g: f64,
    eps_trial: Vector3<f64>,
    /// (τ_y, dτ_y/du) at u = ln Δα.
    tau_y: T,
}

impl<T: Fn(f64) -> (f64, f64)> Problem<T> {
    /// Residual r(y) and its Jacobian, derived by hand (this is the hot path):
    /// ∂s_a/∂ε_b = 2G (b_a δ_ab − b_b/3), ∂‖s‖/∂ε_b = 2G n_b b_b (Σ n_a = 0),
    /// ∂n_a/∂ε_b = (∂s_a/∂ε_b − n_a ∂‖s‖/∂ε_b)/‖s‖.
    fn eval(&self, y: &SVector<f64, 4>) -> (SVector<f64, 4>, SMatrix<f64, 4, 4>) {
        let k = 1.5f64.sqrt();
        let g = self.g;
        let b = Vector3::new((2.0 * y[0]).exp(), (2.0 * y[1]).exp(), (2.0 * y[2]).exp());
        let mean = b.mean();
        let s = b.add_scalar(-mean) * g;
        let s_norm = s.norm();
        let n = s / s_norm;
        let dalpha = y[3].exp();
        let (tau_y, dtau_y_du) = (self.tau_y)(y[3]);
        let mut r = SVector::<f64, 4>::zeros();
        let mut jac = SMatrix::<f64, 4, 4>::zeros();
        for a in 0..3 {
            r[a] = y[a] - self.eps_trial[a] + k * dalpha * n[a];
            for bb in 0..3 {
                let ds = 2.0 * g * (if a == bb { b[a] } else { 0.0 } - b[bb] / 3.0);
                let dn = (ds - n[a] * 2.0 * g * n[bb] * b[bb]) / s_norm;
                jac[(a, bb)] = if a == bb { 1.0 } else { 0.0 } + k * dalpha * dn;
            }
            jac[(a, 3)] = k * dalpha * n[a];
            jac[(3, a)] = 2.0 * k * n[a] * b[a];
        }
        r[3] = (k * s_norm - tau_y) / g;
        jac[(3, 3)] = -dtau_y_du / g;
        (r, jac)
    }
}

/// Solve the local problem in real arithmetic from the first guess `dalpha0` > 0;
/// returns (Fp⁻¹, α).
pub fn solve(
    m: &ElastoPlastic<f64>,
    f: &M3<f64>,
    old: &State<f64>,
    dt: f64,
    dalpha0: f64,
) -> Result<(M3<f64>, f64), MaterialError> {
    let fe_trial = f * old.fp_inv;
    let be_trial = fe_trial * fe_trial.transpose();
    let eigen = SymmetricEigen::new(be_trial);
    let b_trial = eigen.eigenvalues;
    let eps_trial = b_trial.map(|l2| 0.5 * l2.ln());
    let g = m.elastic.shear_modulus();
    let k = 1.5f64.sqrt();
    // First guess: the radial return of the Neo-Hooke deviator s = G dev be, linearized in
    // Δα: b_a = b_a^tr e^{−2k Δα n_a} gives dq/dΔα = −3 G̃ with G̃ = G Σ n_a² b_a^tr
    // (k = √(3/2), Σ n_a = 0), so q^tr − 3 G̃ Δα = τ_y(α_n + Δα, Δα/Δt, θ_n) is solved by
    // scalar Newton steps in u = ln Δα, with the rate and hardening terms of the flow
    // stress. `dalpha0` = (q^tr − τ_y(α_n, 0))/(3G) is the rate-free upper bound it starts from.
    // q^tr − τ_y(Δα) is a small difference of large numbers, so q^tr must be the Neo-Hooke
    // value: a log-strain (Hencky) estimate is off by O(ε_e) in q and by percents in Δα.
    let s_trial = b_trial.add_scalar(-b_trial.mean()) * g;
    let q_trial = k * s_trial.norm();
    let n_trial = s_trial / s_trial.norm();
    let g_tilde = g * n_trial.component_mul(&n_trial).dot(&b_trial);
    let tau_y = m
        .flow
        .along_log_increment(old.alpha, dt, old.theta, m.thermal.theta0);
    let mut u = (dalpha0 * g / g_tilde).ln();
    for _ in 0..SCALAR_GUESS_STEPS {
        let (t, dt_du) = tau_y(u);
        let dalpha = u.exp();
        let step = (q_trial - 3.0 * g_tilde * dalpha - t) / (3.0 * g_tilde * dalpha + dt_du);
        u += step.clamp(-1.0, 1.0);
        if step.abs() < SCALAR_GUESS_TOL {
            break;
        }
    }
    let shift = n_trial * (k * u.exp());
    let y0 = SVector::<f64, 4>::new(
        eps_trial[0] - shift[0],
        eps_trial[1] - shift[1],
        eps_trial[2] - shift[2],
        u,
    );
    let problem = Problem {
        g,
        eps_trial,
        tau_y,
    };
    let y = local_newton::solve(|y| problem.eval(y), y0)?;
    let dalpha = y[3].exp();
    // exp(−√(3/2) Δα N) = diag(λ_a / λ_a^tr) in the eigenbasis.
    let ratio = Vector3::new(
        y[0] - eps_trial[0],
        y[1] - eps_trial[1],
        y[2] - eps_trial[2],
    )
    .map(f64::exp);
    let v = eigen.eigenvectors;
    let flow = v * M3::from_diagonal(&ratio) * v.transpose();
    let f_inv = inverse(f).ok_or(MaterialError::InvertedDeformation {
        det_f: f.determinant(),
    })?;
    Ok((f_inv * flow * fe_trial, old.alpha + dalpha))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flow_stress::{FlowStress, JohnsonCookLaw};
    use crate::plasticity::{ReturnMap, Thermal};

    #[test]
    fn hand_jacobian_matches_central_differences() {
        let m = ElastoPlastic {
            elastic: crate::elastic::Elastic {
                e: 200e9,
                nu: 0.3,
                rho: 7800.0,
            },
            flow: FlowStress::JohnsonCook(JohnsonCookLaw {
                a: 800e6,
                b: 1500e6,
                n: 0.3,
                c: 0.03,
                m: 1.2,
                alpha_dot0: 1e-3,
                theta_m: 1800.0,
            }),
            thermal: Thermal {
                theta0: 293.15,
                c_theta: 460.0,
                alpha_sigma: 1.2e-5,
                gamma_tq: 0.9,
            },
            return_map: ReturnMap::Principal,
        };
        let p = Problem {
            g: m.elastic.shear_modulus(),
            eps_trial: Vector3::new(0.03, -0.01, -0.015),
            tau_y: m
                .flow
                .along_log_increment(0.1, 1e-5, 350.0, m.thermal.theta0),
        };
        let y = SVector::<f64, 4>::new(0.02, -0.008, -0.012, (0.004f64).ln());
        let (_, jac) = p.eval(&y);
        let h = 1e-7;
        for j in 0..4 {
            let (mut yp, mut ym) = (y, y);
            yp[j] += h;
            ym[j] -= h;
            let col = (p.eval(&yp).0 - p.eval(&ym).0) / (2.0 * h);
            let err = (col - jac.column(j)).norm() / jac.column(j).norm();
            assert!(err < 1e-6, "column {j}: relative error {err:e}");
        }
    }
}
