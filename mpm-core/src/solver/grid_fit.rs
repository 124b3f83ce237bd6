//! Fitting the grid to the points each step (module `grid`), with the grid-shift origin
//! (eq. E.8), the node budget `limits::GRID_NODES`, and the shape-function weights of every
//! point evaluated once for the step (module `weights`), on stencils as wide as the
//! largest point domain of the step needs (`shape::Reach`).

use super::Solver;
use crate::failure::{Cause, SimulationError};
use crate::limits::GRID_NODES;
use crate::parallel;
use crate::shape::{
    CpGimp, CpGimpAnalytic, Cpdi, CpdiHex, Kernel, Linear, Point, Reach, ShapeFunction, UGimp,
};
use crate::weights::Domains;
use nalgebra::SVector;
use rayon::prelude::*;

impl<const D: usize> Solver<D> {
    /// Fit the grid to the particles' bounding box (shifted origin if grid shift is on),
    /// unless that box would need more than `limits::GRID_NODES` nodes, and evaluate
    /// every point's shape functions for the step, each body with its own kernel on the
    /// stencil of the widest domain of any body.
    pub(super) fn refit_grid(&mut self) -> Result<(), SimulationError> {
        let mut widest = (Reach::CELL, 0.0, 0);
        for b in 0..self.blocks.len() {
            let (reach, extent, point) = match self.kernel_of(b) {
                ShapeFunction::Linear => self.reach::<Linear>(b),
                ShapeFunction::UGimp => self.reach::<UGimp>(b),
                ShapeFunction::CpGimp => self.reach::<CpGimp>(b),
                ShapeFunction::CpGimpAnalytic => self.reach::<CpGimpAnalytic>(b),
                ShapeFunction::Cpdi => self.reach::<Cpdi>(b),
                ShapeFunction::CpdiHex => self.reach::<CpdiHex>(b),
            };
            if extent > widest.1 || extent.is_nan() {
                widest = (reach, extent, point);
            }
        }
        let (reach, extent, point) = widest;
        if !reach.fits(D) || !extent.is_finite() {
            let limit = (1..)
                .map(|e| e as f64 * 0.5)
                .take_while(|&e| Reach::of(e).fits(D))
                .last()
                .unwrap_or(0.0);
            return Err(self.failure(Some(point), Cause::DomainTooLarge { extent, limit }));
        }
        self.fit_grid(reach)?;
        let (s, p) = (&mut self.scratch, &self.particles);
        s.weights.prepare(&self.grid, reach, p.len());
        let (w, grid) = (&mut s.weights, &self.grid);
        for block in &self.blocks {
            let range = block.range.clone();
            let at: Domains<'_, D> = (&p.position, (&p.half_size, &p.deformation, &p.hex));
            match block.kernel(self.settings.shape_function) {
                ShapeFunction::Linear => w.fill::<Linear>(grid, range, at),
                ShapeFunction::UGimp => w.fill::<UGimp>(grid, range, at),
                ShapeFunction::CpGimp => w.fill::<CpGimp>(grid, range, at),
                ShapeFunction::CpGimpAnalytic => w.fill::<CpGimpAnalytic>(grid, range, at),
                ShapeFunction::Cpdi => w.fill::<Cpdi>(grid, range, at),
                ShapeFunction::CpdiHex => w.fill::<CpdiHex>(grid, range, at),
            }
        }
        Ok(())
    }

    /// Fit the grid to hold every stencil of `reach` over every shift.
    fn fit_grid(&mut self, reach: Reach) -> Result<(), SimulationError> {
        let shift = self.shift.as_mut().map_or(SVector::zeros(), |s| s.sample());
        self.grid.origin = self.settings.origin + shift;
        let x = &self.particles.position;
        type Bounds<const D: usize> = (SVector<f64, D>, SVector<f64, D>);
        let none = (
            SVector::<f64, D>::repeat(f64::INFINITY),
            SVector::<f64, D>::repeat(f64::NEG_INFINITY),
        );
        let with = |(lo, hi): Bounds<D>, p: &SVector<f64, D>| (lo.inf(p), hi.sup(p));
        let both = |a: Bounds<D>, b: Bounds<D>| (a.0.inf(&b.0), a.1.sup(&b.1));
        let (lo, hi) = parallel::fold(x.par_iter(), parallel::light(x.len()), none, with, both);
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
        Ok(())
    }

    /// The stencil block `block` needs with kernel `K` this step: from the largest domain
    /// half-extent [cells] over its points; returns it with that extent and its point.
    fn reach<K: Kernel<D>>(&self, block: usize) -> (Reach, f64, usize) {
        let range = self.blocks[block].range.clone();
        let first = range.start;
        if !K::DOMAIN || range.is_empty() {
            return (Reach::CELL, 0.0, first);
        }
        let (p, inv_h) = (&self.particles, &self.grid.inv_spacing);
        let extent = |i: usize| {
            let point = Point {
                xi: SVector::zeros(),
                half: &p.half_size[i],
                f: &p.deformation[i],
                hex: p.hex.get(i),
                inv_h,
            };
            (K::extent(&point).max(), i)
        };
        // the largest extent, the first point of it
        let wider = |a: (f64, usize), b: (f64, usize)| {
            if b.0 > a.0 || (b.0 == a.0 && b.1 < a.1) {
                b
            } else {
                a
            }
        };
        let cut = parallel::light(p.len());
        let widest = |a, i| wider(a, extent(i));
        let (extent, widest) =
            parallel::fold(range.into_par_iter(), cut, (0.0, first), widest, wider);
        (Reach::of(extent), extent, widest)
    }
}
