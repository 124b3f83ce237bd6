//! The principal return in dual arithmetic: the derivatives of Fp⁻¹ and α along the dual
//! directions (material parameters, or F and the old state) of a return already solved in
//! real arithmetic by `return_principal`, by the implicit function theorem in its four
//! unknowns y = (ε_1..3, ln Δα) instead of the reference return's ten.
//!
//! 1. The trial b^tr = Fe^tr Fe^trᵀ in the real eigenbasis V of its real part: the
//!    eigenvalues λ_a^tr = (Vᵀ b^tr V)_aa carry their exact first derivatives (a
//!    symmetric matrix's eigenvalue moves by v_aᵀ db v_a), and ε_a^tr = ½ ln λ_a^tr.
//! 2. The implicit function theorem at the converged real y*: dy = −K⁻¹ dr, K = ∂r/∂y
//!    real (`return_principal`'s hand Jacobian), dr the residual's derivatives at fixed
//!    y* (through ε^tr, and through τ_y/G: the parameters, α_n and θ_n).
//! 3. The flow tensor M = exp(−√(3/2) Δα N) = Σ_a m_a v_a v_aᵀ, m_a = exp(ε_a − ε_a^tr), is
//!    an isotropic function of b^tr; its derivative in the eigenbasis (Miehe's formula for
//!    isotropic tensor functions) is dm_a on the diagonal and
//!    Θ_ab (Vᵀ db V)_ab off it, Θ_ab = (m_a − m_b)/(λ_a − λ_b), with the limit
//!    Θ_ab = ∂m_a/∂λ_a − ∂m_a/∂λ_b (∂m_a/∂λ_b = m_a (K⁻¹_ab − δ_ab)/(2λ_b), where
//!    K⁻¹_ab = ∂ε_a/∂ε_b^tr) where the two trial eigenvalues coincide within `COINCIDENT`
//!    (the quotient's round-off and the limit's O(λ_a − λ_b) error are then both about
//!    1e-8 of Θ).
//! 4. Fe = M Fe^tr and α = α_n + Δα in dual arithmetic, and Fp⁻¹ = F⁻¹ Fe from the real
//!    F⁻¹: dFp⁻¹ = F⁻¹ (dFe − dF Fp⁻¹).
//! 5. τ in the trial eigenbasis, where the real parts of M and b^tr are diagonal: the
//!    elastic stretch b^e = M b^tr M has m_a² λ_a^tr on the diagonal and
//!    (m_a λ_a^tr + m_b λ_b^tr) dM_ab + m_a m_b db^tr_ab off it, and ln J^e = Σ_a ε_a, so
//!    Neo-Hooke's τ = G (b^e − I) + (Λ ln J^e − 3 α_σ κ (θ − θ0)) I needs neither a dual
//!    b^e = Fe Feᵀ nor a logarithm.
//!
//! A point at or above melting (`return_principal::molten`) has ε_a = mean ε^tr in closed
//! form: steps 1, 3, 4 and 5 with ∂ε_a/∂ε_b^tr = 1/3 (`molten_step`).
//!
//! Real parts are the real return's y* and what follows from them, so they agree with it
//! to round-off: y* and K⁻¹ as the run's batched return kept them (`solve_batch` with
//! `keep`, `Model::update_batch_keeping`), or else formed again from its Fp⁻¹ and Δα (ε_a
//! from the stretches of Fe = F Fp⁻¹ in the trial eigenbasis, the onset of flow, K⁻¹ by
//! blocks). The derivatives are those of
//! the reference return's implicit step (`return_reference::implicit_step`, the same
//! equations in 10 unknowns), which the tests compare.

use crate::error::MaterialError;
use crate::material::{Converged, State};
use crate::plasticity::{return_principal, ElastoPlastic, Flowed};
use crate::scalar::{c, Scalar};
use crate::sym_eigen;
use crate::tensor::{
    inverse, mul_in, mul_real_left_in, mul_real_right_in, mul_transpose_self_in, re,
    rotate_into_in, rotate_out_in, symmetric_in, M3,
};
use nalgebra::{Matrix3, SVector, Vector3};

/// Relative gap of two trial eigenvalues below which Θ_ab takes its limit.
const COINCIDENT: f64 = 1e-8;

/// The derivatives of the local problem's residual r(y) along the dual directions at a
/// fixed y = (ε_1..3, ln Δα), `return_principal`'s equations:
/// r_a = ε_a − ε_a^tr + √(3/2) Δα n_a moves with ε_a^tr alone (n = s/‖s‖ with
/// s_a = G (e^{2ε_a} − mean e^{2ε}) does not depend on G), and
/// r_4 = √(3/2) ‖s‖/G − τ_y(α_n + Δα, Δα/Δt, θ_n)/G with τ_y/G alone (‖s‖/G does not).
/// Real parts zero.
fn residual_derivatives<D: Scalar>(
    m: &ElastoPlastic<D>,
    eps_trial: &Vector3<D>,
    old: &State<D>,
    dt: f64,
    dalpha: f64,
) -> SVector<D, 4> {
    // −dx: the derivative part of x, negated (r_a = … − ε_a^tr, r_4 = … − τ_y/G)
    let minus_d = |x: D| c::<D>(x.re()) - x;
    let tau_y = m.tau_y(old.alpha + c::<D>(dalpha), c::<D>(dalpha), dt, old.theta);
    SVector::<D, 4>::new(
        minus_d(eps_trial[0]),
        minus_d(eps_trial[1]),
        minus_d(eps_trial[2]),
        minus_d(tau_y / m.elastic.shear_modulus()),
    )
}

/// Fp⁻¹, τ and α with their derivatives, from the real return (`fp_inv`, `dalpha` = Δα)
/// of the same F and old state, and its y* and K⁻¹ where the run kept them (else formed
/// here from Fp⁻¹ and Δα, `converged_again`); `in_plane` where F, Fp⁻¹_n and their
/// derivatives keep the z axis (`RealUpdate::in_plane`).
pub fn implicit_step<D: Scalar>(
    m: &ElastoPlastic<D>,
    f: &M3<D>,
    old: &State<D>,
    dt: f64,
    (fp_inv, dalpha, converged, in_plane): (&M3<f64>, f64, Option<&Converged>, bool),
) -> Result<Flowed<D>, MaterialError> {
    let real = (fp_inv, dalpha, converged);
    match in_plane {
        true => implicit_step_in::<true, D>(m, f, old, dt, real),
        false => implicit_step_in::<false, D>(m, f, old, dt, real),
    }
}

/// `implicit_step` of tensors with the structure `IN_PLANE` (`tensor::mul_in`).
fn implicit_step_in<const IN_PLANE: bool, D: Scalar>(
    m: &ElastoPlastic<D>,
    f: &M3<D>,
    old: &State<D>,
    dt: f64,
    (fp_inv, dalpha, converged): (&M3<f64>, f64, Option<&Converged>),
) -> Result<Flowed<D>, MaterialError> {
    let trial = TrialBasis::<D, IN_PLANE>::new(f, old);
    let Converged { y: y_real, k_inv } = match converged {
        Some(kept) => *kept,
        None => converged_again(m, f, old, dt, (&trial, fp_inv, dalpha))?,
    };
    let dr = residual_derivatives(m, &trial.eps, old, dt, dalpha);
    let y = SVector::<D, 4>::from_fn(|i, _| {
        (0..4).fold(c::<D>(y_real[i]), |y_i, j| y_i - dr[j] * k_inv[(i, j)])
    });
    let eps = Vector3::new(y[0], y[1], y[2]);
    let deps = k_inv.fixed_view::<3, 3>(0, 0).into_owned();
    let (fp_inv, tau) = trial.flow_back(m, f, old.theta, &eps, &deps)?;
    // Δα = e^{y_4}: d(Δα) = Δα dy_4, its value the run's
    let dalpha_d = (y[3] - c::<D>(y_real[3]) + c::<D>(1.0)) * c::<D>(dalpha);
    Ok(Flowed {
        fp_inv,
        tau,
        alpha: old.alpha + dalpha_d,
    })
}

/// y* and K⁻¹ of the run's return formed again from its Fp⁻¹ and Δα: ε_a = ½ ln λ_a^e in
/// the trial eigenbasis, the onset of flow, and K⁻¹ by blocks.
fn converged_again<const IN_PLANE: bool, D: Scalar>(
    m: &ElastoPlastic<D>,
    f: &M3<D>,
    old: &State<D>,
    dt: f64,
    (trial, fp_inv, dalpha): (&TrialBasis<D, IN_PLANE>, &M3<f64>, f64),
) -> Result<Converged, MaterialError> {
    let (m_re, old_re) = (m.re(), old.re());
    // λ_a^e = (Vᵀ Fe Feᵀ V)_aa = |Feᵀ v_a|², Fe = F Fp⁻¹ of the run's return
    let fe_t = (re(f) * fp_inv).transpose();
    let stretch = |a: usize| (fe_t * trial.vectors.column(a)).norm_squared();
    let y_real = SVector::<f64, 4>::new(
        0.5 * stretch(0).ln(),
        0.5 * stretch(1).ln(),
        0.5 * stretch(2).ln(),
        dalpha.ln(),
    );
    let onset = m_re
        .flow
        .onset(old_re.alpha, old_re.theta, m_re.thermal.theta0);
    let eps_trial_re = trial.eps.map(|e| e.re());
    let k_inv = return_principal::local_jacobian_inverse(&m_re, eps_trial_re, &onset, dt, &y_real)
        .ok_or(MaterialError::Singular {
            what: "principal return (implicit step)",
        })?;
    Ok(Converged { y: y_real, k_inv })
}

/// Fp⁻¹, τ and α with their derivatives for a point at or above melting
/// (`return_principal::molten`): the whole deviatoric trial strain flows, ε_a = mean ε^tr
/// and Δα = √(2/3) ‖dev ε^tr‖, closed forms in ε^tr, so ∂ε_a/∂ε_b^tr = 1/3 takes the place
/// of K⁻¹ in step 3; `in_plane` as in `implicit_step`.
pub fn molten_step<D: Scalar>(
    m: &ElastoPlastic<D>,
    f: &M3<D>,
    old: &State<D>,
    in_plane: bool,
) -> Result<Flowed<D>, MaterialError> {
    match in_plane {
        true => molten_step_in::<true, D>(m, f, old),
        false => molten_step_in::<false, D>(m, f, old),
    }
}

/// `molten_step` of tensors with the structure `IN_PLANE`.
fn molten_step_in<const IN_PLANE: bool, D: Scalar>(
    m: &ElastoPlastic<D>,
    f: &M3<D>,
    old: &State<D>,
) -> Result<Flowed<D>, MaterialError> {
    let trial = TrialBasis::<D, IN_PLANE>::new(f, old);
    let mean = trial.eps.sum() / c::<D>(3.0);
    let dev = trial.eps.map(|e| e - mean);
    let dalpha = dev.dot(&dev).sqrt() * c::<D>((2.0f64 / 3.0).sqrt());
    let eps = Vector3::repeat(mean);
    let (fp_inv, tau) = trial.flow_back(m, f, old.theta, &eps, &Matrix3::repeat(1.0 / 3.0))?;
    Ok(Flowed {
        fp_inv,
        tau,
        alpha: old.alpha + dalpha,
    })
}

/// The trial state in the real eigenbasis of b^tr (step 1 of the module doc), of tensors
/// with the structure `IN_PLANE`.
struct TrialBasis<D, const IN_PLANE: bool> {
    fe: M3<D>,
    /// V, the real eigenvectors of b^tr.
    vectors: M3<f64>,
    /// Vᵀ b^tr V: λ_a^tr on the diagonal, the derivatives of the off-diagonal terms.
    in_basis: M3<D>,
    /// ε_a^tr = ½ ln λ_a^tr.
    eps: Vector3<D>,
}

impl<D: Scalar, const IN_PLANE: bool> TrialBasis<D, IN_PLANE> {
    #[inline(always)]
    fn new(f: &M3<D>, old: &State<D>) -> Self {
        let fe = mul_in::<IN_PLANE, D>(f, &old.fp_inv);
        let b = mul_transpose_self_in::<IN_PLANE, D>(&fe);
        // in plane, e_z is the third eigenvector (`sym_eigen`)
        let vectors = sym_eigen::decompose(&re(&b)).vectors;
        let in_basis = rotate_into_in::<IN_PLANE, D>(&vectors, &b);
        let eps = Vector3::from_fn(|a, _| in_basis[(a, a)].ln() * c::<D>(0.5));
        TrialBasis {
            fe,
            vectors,
            in_basis,
            eps,
        }
    }

    /// Fp⁻¹ = F⁻¹ M Fe^tr and τ at temperature `theta` from the returned strains `eps`
    /// (ε_a) and their real derivatives `deps` = ∂ε/∂ε^tr (steps 3 to 5).
    #[inline(always)]
    fn flow_back(
        &self,
        m: &ElastoPlastic<D>,
        f: &M3<D>,
        theta: D,
        eps: &Vector3<D>,
        deps: &Matrix3<f64>,
    ) -> Result<(M3<D>, M3<D>), MaterialError> {
        let ratio = Vector3::from_fn(|a, _| (eps[a] - self.eps[a]).exp());
        let flow_in_basis = flow_in_eigenbasis::<IN_PLANE, D>(&ratio, &self.in_basis, deps);
        let flow = rotate_out_in::<IN_PLANE, D>(&self.vectors, &flow_in_basis);
        let fe = mul_in::<IN_PLANE, D>(&flow, &self.fe);
        let fp_inv = plastic_part::<IN_PLANE, D>(f, &fe)?;
        Ok((fp_inv, self.stress(m, theta, eps, &flow_in_basis)))
    }

    /// τ from the returned strains `eps` and the flow M in the trial eigenbasis (step 5):
    /// Neo-Hooke's τ of the elastic stretch b^e = M b^tr M and ln J^e = Σ_a ε_a.
    #[inline(always)]
    fn stress(&self, m: &ElastoPlastic<D>, theta: D, eps: &Vector3<D>, flow: &M3<D>) -> M3<D> {
        let trial = &self.in_basis;
        // m_a λ_a^tr
        let stretch = |a: usize| flow[(a, a)].re() * trial[(a, a)].re();
        let elastic_stretch = symmetric_in::<IN_PLANE, D>(|a, b| match a == b {
            true => flow[(a, a)] * flow[(a, a)] * trial[(a, a)],
            false => {
                let d_trial = trial[(a, b)] - c::<D>(trial[(a, b)].re());
                let m_ab = flow[(a, a)].re() * flow[(b, b)].re();
                flow[(a, b)] * (stretch(a) + stretch(b)) + d_trial * m_ab
            }
        });
        let ln_j = eps[0] + eps[1] + eps[2];
        let (dtheta, alpha_sigma) = (theta - m.thermal.theta0, m.thermal.alpha_sigma);
        let tau =
            m.elastic
                .tau_of_stretch_in::<IN_PLANE>(&elastic_stretch, ln_j, dtheta, alpha_sigma);
        rotate_out_in::<IN_PLANE, D>(&self.vectors, &tau)
    }
}

/// Fp⁻¹ = F⁻¹ Fe with F⁻¹ real (step 4): dFp⁻¹ = F⁻¹ (dFe − dF Fp⁻¹), two products with a
/// real factor where a dual inverse and a dual product would do the same.
#[inline(always)]
fn plastic_part<const IN_PLANE: bool, D: Scalar>(
    f: &M3<D>,
    fe: &M3<D>,
) -> Result<M3<D>, MaterialError> {
    let f_re = re(f);
    let f_inv = inverse(&f_re).ok_or(MaterialError::InvertedDeformation {
        det_f: f_re.determinant(),
    })?;
    let fp_inv = mul_in::<IN_PLANE, f64>(&f_inv, &re(fe));
    let df = f.map(|x| x - c::<D>(x.re()));
    let dfe = fe - mul_real_right_in::<IN_PLANE, D>(&df, &fp_inv);
    Ok(mul_real_left_in::<IN_PLANE, D>(&f_inv, &dfe))
}

/// M = exp(−√(3/2) Δα N) in the trial eigenbasis, with its derivatives (step 3 of the
/// module doc): `ratio` the m_a, `in_basis` Vᵀ b^tr V (diagonal λ_a^tr), `deps`
/// ∂ε_a/∂ε_b^tr.
#[inline(always)]
fn flow_in_eigenbasis<const IN_PLANE: bool, D: Scalar>(
    ratio: &Vector3<D>,
    in_basis: &M3<D>,
    deps: &Matrix3<f64>,
) -> M3<D> {
    let lambda = Vector3::from_fn(|a, _| in_basis[(a, a)].re());
    let m = ratio.map(|m| m.re());
    let theta = |a: usize, b: usize| {
        let gap = lambda[a] - lambda[b];
        if gap.abs() > COINCIDENT * lambda[a].max(lambda[b]) {
            (m[a] - m[b]) / gap
        } else {
            // ∂m_a/∂λ_b, symmetrized over the pair
            let slope = |a: usize, b: usize| {
                let delta = if a == b { 1.0 } else { 0.0 };
                m[a] * (deps[(a, b)] - delta) / (2.0 * lambda[b])
            };
            0.5 * (slope(a, a) - slope(a, b) + slope(b, b) - slope(b, a))
        }
    };
    symmetric_in::<IN_PLANE, D>(|a, b| {
        if a == b {
            ratio[a]
        } else {
            (in_basis[(a, b)] - c::<D>(in_basis[(a, b)].re())) * c::<D>(theta(a, b))
        }
    })
}

#[cfg(test)]
mod tests {
    use crate::ad::seed_named;
    use crate::elastic::Elastic;
    use crate::flow_stress::{FlowStress, JohnsonCookLaw};
    use crate::material::{Model, RealUpdate, State};
    use crate::plasticity::{ElastoPlastic, ReturnMap, Thermal};
    use crate::tensor::M3;

    /// Directions: A, B, N, C, M, then F_00, F_01 and F_12, then α_n.
    type D9 = crate::dual::Dual<9>;
    const PARAMETERS: [&str; 9] = ["A", "B", "N", "C", "M", "", "", "", ""];
    const DT: f64 = 1e-7;

    /// A 4340-like Johnson-Cook steel with the given return mapping.
    fn steel(return_map: ReturnMap) -> ElastoPlastic<f64> {
        ElastoPlastic {
            elastic: Elastic {
                e: 200e9,
                nu: 0.29,
                rho: 7830.0,
            },
            flow: FlowStress::JohnsonCook(JohnsonCookLaw {
                a: 792e6,
                b: 510e6,
                n: 0.26,
                c: 0.014,
                m: 1.03,
                alpha_dot0: 1.0,
                theta_m: 1793.0,
            }),
            thermal: Thermal {
                theta0: 293.15,
                c_theta: 477.0,
                alpha_sigma: 1.2e-5,
                gamma_tq: 0.9,
            },
            return_map,
        }
    }

    /// The model with its parameters, and `f` and `old` with their entries, seeded in
    /// the directions of `PARAMETERS`.
    fn seeded(
        return_map: ReturnMap,
        f: &M3<f64>,
        old: &State<f64>,
    ) -> (ElastoPlastic<D9>, M3<D9>, State<D9>) {
        let model = steel(return_map).map_params(|name, v| seed_named::<9>(&PARAMETERS, name, v));
        let mut f_d = f.map(D9::from);
        f_d[(0, 0)] = D9::seeded(f[(0, 0)], 5);
        f_d[(0, 1)] = D9::seeded(f[(0, 1)], 6);
        f_d[(1, 2)] = D9::seeded(f[(1, 2)], 7);
        let mut old_d = old.map(D9::from);
        old_d.alpha = D9::seeded(old.alpha, 8);
        (model, f_d, old_d)
    }

    /// The update from `old` to `f` with every direction seeded, by one return mapping.
    fn seeded_update(return_map: ReturnMap, f: &M3<f64>, old: &State<f64>) -> (M3<D9>, State<D9>) {
        let (model, f_d, old_d) = seeded(return_map, f, old);
        model
            .update(&f_d, DT, &old_d)
            .expect("the update converges")
    }

    /// Largest difference of the derivative parts of `a` and `b` in any direction,
    /// relative to the largest derivative part of `a` in that direction.
    fn worst(a: &[D9], b: &[D9]) -> f64 {
        (0..9)
            .map(|k| {
                let scale = a.iter().map(|x| x.eps[k].abs()).fold(0.0, f64::max);
                let gap = a.iter().zip(b).map(|(x, y)| (x.eps[k] - y.eps[k]).abs());
                gap.fold(0.0, f64::max) / scale.max(f64::MIN_POSITIVE)
            })
            .fold(0.0, f64::max)
    }

    /// σ, Fp⁻¹, α and θ of an update as one list.
    fn outputs(sigma: &M3<D9>, state: &State<D9>) -> Vec<D9> {
        let mut out: Vec<D9> = sigma.iter().chain(state.fp_inv.iter()).copied().collect();
        out.extend([state.alpha, state.theta]);
        out
    }

    /// A plastic state to continue from: a real update along `f0` from the virgin state.
    fn prestrained(f0: &M3<f64>) -> State<f64> {
        let virgin = State::virgin(293.15);
        steel(ReturnMap::Principal)
            .update(f0, 1e-6, &virgin)
            .unwrap()
            .1
    }

    /// The principal return's implicit step in 4 unknowns gives the derivatives of the
    /// reference return's in 10 (an independent set of equations: the exponential map
    /// solved for Fp⁻¹), along parameters, F and α_n, with distinct, coinciding and nearly
    /// coinciding trial stretches.
    #[test]
    fn derivatives_match_the_reference_return() {
        let shear = M3::new(1.004, 0.012, 0.0, 0.003, 0.995, 0.002, 0.0, -0.001, 1.0);
        let uniaxial = M3::new(0.992, 0.0, 0.0, 0.0, 1.003, 0.0, 0.0, 0.0, 1.003);
        let nearly = M3::new(0.992, 0.0, 0.0, 0.0, 1.003, 0.0, 0.0, 0.0, 1.003 + 1e-11);
        let close = M3::new(0.992, 0.0, 0.0, 0.0, 1.003, 0.0, 0.0, 0.0, 1.003 + 1e-7);
        let prestrain = M3::new(0.99, 0.004, 0.0, 0.0, 1.004, 0.0, 0.0, 0.0, 1.006);
        for (name, f, old) in [
            ("shear from virgin", shear, State::virgin(293.15)),
            (
                "shear after prestrain",
                shear * prestrain,
                prestrained(&prestrain),
            ),
            ("uniaxial", uniaxial, State::virgin(293.15)),
            ("nearly uniaxial", nearly, State::virgin(293.15)),
            ("close to uniaxial", close, State::virgin(293.15)),
        ] {
            let (s_p, new_p) = seeded_update(ReturnMap::Principal, &f, &old);
            let (s_r, new_r) = seeded_update(ReturnMap::Reference, &f, &old);
            assert!(new_p.alpha.re > old.alpha, "{name}: the step must yield");
            let error = worst(&outputs(&s_r, &new_r), &outputs(&s_p, &new_p));
            // round-off ~1e-12; the quotient or limit of Θ near `COINCIDENT` ~1e-8
            assert!(error < 1e-7, "{name}: relative derivative gap {error:e}");
        }
    }

    /// Given the real update's new state (the run's own return, in a derivative pass),
    /// the update in dual arithmetic gives what the whole update gives: elastic, plastic
    /// from virgin and after prestrain, molten, and yielding below the last digit of α_n
    /// (the state keeps Δα as solved), with both returns.
    #[test]
    fn the_update_from_the_real_return_gives_the_whole_update() {
        let shear = M3::new(1.004, 0.012, 0.0, 0.003, 0.995, 0.002, 0.0, -0.001, 1.0);
        let prestrain = M3::new(0.99, 0.004, 0.0, 0.0, 1.004, 0.0, 0.0, 0.0, 1.006);
        let small = M3::new(1.0001, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
        let (tiny_f, tiny_old) = onset_of_flow();
        let molten = State {
            theta: 1800.0,
            ..State::virgin(293.15)
        };
        for return_map in [ReturnMap::Principal, ReturnMap::Reference] {
            for (name, f, old) in [
                ("elastic", small, State::virgin(293.15)),
                ("shear from virgin", shear, State::virgin(293.15)),
                (
                    "after prestrain",
                    shear * prestrain,
                    prestrained(&prestrain),
                ),
                ("molten", shear, molten),
                ("below the last digit of α_n", tiny_f, tiny_old),
            ] {
                let (real, kept) = kept_update(return_map, &f, &old);
                let returns = return_map == ReturnMap::Principal && real.dalpha > 0.0;
                let expected = returns && name != "molten";
                assert_eq!(kept.is_some(), expected, "{return_map:?}, {name}: kept");
                let (model, f_d, old_d) = seeded(return_map, &f, &old);
                let (s_w, new_w) = model.update(&f_d, DT, &old_d).unwrap();
                let whole = outputs(&s_w, &new_w);
                for converged in [None, kept.as_ref()] {
                    let from = RealUpdate {
                        state: &real,
                        converged,
                        in_plane: false,
                    };
                    let (s_r, new_r) = model.update_from_real(&f_d, DT, &old_d, from).unwrap();
                    let from_real = outputs(&s_r, &new_r);
                    let error = worst(&whole, &from_real);
                    assert!(
                        error < 1e-12,
                        "{return_map:?}, {name}, kept {}: derivative gap {error:e}",
                        converged.is_some()
                    );
                    // values to round-off: of G for σ (τ = G (b^e − I) + …, b^e − I small
                    // beside b^e), of 1 for Fp⁻¹, α and θ
                    let g = steel(return_map).elastic.shear_modulus();
                    for (k, (w, r)) in whole.iter().zip(&from_real).enumerate() {
                        let scale = if k < 9 { g } else { 1.0 };
                        let gap = (w.re - r.re).abs();
                        assert!(
                            gap <= 1e-14 * w.re.abs().max(scale),
                            "{name}: {gap:e} in {k}"
                        );
                    }
                }
            }
        }
    }

    /// Where F, Fp⁻¹_n and their derivatives keep the z axis, the update that skips the
    /// terms that structure makes zero gives the general update's values and derivatives
    /// exactly: elastic, yielding from virgin and after prestrain, and molten.
    #[test]
    fn the_in_plane_update_gives_the_general_numbers() {
        let shear = M3::new(1.004, 0.012, 0.0, 0.003, 0.995, 0.0, 0.0, 0.0, 1.001);
        let prestrain = M3::new(0.99, 0.004, 0.0, 0.0, 1.004, 0.0, 0.0, 0.0, 1.006);
        let molten = State {
            theta: 1800.0,
            ..State::virgin(293.15)
        };
        let small = M3::new(1.0001, 0.00002, 0.0, -0.00001, 1.0, 0.0, 0.0, 0.0, 1.00003);
        for (name, f, old) in [
            ("elastic", small, State::virgin(293.15)),
            ("from virgin", shear, State::virgin(293.15)),
            (
                "after prestrain",
                shear * prestrain,
                prestrained(&prestrain),
            ),
            ("molten", shear, molten),
        ] {
            let off_plane = [(0, 2), (1, 2), (2, 0), (2, 1)];
            assert!(off_plane.iter().all(|&ij| old.fp_inv[ij] == 0.0), "{name}");
            let (real, kept) = kept_update(ReturnMap::Principal, &f, &old);
            let (model, mut f_d, old_d) = seeded(ReturnMap::Principal, &f, &old);
            // no derivative along F_12, which would leave the plane
            f_d[(1, 2)] = D9::from(0.0);
            let update = |in_plane| {
                let from = RealUpdate {
                    state: &real,
                    converged: kept.as_ref(),
                    in_plane,
                };
                let (sigma, new) = model.update_from_real(&f_d, DT, &old_d, from).unwrap();
                outputs(&sigma, &new)
            };
            let (general, in_plane) = (update(false), update(true));
            assert!(general.iter().any(|x| x.eps.norm() > 0.0), "{name}");
            for (k, (g, p)) in general.iter().zip(&in_plane).enumerate() {
                assert!(
                    g.re == p.re && g.eps == p.eps,
                    "{name}, entry {k}: {g:?} against {p:?}"
                );
            }
        }
    }

    /// The real update of one point by the batch, and the return it kept (if it solved one).
    fn kept_update(
        return_map: ReturnMap,
        f: &M3<f64>,
        old: &State<f64>,
    ) -> (State<f64>, Option<crate::material::Converged>) {
        let (mut real, mut kept) = (None, None);
        steel(return_map).update_batch_keeping(
            &[*f],
            DT,
            &[*old],
            &mut |_, result| real = Some(result.unwrap().1),
            &mut |_, converged| kept = Some(*converged),
        );
        (real.unwrap(), kept)
    }

    /// F whose step from a state with α_n = 1000 yields by so little that α_n + Δα rounds
    /// to α_n (the onset of flow found by bisection on the step's size), and that state.
    fn onset_of_flow() -> (M3<f64>, State<f64>) {
        let prestrain = M3::new(0.99, 0.004, 0.0, 0.0, 1.004, 0.0, 0.0, 0.0, 1.006);
        // α_n = 1000, whose last digit (1.1e-13) lies far above Δα at the onset of flow
        let old = State {
            alpha: 1e3,
            ..prestrained(&prestrain)
        };
        let model = steel(ReturnMap::Principal);
        // F whose trial Fe = F Fp_n⁻¹ is I + s (Fe_0 − I), Fe_0 the prestrain's
        let fe = prestrain * old.fp_inv;
        let fp = old.fp_inv.try_inverse().unwrap();
        let at = |s: f64| (M3::identity() + (fe - M3::identity()) * s) * fp;
        let yields = |s: f64| {
            matches!(
                model.trial(&at(s), &old),
                super::super::Trial::Yields { .. }
            )
        };
        let (mut elastic, mut plastic) = (0.0, 10.0);
        assert!(!yields(elastic) && yields(plastic));
        for _ in 0..200 {
            let mid = 0.5 * (elastic + plastic);
            if mid == elastic || mid == plastic {
                break;
            }
            match yields(mid) {
                true => plastic = mid,
                false => elastic = mid,
            }
        }
        (at(plastic), old)
    }

    /// A step that yields by so little that α_n + Δα rounds to α_n: the implicit step
    /// takes ln Δα from the return itself, so the derivatives stay finite (from α − α_n
    /// they were ln 0).
    #[test]
    fn a_step_that_yields_below_the_last_digit_of_alpha_keeps_finite_derivatives() {
        let (f, old) = onset_of_flow();
        let (sigma, state) = seeded_update(ReturnMap::Principal, &f, &old);
        assert_eq!(
            state.alpha.re, old.alpha,
            "Δα lies below the last digit of α_n"
        );
        for x in outputs(&sigma, &state) {
            assert!(
                x.eps.iter().all(|d| d.is_finite()),
                "a derivative is not finite: {x:?}"
            );
        }
    }
}
