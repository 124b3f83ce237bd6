//! Safeguarded Newton solver for the local return-mapping systems.
//!
//! Full Newton steps with a backtracking line search on ‖r‖∞. The callers solve for
//! u = ln Δα (the last unknown), which keeps Δα > 0 and removes the infinite slope of
//! α^N at first yield. A step changes u by at most `MAX_LOG_STEP` (Δα by a factor
//! e^5 ≈ 150): when Δα is tiny the residual barely depends on u and the raw Newton
//! step in u can be astronomically large.

use crate::error::MaterialError;
use nalgebra::{Const, DimMin, SMatrix, SVector};

/// Converged when the scaled residual is below this.
pub const TOL: f64 = 1e-13;
pub const MAX_ITERATIONS: usize = 60;
pub const MAX_LOG_STEP: f64 = 5.0;
/// A full Newton step smaller than this ends the solve without another evaluation: the
/// error left after it is O(|dx|²) ≈ 1e-14 in the log strains and ln Δα, below `TOL`. (At
/// 1e-9 a JC return at first yield took one more evaluation: 749 → 687 ns per step.)
pub const CONVERGED_STEP: f64 = 1e-7;

/// ∂r/∂x of a local problem: whatever solves J dx = b (a dense matrix by LU, or a
/// structured one by its own elimination).
pub trait Jacobian<const N: usize> {
    fn solve(&self, b: &SVector<f64, N>) -> Option<SVector<f64, N>>;
}

impl<const N: usize> Jacobian<N> for SMatrix<f64, N, N>
where
    Const<N>: DimMin<Const<N>, Output = Const<N>>,
{
    fn solve(&self, b: &SVector<f64, N>) -> Option<SVector<f64, N>> {
        self.lu().solve(b)
    }
}

/// Solve r(x) = 0 from `x0`, whose last component is u = ln Δα. `eval` returns r and
/// ∂r/∂x. Returns the root.
pub fn solve<const N: usize, J: Jacobian<N>>(
    mut eval: impl FnMut(&SVector<f64, N>) -> (SVector<f64, N>, J),
    x0: SVector<f64, N>,
) -> Result<SVector<f64, N>, MaterialError> {
    let mut x = x0;
    let (mut r, mut k) = eval(&x);
    for _ in 0..MAX_ITERATIONS {
        let r_norm = r.amax();
        if !r_norm.is_finite() {
            return Err(MaterialError::NonFinite {
                what: "local residual",
            });
        }
        if r_norm < TOL {
            return Ok(x);
        }
        let dx = k.solve(&(-r)).ok_or(MaterialError::Singular {
            what: "return mapping",
        })?;
        if dx.amax() < CONVERGED_STEP {
            // Quadratic convergence: the residual after this step is O(|dx|²), below
            // TOL, so it need not be evaluated.
            return Ok(x + dx);
        }
        let mut step = (MAX_LOG_STEP / dx[N - 1].abs()).min(1.0);
        let mut accepted = false;
        for _ in 0..12 {
            let trial = x + dx * step;
            let (r_t, k_t) = eval(&trial);
            if r_t.amax() < r_norm * (1.0 - 1e-4 * step) || r_t.amax() < TOL {
                x = trial;
                r = r_t;
                k = k_t;
                accepted = true;
                break;
            }
            step *= 0.5;
        }
        if !accepted {
            // No decrease is possible: the residual sits at round-off level.
            if dx.amax() < 1e-12 {
                return Ok(x);
            }
            return Err(MaterialError::ReturnMapNotConverged {
                iterations: MAX_ITERATIONS,
                residual: r_norm,
            });
        }
        if (dx * step).amax() < 1e-15 {
            return Ok(x);
        }
    }
    Err(MaterialError::ReturnMapNotConverged {
        iterations: MAX_ITERATIONS,
        residual: r.amax(),
    })
}
