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
use crate::scalar::{c, Scalar};
use crate::tensor::{inverse, M3};
use nalgebra::{SVector, SymmetricEigen, Vector3};
use num_dual::{jacobian, DualSVec64};

fn residual<E: Scalar>(
    m: &ElastoPlastic<E>,
    y: &SVector<E, 4>,
    eps_trial: &Vector3<f64>,
    old: &State<f64>,
    dt: f64,
) -> SVector<E, 4> {
    let g = m.elastic.shear_modulus();
    let b = [(y[0] * 2.0).exp(), (y[1] * 2.0).exp(), (y[2] * 2.0).exp()];
    let mean = (b[0] + b[1] + b[2]) / c::<E>(3.0);
    let s = [(b[0] - mean) * g, (b[1] - mean) * g, (b[2] - mean) * g];
    let s_norm = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    let sqrt_3_2 = c::<E>(1.5f64.sqrt());
    let dalpha = y[3].exp();
    let mut r = SVector::<E, 4>::from_element(c(0.0));
    for a in 0..3 {
        r[a] = y[a] - c::<E>(eps_trial[a]) + sqrt_3_2 * dalpha * s[a] / s_norm;
    }
    let theta = c::<E>(old.theta);
    r[3] = (sqrt_3_2 * s_norm - m.tau_y(c::<E>(old.alpha) + dalpha, dalpha, dt, theta)) / g;
    r
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
    let eps_trial = eigen.eigenvalues.map(|l2| 0.5 * l2.ln());
    let m_d: ElastoPlastic<DualSVec64<4>> = m.lift();
    // First guess: radial return in logarithmic strain, where the Neo-Hooke deviator is
    // ≈ 2G dev ε. (The trial Kirchhoff stress grows like e^{2ε} and overestimates Δα at
    // large increments.)
    let dev_trial = eps_trial.add_scalar(-eps_trial.mean());
    let sqrt_3_2 = 1.5f64.sqrt();
    let g = m.elastic.shear_modulus();
    let tau_y0 = m.tau_y(old.alpha, 0.0, dt, old.theta);
    let dalpha_log = (sqrt_3_2 * 2.0 * g * dev_trial.norm() - tau_y0) / (3.0 * g);
    let dalpha0 = if dalpha_log > 0.0 {
        dalpha_log.min(dalpha0)
    } else {
        dalpha0
    };
    let shift = dev_trial * (sqrt_3_2 * dalpha0 / dev_trial.norm());
    let y0 = SVector::<f64, 4>::new(
        eps_trial[0] - shift[0],
        eps_trial[1] - shift[1],
        eps_trial[2] - shift[2],
        dalpha0.ln(),
    );
    let (y, _) = local_newton::solve(
        |y| jacobian(|yd| residual(&m_d, &yd, &eps_trial, old, dt), y),
        y0,
    )?;
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
