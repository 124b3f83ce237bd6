//! Fitting the grid to the points each step (module `grid`), with the grid-shift origin
//! (eq. E.8), the node budget `limits::GRID_NODES`, and the shape-function weights of every
//! point evaluated once for the step (module `weights`), on stencils as wide as the
//! largest point domain of the step needs (`shape::Reach`).

use super::Solver;
use crate::failure::{Cause, SimulationError};
use crate::shape::{
    CpGimp, CpGimpAnalytic, Cpdi, CpdiHex, Kernel, Linear, Point, Reach, ShapeFunction, UGimp,
};
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
            ShapeFunction::CpGimp => self.refit_grid_for::<CpGimp>(),
            ShapeFunction::CpGimpAnalytic => self.refit_grid_for::<CpGimpAnalytic>(),
            ShapeFunction::Cpdi => self.refit_grid_for::<Cpdi>(),
            ShapeFunction::CpdiHex => self.refit_grid_for::<CpdiHex>(),
        }
    }

    /// `refit_grid` for kernel `K`: the grid holds every stencil over every shift.
    fn refit_grid_for<K: Kernel<D>>(&mut self) -> Result<(), SimulationError> {
        let reach = self.reach::<K>()?;
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
        let (pad, support) = (reach.pad, reach.support + reach.pad);
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
        s.weights.compute::<K>(
            &self.grid,
            reach,
            &p.position,
            (&p.half_size, &p.deformation, &p.hex),
        );
        Ok(())
    }

    /// The stencil size this step: from the largest domain half-extent over the points,
    /// which may not exceed what `MAX_STENCIL_NODES` holds (a failure naming the point).
    fn reach<K: Kernel<D>>(&self) -> Result<Reach, SimulationError> {
        if !K::DOMAIN {
            return Ok(Reach::CELL);
        }
        let (p, inv_h) = (&self.particles, &self.grid.inv_spacing);
        let (extent, widest) = (0..p.len())
            .into_par_iter()
            .map(|i| {
                let point = Point {
                    xi: SVector::zeros(),
                    half: &p.half_size[i],
                    f: &p.deformation[i],
                    hex: p.hex.get(i),
                    inv_h,
                };
                (K::extent(&point).max(), i)
            })
            .reduce(
                || (0.0, 0),
                |a, b| {
                    if b.0 > a.0 || (b.0 == a.0 && b.1 < a.1) {
                        b
                    } else {
                        a
                    }
                },
            );
        let reach = Reach::of(extent);
        if !reach.fits(D) || !extent.is_finite() {
            let limit = (1..)
                .map(|e| e as f64 * 0.5)
                .take_while(|&e| Reach::of(e).fits(D))
                .last()
                .unwrap_or(0.0);
            return Err(self.failure(Some(widest), Cause::DomainTooLarge { extent, limit }));
        }
        Ok(reach)
    }
}
