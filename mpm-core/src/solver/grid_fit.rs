//! Fitting the grid to the points each step (module `grid`), with the grid-shift origin
//! (eq. E.8), the node budget `limits::GRID_NODES`, and the shape-function weights of every
//! point evaluated once for the step (module `weights`).

use super::Solver;
use crate::failure::{Cause, SimulationError};
use crate::shape::{Kernel, Linear, ShapeFunction, UGimp};
use materials::limits::GRID_NODES;
use nalgebra::SVector;
use rayon::prelude::*;

impl<const D: usize> Solver<D> {
    /// Fit the grid to the particles' bounding box (shifted origin if grid shift is on),
    /// unless that box would need more than `limits::GRID_NODES` nodes, and evaluate
    /// every point's shape functions for the step.
    pub(super) fn refit_grid(&mut self) -> Result<(), SimulationError> {
        match self.settings.shape_function {
            ShapeFunction::Linear => self.refit_grid_for::<Linear>(),
            ShapeFunction::UGimp => self.refit_grid_for::<UGimp>(),
        }
    }

    /// `refit_grid` for kernel `K`: the grid holds every stencil over every shift.
    fn refit_grid_for<K: Kernel<D>>(&mut self) -> Result<(), SimulationError> {
        let shift = self.shift.as_mut().map_or(SVector::zeros(), |s| s.sample());
        self.grid.origin = self.settings.origin + shift;
        let x = &self.particles.position;
        let (lo, hi) = x
            .par_iter()
            .fold(
                || {
                    (
                        SVector::<f64, D>::repeat(f64::INFINITY),
                        SVector::<f64, D>::repeat(f64::NEG_INFINITY),
                    )
                },
                |(lo, hi), p| (lo.inf(p), hi.sup(p)),
            )
            .reduce(
                || {
                    (
                        SVector::repeat(f64::INFINITY),
                        SVector::repeat(f64::NEG_INFINITY),
                    )
                },
                |a, b| (a.0.inf(&b.0), a.1.sup(&b.1)),
            );
        let (cmin, cmax) = (self.grid.cell_of(&lo), self.grid.cell_of(&hi));
        let (pad, support) = (K::PAD, K::SUPPORT + K::SHIFT);
        let nodes: f64 = (0..D)
            .map(|i| cmax[i] as f64 - cmin[i] as f64 + support as f64)
            .product();
        if let Err(e) = GRID_NODES.check(nodes, || {
            format!(
                "the points span {lo:?} to {hi:?} m on cells of {:?} m",
                self.grid.spacing
            )
        }) {
            return Err(self.failure(None, Cause::GridTooLarge(e)));
        }
        self.grid.fit(cmin, cmax, pad, support);
        let (s, p) = (&mut self.scratch, &self.particles);
        s.weights
            .compute::<K>(&self.grid, &p.position, &p.half_size);
        Ok(())
    }
}
