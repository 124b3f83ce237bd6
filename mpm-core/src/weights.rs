//! Shape-function weights cached per particle for one step (Karamelo's per-particle
//! weight cache, NairnMPM's node lists built once per step): after the grid is refitted,
//! every particle's stencil (first node number) and its weights N_I and gradients ∇N_I
//! [1/m] are evaluated once, in parallel, and then read by every transfer of the step
//! (USF and MUSL map to the grid twice and back twice; positions do not move until the
//! step's last stage).

use crate::grid::Grid;
use crate::parallel;
use crate::shape::{Hex, Kernel, Point, Reach};
use nalgebra::{Matrix3, SVector};
use rayon::prelude::*;
use std::ops::Range;

/// Weights of every particle's stencil for the current grid.
#[derive(Debug, Clone, Default)]
pub struct WeightCache<const D: usize> {
    /// The stencil of every point this step.
    reach: Reach,
    /// Stencil nodes per particle.
    nodes: usize,
    /// Node-number offsets of the stencil nodes from the first one (x fastest).
    offsets: Vec<usize>,
    /// Node number of each particle's first stencil node.
    first: Vec<usize>,
    /// N_I, `nodes` per particle.
    n: Vec<f64>,
    /// ∇N_I [1/m], `nodes` per particle.
    grad: Vec<SVector<f64, D>>,
}

/// What `WeightCache::fill` reads per point: positions [m], and the domains: half-widths
/// [m], deformation gradients, hexahedral domains (may be empty).
pub type Domains<'a, const D: usize> = (
    &'a [SVector<f64, D>],
    (&'a [SVector<f64, D>], &'a [Matrix3<f64>], &'a [Hex<D>]),
);

/// One particle's stencil: node numbers are `first + offsets[k]`. A domain kernel's
/// stencil is as wide as the step's widest domain, and most points reach only some of its
/// nodes (a point of a 2-per-cell lattice 8 of 27): the transfers skip entries with N_I = 0
/// and ∇N_I = 0, which made uGIMP and CPDI 12-16 % faster on `bench-mpm` case (a). (Packing
/// the reached entries to the front, to read less, gave the same.)
pub struct Stencil<'a, const D: usize> {
    pub first: usize,
    pub offsets: &'a [usize],
    pub n: &'a [f64],
    pub grad: &'a [SVector<f64, D>],
}

impl<const D: usize> WeightCache<D> {
    /// Size the cache for `count` points on stencils of `reach` on `grid` (fitted to hold
    /// them); `fill` then evaluates each body's points with its kernel.
    pub fn prepare(&mut self, grid: &Grid<D>, reach: Reach, count: usize) {
        let nodes = reach.nodes(D);
        self.nodes = nodes;
        self.reach = reach;
        stencil_offsets(grid, reach.support, &mut self.offsets);
        self.first.resize(count, 0);
        self.n.resize(count * nodes, 0.0);
        self.grad.resize(count * nodes, SVector::zeros());
    }

    /// Evaluate kernel `K` at the points `range` of `positions`, with reference domain
    /// half-widths `half` [m], deformation gradients `f` and hexahedral domains `hex`
    /// (empty unless some body runs `CpdiHex`), all indexed like `positions`.
    pub fn fill<K: Kernel<D>>(
        &mut self,
        grid: &Grid<D>,
        range: Range<usize>,
        (positions, (half, f, hex)): Domains<'_, D>,
    ) {
        let (nodes, reach) = (self.nodes, self.reach);
        let pad: usize = grid.strides.iter().map(|s| s * reach.pad).sum();
        let (start, end) = (range.start, range.end);
        let points = (positions[range.clone()].par_iter().enumerate())
            .zip(self.first[range].par_iter_mut())
            .zip(self.n[start * nodes..end * nodes].par_chunks_mut(nodes))
            .zip(self.grad[start * nodes..end * nodes].par_chunks_mut(nodes));
        let cut = parallel::light(positions.len());
        parallel::for_each(points, cut, |((((k, x), first), n), grad)| {
            let i = start + k;
            let (corner, xi) = grid.locate(x);
            let point = Point {
                xi,
                half: &half[i],
                f: &f[i],
                hex: hex.get(i),
                inv_h: &grid.inv_spacing,
            };
            let start = K::evaluate(&point, reach, n, grad);
            let shift: usize = (0..D)
                .map(|k| (start[k] + reach.pad as i64) as usize * grid.strides[k])
                .sum();
            *first = corner - pad + shift;
        });
    }

    /// The stencil of particle `i`.
    #[inline]
    pub fn stencil(&self, i: usize) -> Stencil<'_, D> {
        let range = i * self.nodes..(i + 1) * self.nodes;
        Stencil {
            first: self.first[i],
            offsets: &self.offsets,
            n: &self.n[range.clone()],
            grad: &self.grad[range],
        }
    }

    /// Nodes per axis the kernel of the last `compute` reaches.
    pub fn support(&self) -> usize {
        self.reach.support
    }

    /// Node number of particle `i`'s first stencil node.
    #[inline]
    pub fn first(&self, i: usize) -> usize {
        self.first[i]
    }

    /// Bytes kept per particle by a kernel of `nodes` stencil nodes.
    pub const fn bytes_per_particle(nodes: usize) -> usize {
        std::mem::size_of::<usize>()
            + nodes * (std::mem::size_of::<f64>() + std::mem::size_of::<SVector<f64, D>>())
    }
}

/// Node-number offsets of a `support`ᴰ stencil from its first node (x fastest), into
/// `offsets` (reused from step to step).
fn stencil_offsets<const D: usize>(grid: &Grid<D>, support: usize, offsets: &mut Vec<usize>) {
    let count = support.pow(D as u32);
    offsets.clear();
    offsets.extend((0..count).map(|k| {
        let mut rest = k;
        let mut offset = 0;
        for stride in grid.strides {
            offset += (rest % support) * stride;
            rest /= support;
        }
        offset
    }));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::{linear, Linear};
    use nalgebra::Vector3;

    #[test]
    fn the_cache_holds_the_linear_weights_of_each_corner() {
        let mut g = Grid::new(Vector3::new(0.5, 0.25, 1.0), Vector3::zeros());
        g.fit([0, 0, 0], [3, 3, 3], 0, 2);
        let x = vec![Vector3::new(0.6, 0.3, 2.2), Vector3::new(1.9, 0.01, 0.5)];
        let mut cache = WeightCache::default();
        let domains = ([Vector3::zeros(); 2], [nalgebra::Matrix3::identity(); 2]);
        cache.prepare(&g, Reach::CELL, x.len());
        cache.fill::<Linear>(&g, 0..x.len(), (&x, (&domains.0, &domains.1, &[])));
        let offsets = g.corner_offsets();
        for (i, x) in x.iter().enumerate() {
            let (base, xi) = g.locate(x);
            let w = linear(&xi, &g.inv_spacing);
            let s = cache.stencil(i);
            assert_eq!(s.first, base);
            for (k, offset) in offsets.iter().enumerate() {
                assert_eq!(s.first + s.offsets[k], base + offset);
                assert_eq!(s.n[k], w.n[k]);
                assert_eq!(s.grad[k], w.grad[k]);
            }
        }
    }
}
