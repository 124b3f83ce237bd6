//! Reference return mapping: thesis algorithm 3, the exponential map eq. 4.48 solved for
//! the 9 entries of Fp⁻¹ and α (10 unknowns) by Newton with the Jacobian from num-dual,
//! using the closed matrix exponential of `expm` (exact at Δα = 0).
//!
//! r(x) = [ F Fp⁻¹ − exp(−Δα √(3/2) N) F Fp_n⁻¹ ;  φ/G ],  x = [Fp⁻¹ (row-major), ln Δα].
//!
//! The plastic increment enters as u = ln Δα: the JC rate term 1 + C ln(Δα/(Δt α̇0)) is
//! then linear in u and α^N = (α_n + e^u)^N has no infinite slope at first yield, so
//! Newton converges from the perfectly-plastic estimate without special cases.

use crate::error::MaterialError;
use crate::expm::expm;
use crate::local_newton;
use crate::material::State;
use crate::plasticity::ElastoPlastic;
use crate::scalar::{c, Scalar};
use crate::tensor::{dev, lift, mul, norm, M3};
use nalgebra::{SMatrix, SVector};
use num_dual::{jacobian, DualSVec64};

type X<E> = SVector<E, 10>;

fn pack<E: Scalar>(fp_inv: &M3<E>, last: E) -> X<E> {
    let mut x = X::from_element(c(0.0));
    for i in 0..3 {
        for j in 0..3 {
            x[3 * i + j] = fp_inv[(i, j)];
        }
    }
    x[9] = last;
    x
}

fn unpack<E: Scalar>(x: &X<E>) -> (M3<E>, E) {
    (M3::from_fn(|i, j| x[3 * i + j]), x[9])
}

/// Residual of algorithm 3 (dimensionless: the yield function is scaled by G).
pub fn residual<E: Scalar>(
    m: &ElastoPlastic<E>,
    x: &X<E>,
    f: &M3<E>,
    old: &State<E>,
    dt: f64,
) -> X<E> {
    let (fp_inv, ln_dalpha) = unpack(x);
    let dalpha = ln_dalpha.exp();
    let fe = mul(f, &fp_inv);
    let tau = m.tau(&fe, old.theta);
    let s = dev(&tau);
    let s_norm = norm(&s);
    let sqrt_3_2 = c::<E>(1.5f64.sqrt());
    let flow = expm(&(s * (-dalpha * sqrt_3_2 / s_norm)));
    let r_m = fe - mul(&mul(&flow, f), &old.fp_inv);
    let phi = (s_norm * sqrt_3_2 - m.tau_y(old.alpha + dalpha, dalpha, dt, old.theta))
        / m.elastic.shear_modulus();
    pack(&r_m, phi)
}

fn residual_and_jacobian(
    m: &ElastoPlastic<f64>,
    x: &X<f64>,
    f: &M3<f64>,
    old: &State<f64>,
    dt: f64,
) -> (X<f64>, SMatrix<f64, 10, 10>) {
    type D10 = DualSVec64<10>;
    let m_d: ElastoPlastic<D10> = m.lift();
    let f_d: M3<D10> = lift(f);
    let old_d = old.map(c::<D10>);
    jacobian(|xd| residual(&m_d, &xd, &f_d, &old_d, dt), x)
}

/// Solve the local problem in real arithmetic from the first guess `dalpha0` > 0;
/// returns (Fp⁻¹, Δα).
pub fn solve(
    m: &ElastoPlastic<f64>,
    f: &M3<f64>,
    old: &State<f64>,
    dt: f64,
    dalpha0: f64,
) -> Result<(M3<f64>, f64), MaterialError> {
    let x0 = pack(&old.fp_inv, dalpha0.ln());
    let x = local_newton::solve(|x| residual_and_jacobian(m, x, f, old, dt), x0)?;
    let (fp_inv, ln_dalpha) = unpack(&x);
    Ok((fp_inv, ln_dalpha.exp()))
}

/// One Newton step in the scalar type `D` from the converged real solution: the real
/// part is unchanged to round-off, the dual parts are the implicit-function-theorem
/// derivatives dx/dp = −K⁻¹ ∂r/∂p of the converged local solution.
pub fn implicit_step<D: Scalar>(
    m: &ElastoPlastic<D>,
    f: &M3<D>,
    old: &State<D>,
    dt: f64,
    fp_inv: &M3<f64>,
    dalpha: f64,
) -> Result<(M3<D>, D), MaterialError> {
    let x = pack(fp_inv, dalpha.ln());
    let (_, k) = residual_and_jacobian(&m.re(), &x, &crate::tensor::re(f), &old.re(), dt);
    let k_inv = k.try_inverse().ok_or(MaterialError::Singular {
        what: "return mapping (implicit step)",
    })?;
    let x_d: X<D> = x.map(|v| c::<D>(v));
    let r = residual(m, &x_d, f, old, dt);
    let mut out = x_d;
    for i in 0..10 {
        for j in 0..10 {
            out[i] -= r[j] * k_inv[(i, j)];
        }
    }
    let (fp_inv, ln_dalpha) = unpack(&out);
    Ok((fp_inv, old.alpha + ln_dalpha.exp()))
}
