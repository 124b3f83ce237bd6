//! Safeguarded Newton solver for the local return-mapping systems.
//!
//! Full Newton steps with a backtracking line search on ‖r‖∞. The callers solve for
//! u = ln Δα (the last unknown), which keeps Δα > 0 and removes the infinite slope of
//! α^N at first yield. A step changes u by at most `MAX_LOG_STEP` (Δα by a factor
//! e^5 ≈ 150): when Δα is tiny the residual barely depends on u and the raw Newton
//! step in u can be astronomically large.

use crate::error::MaterialError;
use crate::lanes::{finite, lane, none, select, select_matrix, Lane, Mask};
use nalgebra::{Const, DimMin, SMatrix, SVector};
use simba::simd::SimdBool;

/// Converged when the scaled residual is below this.
pub const TOL: f64 = 1e-13;
pub const MAX_ITERATIONS: usize = 60;
pub const MAX_LOG_STEP: f64 = 5.0;
/// A full Newton step smaller than this ends the solve without another evaluation: the
/// error left after it is O(|dx|²) ≈ 1e-14 in the log strains and ln Δα, below `TOL`. (At
/// 1e-9 a JC return at first yield took one more evaluation: 749 → 687 ns per step.)
pub const CONVERGED_STEP: f64 = 1e-7;

/// ∂r/∂x of a local problem: whatever solves J dx = b (a dense matrix by LU, or a
/// structured one by its own elimination), for one point or a batch in lanes.
pub trait Jacobian<L: Lane, const N: usize>: Copy {
    /// J⁻¹ b, and the lanes where J is regular (the others hold no number).
    fn solve(&self, b: &SVector<L, N>) -> (SVector<L, N>, Mask<L>);
    /// `self` in the lanes of `mask`, `other` in the rest.
    fn select(self, mask: Mask<L>, other: Self) -> Self;
}

impl<const N: usize> Jacobian<f64, N> for SMatrix<f64, N, N>
where
    Const<N>: DimMin<Const<N>, Output = Const<N>>,
{
    fn solve(&self, b: &SVector<f64, N>) -> (SVector<f64, N>, bool) {
        match self.lu().solve(b) {
            Some(x) => (x, true),
            None => (SVector::zeros(), false),
        }
    }

    fn select(self, mask: bool, other: Self) -> Self {
        if mask {
            self
        } else {
            other
        }
    }
}

/// Solve r(x) = 0 from `x0`, whose last component is u = ln Δα. `eval` returns r and
/// ∂r/∂x. Returns the root.
pub fn solve<const N: usize, J: Jacobian<f64, N>>(
    eval: impl FnMut(&SVector<f64, N>) -> (SVector<f64, N>, J),
    x0: SVector<f64, N>,
) -> Result<SVector<f64, N>, MaterialError> {
    let Roots {
        x,
        failures: [failure],
    } = solve_lanes(eval, x0);
    match failure {
        Some(error) => Err(error),
        None => Ok(x),
    }
}

/// A converged local problem kept for its derivative: the root y* and K⁻¹, the inverse of
/// the Jacobian there, from which dy = −K⁻¹ dr (the implicit function theorem) follows for
/// any derivative dr of the residual at fixed y.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Converged<const N: usize> {
    pub y: SVector<f64, N>,
    pub k_inv: SMatrix<f64, N, N>,
}

/// The roots of a batch, and the failure of each lane that has none.
pub struct Roots<L: Lane, const N: usize> {
    pub x: SVector<L, N>,
    pub failures: L::Failures,
}

/// `solve` for the lanes of a batch in lockstep: each lane takes the steps it would take
/// alone, and is frozen from the iteration where it ends (converged or failed), so its
/// root does not depend on the other lanes.
pub fn solve_lanes<L: Lane, const N: usize, J: Jacobian<L, N>>(
    mut eval: impl FnMut(&SVector<L, N>) -> (SVector<L, N>, J),
    x0: SVector<L, N>,
) -> Roots<L, N> {
    let tol = L::splat(TOL);
    let mut failures = L::Failures::default();
    let mut fail = |mask: Mask<L>, error: &dyn Fn(usize) -> MaterialError| {
        for (i, slot) in failures.as_mut().iter_mut().enumerate() {
            if lane::<L>(mask, i) {
                *slot = Some(error(i));
            }
        }
    };
    let (mut x, mut root) = (x0, x0);
    let (mut r, mut k) = eval(&x);
    let mut active = !none::<L>();
    for _ in 0..MAX_ITERATIONS {
        let r_norm = r.amax();
        let non_finite = active & !finite(r_norm);
        fail(non_finite, &|_| MaterialError::NonFinite {
            what: "local residual",
        });
        let converged = active & !non_finite & r_norm.simd_lt(tol);
        root = select_matrix(converged, &x, &root);
        active = active & !non_finite & !converged;
        if !active.any() {
            break;
        }
        let (dx, regular) = k.solve(&(-r));
        let singular = active & !regular;
        fail(singular, &|_| MaterialError::Singular {
            what: "return mapping",
        });
        active = active & regular;
        let dx_norm = dx.amax();
        let small = active & dx_norm.simd_lt(L::splat(CONVERGED_STEP));
        root = select_matrix(small, &(x + dx), &root);
        active = active & !small;
        if !active.any() {
            break;
        }
        let mut step = (L::splat(MAX_LOG_STEP) / dx[N - 1].simd_abs()).simd_min(L::splat(1.0));
        let mut searching = active;
        for _ in 0..12 {
            let trial = x + dx * step;
            let (r_t, k_t) = eval(&trial);
            let r_t_norm = r_t.amax();
            let decrease = r_norm * (L::splat(1.0) - L::splat(1e-4) * step);
            let accept = searching & (r_t_norm.simd_lt(decrease) | r_t_norm.simd_lt(tol));
            if accept.all() {
                (x, r, k) = (trial, r_t, k_t);
            } else {
                x = select_matrix(accept, &trial, &x);
                r = select_matrix(accept, &r_t, &r);
                k = k_t.select(accept, k);
            }
            searching = searching & !accept;
            if !searching.any() {
                break;
            }
            step = select(searching, step * L::splat(0.5), step);
        }
        // no step was accepted: a stalled solve that has stopped moving is converged
        let stopped = searching & dx_norm.simd_lt(L::splat(1e-12));
        root = select_matrix(stopped, &x, &root);
        fail(searching & !stopped, &|i| {
            MaterialError::ReturnMapNotConverged {
                iterations: MAX_ITERATIONS,
                residual: r_norm.extract(i),
            }
        });
        active = active & !searching;
        let still = active & (dx * step).amax().simd_lt(L::splat(1e-15));
        root = select_matrix(still, &x, &root);
        active = active & !still;
        if !active.any() {
            break;
        }
    }
    let r_norm = r.amax();
    fail(active, &|i| MaterialError::ReturnMapNotConverged {
        iterations: MAX_ITERATIONS,
        residual: r_norm.extract(i),
    });
    Roots { x: root, failures }
}
