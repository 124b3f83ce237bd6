//! Fitting the grid to the points each step (module `grid`), with the grid-shift origin
//! (eq. E.8), the node budget `limits::GRID_NODES`, and the shape-function weights of every
//! point evaluated once for the step (module `weights`); the largest point domain of the
//! step sets the grid's padding (`shape::Reach`).

use super::Solver;
use crate::failure::{Cause, SimulationError};
use crate::limits::GRID_NODES;
use crate::parallel;
use crate::shape::{
    CpGimp, CpGimpAnalytic, Cpdi, CpdiHex, Kernel, Linear, Point, Reach, ShapeFunction, UGimp,
    MAX_STENCIL_NODES,
};
use crate::weights::Domains;
use nalgebra::SVector;
use rayon::prelude::*;

impl<const D: usize> Solver<D> {
    /// Fit the grid to the particles' bounding box (shifted origin if grid shift is on),
    /// unless that box would need more than `limits::GRID_NODES` nodes, and evaluate
    /// every point's shape functions for the step, each body with its own kernel.
    pub(super) fn refit_grid(&mut self) -> Result<(), SimulationError> {
        self.fit_grid_to_points()?;
        self.evaluate_weights(|_| true);
        Ok(())
    }

    /// Fit the grid to the points' bounding box as `refit_grid` does and make room for
    /// the step's weights, the most nodes any point reaches.
    pub(super) fn fit_grid_to_points(&mut self) -> Result<(), SimulationError> {
        let mut widest = Widest::default();
        for b in 0..self.blocks.len() {
            let block = match self.kernel_of(b) {
                ShapeFunction::Linear => self.reach::<Linear>(b),
                ShapeFunction::UGimp => self.reach::<UGimp>(b),
                ShapeFunction::CpGimp => self.reach::<CpGimp>(b),
                ShapeFunction::CpGimpAnalytic => self.reach::<CpGimpAnalytic>(b),
                ShapeFunction::Cpdi => self.reach::<Cpdi>(b),
                ShapeFunction::CpdiHex => self.reach::<CpdiHex>(b),
            };
            widest = widest.or(block);
        }
        if let Some((point, extent)) = widest.too_large() {
            return Err(self.failure(Some(point), Cause::DomainTooLarge { extent }));
        }
        let reach = Reach::of(widest.extent);
        self.fit_grid(reach)?;
        let (s, p) = (&mut self.scratch, &self.particles);
        s.weights.prepare(widest.nodes, reach.support, p.len());
        Ok(())
    }

    /// Evaluate the weights of the points of every body `b` with `evaluates(b)`, each
    /// with its body's kernel, on the fitted grid.
    pub(super) fn evaluate_weights(&mut self, evaluates: impl Fn(usize) -> bool) {
        let (w, grid, p) = (&mut self.scratch.weights, &self.grid, &self.particles);
        for (b, block) in self.blocks.iter().enumerate() {
            if !evaluates(b) {
                continue;
            }
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

    /// How far the points of block `block` reach with kernel `K` this step.
    fn reach<K: Kernel<D>>(&self, block: usize) -> Widest {
        let range = self.blocks[block].range.clone();
        let first = range.start;
        let cell = Widest {
            nodes: K::nodes(&SVector::zeros()),
            ..Widest::default()
        };
        if !K::DOMAIN || range.is_empty() {
            return cell;
        }
        let (p, inv_h) = (&self.particles, &self.grid.inv_spacing);
        let of = |i: usize| {
            let point = Point {
                xi: SVector::zeros(),
                half: &p.half_size[i],
                f: &p.deformation[i],
                hex: p.hex.get(i),
                inv_h,
            };
            let e = K::extent(&point);
            Widest {
                extent: e.max(),
                point: i,
                nodes: K::nodes(&e),
                crowded: i,
                crowded_extent: e.max(),
            }
        };
        let cut = parallel::light(p.len());
        let start = Widest {
            point: first,
            crowded: first,
            ..cell
        };
        let with = |a: Widest, i| a.or(of(i));
        parallel::fold(range.into_par_iter(), cut, start, with, Widest::or)
    }
}

/// How far the points reach: the largest domain half-extent [cells] (NaN if any is) and
/// the first point of it; the most nodes any point reaches, the first point that reaches
/// them and its half-extent.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Widest {
    extent: f64,
    point: usize,
    nodes: usize,
    crowded: usize,
    crowded_extent: f64,
}

impl Default for Widest {
    fn default() -> Self {
        Widest {
            extent: 0.0,
            point: 0,
            nodes: 1,
            crowded: 0,
            crowded_extent: 0.0,
        }
    }
}

impl Widest {
    /// The wider of `self` and `other` (on equal extents, the lower point), with the more
    /// crowded of both (on equal node counts, the lower point).
    fn or(self, other: Widest) -> Widest {
        let wider = other.extent > self.extent
            || (other.extent == self.extent && other.point < self.point)
            || other.extent.is_nan();
        let widest = if wider && !self.extent.is_nan() {
            other
        } else {
            self
        };
        let more =
            other.nodes > self.nodes || (other.nodes == self.nodes && other.crowded < self.crowded);
        let crowded = if more { other } else { self };
        Widest {
            nodes: crowded.nodes,
            crowded: crowded.crowded,
            crowded_extent: crowded.crowded_extent,
            ..widest
        }
    }

    /// The point whose domain no stencil may hold, and its half-extent [cells]: a
    /// non-finite domain first, else the point reaching the most nodes if they are more
    /// than `MAX_STENCIL_NODES` (not always the widest: a domain wide along every axis
    /// reaches more nodes than one wider along a single axis).
    fn too_large(&self) -> Option<(usize, f64)> {
        if !self.extent.is_finite() {
            Some((self.point, self.extent))
        } else if self.nodes > MAX_STENCIL_NODES {
            Some((self.crowded, self.crowded_extent))
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reached(point: usize, extent: f64, nodes: usize) -> Widest {
        Widest {
            extent,
            point,
            nodes,
            crowded: point,
            crowded_extent: extent,
        }
    }

    /// A 3D uGIMP domain 4.1 cells wide along every axis reaches (⌈8.2⌉ + 2)³ = 1 331
    /// nodes; one 6 cells wide along x only reaches 14 · 3 · 3 = 126. The error names the
    /// first, in either order of the points.
    #[test]
    fn the_failure_names_the_point_with_too_many_nodes_not_the_widest() {
        let (cube, needle) = (reached(7, 4.1, 1331), reached(3, 6.0, 126));
        for both in [cube.or(needle), needle.or(cube)] {
            assert_eq!((both.extent, both.point, both.nodes), (6.0, 3, 1331));
            assert_eq!(both.too_large(), Some((7, 4.1)));
        }
        let fine = reached(2, 6.0, 126).or(reached(5, 1.0, 27));
        assert_eq!(fine.too_large(), None);
        let nan = reached(4, f64::NAN, 9).or(reached(1, 2.0, 2000));
        assert_eq!(nan.too_large().map(|(p, _)| p), Some(4));
    }
}
