//! Derivatives by forward-mode AD (`Dual` numbers) of the generic model code: the
//! consistent tangent dσ/dF and parameter sensitivities dσ/dp.

use crate::dual::Dual;
use crate::error::MaterialError;
use crate::material::{Model, State};
use crate::scalar::c;
use crate::tensor::M3;
use nalgebra::SMatrix;

/// Parameter `name` of value `v`: seeded in direction k if it is `free[k]` (k < N), else
/// constant.
pub fn seed_named<const N: usize>(free: &[&str], name: &str, v: f64) -> Dual<N> {
    match free.iter().position(|n| *n == name) {
        Some(k) => Dual::seeded(v, k),
        None => c(v),
    }
}

/// dσ_ij/dF_kl as a 9×9 matrix (row 3i+j, column 3k+l).
pub type Tangent = SMatrix<f64, 9, 9>;

/// Cauchy stress, its consistent tangent dσ_ij/dF_kl as a 9×9 matrix (row index 3i+j,
/// column index 3k+l) and the new state, for one update from `old`.
pub fn tangent<M: Model<f64>>(
    model: &M,
    f: &M3<f64>,
    dt: f64,
    old: &State<f64>,
) -> Result<(M3<f64>, Tangent, State<f64>), MaterialError> {
    type D9 = Dual<9>;
    let m = model.map_params(|_, v| c::<D9>(v));
    let fd = M3::from_fn(|i, j| D9::seeded(f[(i, j)], 3 * i + j));
    let old_d = old.map(c::<D9>);
    let (sigma, new) = m.update(&fd, dt, &old_d)?;
    let mut d = Tangent::zeros();
    for i in 0..3 {
        for j in 0..3 {
            d.set_row(3 * i + j, &sigma[(i, j)].eps.transpose());
        }
    }
    Ok((sigma.map(|s| s.re), d, new.re()))
}

/// Cauchy stress and dσ/dp for the `P` named parameters, for one update from `old`.
pub fn sensitivities<M: Model<f64>, const P: usize>(
    model: &M,
    names: &[&str; P],
    f: &M3<f64>,
    dt: f64,
    old: &State<f64>,
) -> Result<(M3<f64>, [M3<f64>; P]), MaterialError> {
    let m = model.map_params(|name, v| seed_named::<P>(names, name, v));
    let (sigma, _) = m.update(&f.map(c), dt, &old.map(c))?;
    let mut out = [M3::zeros(); P];
    for (k, ds) in out.iter_mut().enumerate() {
        *ds = sigma.map(|s| s.eps[k]);
    }
    Ok((sigma.map(|s| s.re), out))
}
