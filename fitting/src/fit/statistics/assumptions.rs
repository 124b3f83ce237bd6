//! What the fitted parameters owe to the model's fixed assumptions: the MPM
//! level's contact penalty κ and friction μ are chosen, not fitted. For each change of
//! `CONTACT_CHANGES` (κ and μ halved and doubled, on every experiment with contact at once)
//! the report gives
//! - ΔS/S, the change of the objective at the fitted parameters, and
//! - the parameter shift of a refit, linearized at the optimum: with r the residuals and
//!   J = dr/dp there, the changed models move r by Δr, and the Gauss-Newton step from the
//!   optimum (where Jᵀr = 0) is Δp = −(JᵀJ)⁻¹ JᵀΔr. It costs one run per experiment and
//!   change instead of a refit, and is exact for a model linear in p.
//!
//! A shift beyond a standard error says that the fitted values carry the choice of κ or μ
//! more than the noise of the data.

use crate::fit::objective::Objective;
use crate::shpb_model::CONTACT_CHANGES;
use anyhow::{Context, Result};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// One change of the contact assumptions and what it does to the fit.
#[derive(Debug, Clone)]
pub struct AssumptionShift {
    pub label: &'static str,
    /// (S' − S)/S at the fitted parameters [-].
    pub cost_change: f64,
    /// Linearized refit shift of each free parameter, in the objective's order [SI].
    pub shifts: Vec<f64>,
}

/// The shifts of every contact change at the fitted bounded parameters `p`, with the
/// residuals `r` and their Jacobian `jp` = dr/dp there. Empty when no experiment of the
/// objective has contact.
pub fn contact_shifts(
    objective: &Objective,
    p: &[f64],
    r: &[f64],
    jp: &DMatrix<f64>,
) -> Result<Vec<AssumptionShift>> {
    let material = objective.material(p);
    let blocks = &objective.blocks;
    let jobs: Vec<(usize, usize)> = (0..CONTACT_CHANGES.len())
        .flat_map(|c| (0..blocks.len()).map(move |b| (c, b)))
        .collect();
    let predictions: Vec<Option<Vec<f64>>> = jobs
        .par_iter()
        .map(|&(c, b)| {
            let block = blocks[b];
            let changed = block.model.with_contact(&CONTACT_CHANGES[c])?;
            changed
                .map(|m| m.predict(&material))
                .transpose()
                .with_context(|| {
                    format!("experiment `{}`, {}", block.name, CONTACT_CHANGES[c].label)
                })
        })
        .collect::<Result<_>>()?;
    if predictions.iter().all(Option::is_none) {
        return Ok(Vec::new());
    }
    let jtj_inv = (jp.transpose() * jp).try_inverse();
    let s = r.iter().map(|x| x * x).sum::<f64>();
    let shifts = CONTACT_CHANGES.iter().enumerate().map(|(c, change)| {
        let mut dr = DVector::<f64>::zeros(r.len());
        let mut row = 0;
        for (b, block) in blocks.iter().enumerate() {
            let n = block.measured.len();
            if let Some(y) = &predictions[c * blocks.len() + b] {
                for (k, changed) in block.residuals(y).enumerate() {
                    dr[row + k] = changed - r[row + k];
                }
            }
            row += n;
        }
        let changed_s: f64 = r.iter().zip(dr.iter()).map(|(a, d)| (a + d).powi(2)).sum();
        let shifts = match &jtj_inv {
            Some(inv) => (-(inv * (jp.transpose() * &dr))).iter().copied().collect(),
            None => vec![f64::NAN; jp.ncols()],
        };
        AssumptionShift {
            label: change.label,
            cost_change: changed_s / s - 1.0,
            shifts,
        }
    });
    Ok(shifts.collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::levels::model::{ExperimentModel, Material};
    use crate::fit::objective::Block;
    use crate::fit::optimize::run::residuals_and_jacobian_in_p;
    use crate::fit::params::{FreeParam, ParamSpace};
    use crate::shpb_model::ContactChange;
    use materials::material::Model;

    /// y_k = A x_k + μ g_k [Pa]: linear in the fitted A, with a friction term the fit does
    /// not vary and no penalty term.
    struct Toy {
        friction: f64,
    }

    const X: [f64; 5] = [0.1, 0.4, 0.5, 0.9, 1.3];
    const G: [f64; 5] = [1e8, 3e7, 2e8, 5e7, 1.5e8];

    impl ExperimentModel for Toy {
        fn level(&self) -> &'static str {
            "toy"
        }
        fn len(&self) -> usize {
            X.len()
        }
        fn predict(&self, material: &Material) -> Result<Vec<f64>> {
            let a = material.param("A").expect("JC");
            Ok((0..X.len())
                .map(|k| a * X[k] + self.friction * G[k])
                .collect())
        }
        fn with_contact(&self, c: &ContactChange) -> Result<Option<Box<dyn ExperimentModel>>> {
            Ok(Some(Box::new(Toy {
                friction: self.friction * c.friction,
            })))
        }
    }

    /// For a model linear in the parameters the linearized refit is the refit: doubling
    /// μ0 = 0.1 moves A by −μ0 Σ x g / Σ x² (least squares in closed form), halving it by
    /// half that the other way; κ moves nothing. The measured values carry an offset
    /// so that the optimum has residuals (Jᵀr = 0 there, r ≠ 0).
    #[test]
    fn linearized_shift_is_the_refit_of_a_linear_model() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/materials");
        let base =
            materials::load_elasto_plastic(std::path::Path::new(dir).join("ss304l.toml")).unwrap();
        let (a_true, mu0) = (3e8, 0.1);
        let offsets = [2e6, -1e6, -3e6, 1e6, 0.5e6];
        let measured: Vec<f64> = (0..X.len())
            .map(|k| a_true * X[k] + mu0 * G[k] + offsets[k])
            .collect();
        let block = Block::new(
            "toy",
            Box::new(Toy { friction: mu0 }),
            measured.clone(),
            X.to_vec(),
            X.to_vec(),
            "x",
            "y [Pa]",
            1.0,
            1.0,
        )
        .unwrap();
        // the least-squares optimum of A, in closed form
        let sxx: f64 = X.iter().map(|x| x * x).sum();
        let fit = |mu: f64| {
            (0..X.len())
                .map(|k| X[k] * (measured[k] - mu * G[k]))
                .sum::<f64>()
                / sxx
        };
        let a_opt = fit(mu0);
        let space = ParamSpace::new(vec![FreeParam::new("A", 1e8, 1e9, a_opt).unwrap()]).unwrap();
        let objective = Objective::new(base, vec![&block], space.clone()).unwrap();
        let u = space.to_unbounded(&[a_opt]);
        let (r, jp) = residuals_and_jacobian_in_p(&objective, &u).unwrap();
        assert!(
            r.iter().any(|x| x.abs() > 1e-4),
            "the optimum has residuals"
        );
        let shifts = contact_shifts(&objective, &[a_opt], &r, &jp).unwrap();
        let labels: Vec<&str> = shifts.iter().map(|s| s.label).collect();
        assert_eq!(labels, ["κ / 2", "κ × 2", "μ / 2", "μ × 2"]);
        for s in &shifts[..2] {
            assert_eq!((s.shifts[0], s.cost_change), (0.0, 0.0), "{}", s.label);
        }
        for (s, factor) in shifts[2..].iter().zip([0.5, 2.0]) {
            let exact = fit(mu0 * factor) - a_opt;
            let err = (s.shifts[0] - exact).abs() / exact.abs();
            // the forward-difference Jacobian of a linear model is exact to its round-off
            assert!(
                err < 1e-6,
                "{}: ΔA {} vs refit {exact}: {err:e}",
                s.label,
                s.shifts[0]
            );
            assert!(
                s.cost_change > 0.0,
                "{}: the changed model fits worse",
                s.label
            );
        }
    }
}
