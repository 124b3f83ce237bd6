//! Contact forces act where the surfaces touch: a rigid body's penalty force on a point
//! (eq. 9.4) is applied at the nearest point x_c of the point's domain, not at its centre.
//! It goes to the nodes of the point's stencil with the grid's linear hat functions at
//! x_c, N̂_I(x_c) = Π_k max(0, 1 − |x_c,k − X_I,k| / h_k), kept only on nodes that the
//! grid solve accelerates (mass above the cutoff) and renormalised to sum to one, so the
//! whole force reaches the body.
//!
//! Why: a force at the centre of an end point reaches the nodes on both sides of it, and
//! the node inside the body then needs a stress gradient to balance its share. With the
//! ends of a compressed cylinder on node planes, the end cells carried only ≈ 3/4 of the
//! interior stress and the specimen came out stiffer than its material, an error of first
//! order in the spacing. At the surface point a face on a node plane loads
//! only that plane and the stress stays uniform.
//!
//! The work of the loads is f · Σ_I w_I v_I Δt with the same weights w_I.

use super::Solver;
use crate::grid::Grid;
use materials::scalar::c;
use materials::Scalar;
use nalgebra::SVector;

/// One contact force at a surface point, and the nodes it was shared among this step.
#[derive(Debug, Clone)]
pub(super) struct SurfaceLoad<const D: usize> {
    /// The point the force acts on.
    pub particle: usize,
    /// Where it acts [m].
    pub at: SVector<f64, D>,
    /// The force [N].
    pub force: SVector<f64, D>,
    /// Range of this load's (node, weight) pairs in `Scratch::load_weights`.
    pub weights: std::ops::Range<usize>,
}

impl<const D: usize> Solver<D> {
    /// Add every surface load to the nodal forces, sharing it among the accelerated nodes
    /// of its point's stencil (needs this step's nodal masses).
    pub(super) fn add_surface_loads(&mut self) {
        let (grid, cutoff) = (&mut self.grid, self.mass_cutoff);
        let s = &mut self.scratch;
        let (loads, shares, weights) = (&mut s.loads, &mut s.load_weights, &s.weights);
        shares.clear();
        for load in loads.iter_mut() {
            let start = shares.len();
            let stencil = weights.stencil(load.particle);
            let own = stencil.node.iter().zip(stencil.n);
            let own = own.map(|(&node, &n)| (node as usize, n));
            load_shares(grid, cutoff, &load.at, own, shares);
            for &(node, w) in &shares[start..] {
                grid.nodes[node].force += load.force * w;
            }
            load.weights = start..shares.len();
        }
    }

    /// Work of the surface loads on the grid velocity this step [J] and its absolute value.
    pub(super) fn surface_load_work(&self) -> (f64, f64) {
        let s = &self.scratch;
        s.loads.iter().fold((0.0, 0.0), |(w, abs), load| {
            let v: SVector<f64, D> = s.load_weights[load.weights.clone()]
                .iter()
                .map(|&(node, n)| self.grid.nodes[node].velocity * n)
                .sum();
            let dw = load.force.dot(&v) * self.dt;
            (w + dw, abs + dw.abs())
        })
    }
}

/// Append to `shares` the (node, w_I) of a load at `at` [m] (real, or with derivatives):
/// the linear hats at `at` of the nodes of `own` (each node of the point's stencil once,
/// with the point's own weight) that the grid solve accelerates, renormalised to sum to
/// one; when none is within a cell of `at` (a domain stretched far from its centre), the
/// point's own weights. Which nodes share follows the real parts.
pub(super) fn load_shares<T: Scalar, const D: usize>(
    grid: &Grid<D>,
    cutoff: f64,
    at: &SVector<T, D>,
    own: impl Iterator<Item = (usize, T)> + Clone,
    shares: &mut Vec<(usize, T)>,
) {
    let start = shares.len();
    for (node, _) in own.clone() {
        let n = &grid.nodes[node];
        let offset = at - grid.node_position(node).map(c::<T>);
        let hat = hat_at(&offset, &grid.inv_spacing);
        if hat.re() > 0.0 && n.mass > cutoff * n.heaviest {
            shares.push((node, hat));
        }
    }
    if start == shares.len() {
        shares.extend(own);
    }
    let total = shares[start..]
        .iter()
        .fold(c::<T>(0.0), |t, (_, w)| t + w.clone());
    for (_, w) in &mut shares[start..] {
        *w /= total.clone();
    }
}

/// The linear hat of a node at offset `d` from it [m], Π_k max(0, 1 − |d_k| / h_k).
#[inline]
fn hat_at<T: Scalar, const D: usize>(d: &SVector<T, D>, inv_h: &SVector<f64, D>) -> T {
    (0..D).fold(c::<T>(1.0), |hat, k| {
        let u = d[k].clone() * inv_h[k];
        let u = if u.re() < 0.0 { -u } else { u };
        if u.re() >= 1.0 {
            c::<T>(0.0)
        } else {
            hat * (c::<T>(1.0) - u)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn hat_is_one_at_the_node_and_zero_a_cell_away() {
        let inv_h = Vector2::new(2.0, 4.0);
        assert_eq!(hat_at(&Vector2::<f64>::zeros(), &inv_h), 1.0);
        assert!((hat_at(&Vector2::<f64>::new(0.25, 0.125), &inv_h) - 0.25).abs() < 1e-15);
        assert_eq!(hat_at(&Vector2::<f64>::new(0.5, 0.0), &inv_h), 0.0);
        assert_eq!(hat_at(&Vector2::<f64>::new(0.0, -0.3), &inv_h), 0.0);
    }
}
