//! Shape-function weights cached per particle for one step (Karamelo's per-particle
//! weight cache, NairnMPM's node lists built once per step): after the grid is refitted,
//! the list of nodes every particle reaches (node numbers) with its weights N_I and
//! gradients ∇N_I [1/m] is evaluated once, in parallel, and then read by every transfer of
//! the step (USF and MUSL map to the grid twice and back twice; positions do not move
//! until the step's last stage). Each particle has room for the most nodes any point of
//! the step reaches (8 in 3D for linear, at most 64 for CPDI however far its domain
//! stretches).

use crate::grid::Grid;
use crate::parallel;
use crate::shape::{Hex, Kernel, Point, Weights};
use nalgebra::{Matrix3, SVector};
use rayon::prelude::*;
use std::ops::Range;

/// Weights of the nodes every particle reaches on the current grid.
#[derive(Debug, Clone, Default)]
pub struct WeightCache<const D: usize> {
    /// Room per particle: the most nodes any point of the step reaches.
    room: usize,
    /// Nodes per axis any point of the step reaches at most (`shape::Reach`).
    support: usize,
    /// Nodes each particle reaches.
    len: Vec<u16>,
    /// Each particle's lowest node number.
    lowest: Vec<usize>,
    /// Node numbers, `room` per particle.
    node: Vec<u32>,
    /// N_I, `room` per particle.
    n: Vec<f64>,
    /// ∇N_I [1/m], `room` per particle.
    grad: Vec<SVector<f64, D>>,
}

/// What `WeightCache::fill` reads per point: positions [m], and the domains: half-widths
/// [m], deformation gradients, hexahedral domains (may be empty).
pub type Domains<'a, const D: usize> = (
    &'a [SVector<f64, D>],
    (&'a [SVector<f64, D>], &'a [Matrix3<f64>], &'a [Hex<D>]),
);

/// The nodes one particle reaches, node numbers into `Grid::nodes`, with their weights
/// N_I and gradients ∇N_I [1/m]; each node once.
pub struct Stencil<'a, const D: usize> {
    pub node: &'a [u32],
    pub n: &'a [f64],
    pub grad: &'a [SVector<f64, D>],
}

/// One particle's room in the cache while its weights are written to it: nodes given by
/// number (`push_node`) or, as kernels give them, by offsets from the lower corner of the
/// point's cell (`Weights::push`, after `corner` is set).
pub(crate) struct NodeWeights<'a, const D: usize> {
    /// Node number of the lower corner of the point's cell.
    corner: usize,
    strides: &'a [usize; D],
    node: &'a mut [u32],
    n: &'a mut [f64],
    grad: &'a mut [SVector<f64, D>],
    len: usize,
}

impl<const D: usize> NodeWeights<'_, D> {
    /// Node `node` with N and ∇N [1/m], after those pushed before.
    #[inline]
    pub(crate) fn push_node(&mut self, node: u32, n: f64, grad: SVector<f64, D>) {
        self.node[self.len] = node;
        self.n[self.len] = n;
        self.grad[self.len] = grad;
        self.len += 1;
    }
}

impl<const D: usize> Weights<D> for NodeWeights<'_, D> {
    #[inline]
    fn push(&mut self, offset: [i64; D], n: f64, grad: SVector<f64, D>) {
        let shift: i64 = (0..D).map(|k| offset[k] * self.strides[k] as i64).sum();
        self.push_node((self.corner as i64 + shift) as u32, n, grad);
    }
}

impl<const D: usize> WeightCache<D> {
    /// Size the cache for `count` points that reach at most `room` nodes each, at most
    /// `support` per axis; `fill` then evaluates each body's points with its kernel.
    pub fn prepare(&mut self, room: usize, support: usize, count: usize) {
        self.room = room;
        self.support = support;
        self.len.resize(count, 0);
        self.lowest.resize(count, 0);
        self.node.resize(count * room, 0);
        self.n.resize(count * room, 0.0);
        self.grad.resize(count * room, SVector::zeros());
    }

    /// Evaluate kernel `K` at the points `range` of `positions`, with reference domain
    /// half-widths `half` [m], deformation gradients `f` and hexahedral domains `hex`
    /// (empty unless some body runs `CpdiHex`), all indexed like `positions`, on `grid`
    /// (fitted to hold every node they reach).
    pub fn fill<K: Kernel<D>>(
        &mut self,
        grid: &Grid<D>,
        range: Range<usize>,
        (positions, (half, f, hex)): Domains<'_, D>,
    ) {
        self.fill_with(grid, range, |i, out| {
            let (corner, xi) = grid.locate(&positions[i]);
            let point = Point {
                xi,
                half: &half[i],
                f: &f[i],
                hex: hex.get(i),
                inv_h: &grid.inv_spacing,
            };
            out.corner = corner;
            K::evaluate(&point, out);
            corner
        });
    }

    /// The weights of the points `range` on `grid`, in parallel: `weights(i, out)` pushes
    /// point i's nodes to `out` and returns the node its lowest is taken to be if it
    /// pushes none (its cell's lower corner).
    pub(crate) fn fill_with(
        &mut self,
        grid: &Grid<D>,
        range: Range<usize>,
        weights: impl Fn(usize, &mut NodeWeights<'_, D>) -> usize + Sync,
    ) {
        let (room, count) = (self.room, self.len.len());
        let (start, end) = (range.start, range.end);
        let points = (self.len[range.clone()].par_iter_mut())
            .zip(&mut self.lowest[range])
            .zip(self.node[start * room..end * room].par_chunks_mut(room))
            .zip(self.n[start * room..end * room].par_chunks_mut(room))
            .zip(self.grad[start * room..end * room].par_chunks_mut(room))
            .enumerate();
        let cut = parallel::light(count);
        parallel::for_each(points, cut, |(k, ((((len, lowest), node), n), grad))| {
            let mut out = NodeWeights {
                corner: 0,
                strides: &grid.strides,
                node,
                n,
                grad,
                len: 0,
            };
            let empty = weights(start + k, &mut out);
            *len = out.len as u16;
            *lowest = out.node[..out.len]
                .iter()
                .min()
                .map_or(empty, |&m| m as usize);
        });
    }

    /// The nodes particle `i` reaches.
    #[inline]
    pub fn stencil(&self, i: usize) -> Stencil<'_, D> {
        let range = i * self.room..i * self.room + self.len[i] as usize;
        Stencil {
            node: &self.node[range.clone()],
            n: &self.n[range.clone()],
            grad: &self.grad[range],
        }
    }

    /// Nodes per axis any point of the step reaches at most.
    pub fn support(&self) -> usize {
        self.support
    }

    /// Particle `i`'s lowest node number.
    #[inline]
    pub fn lowest(&self, i: usize) -> usize {
        self.lowest[i]
    }

    /// Bytes kept per particle by a kernel that reaches `nodes` nodes.
    pub const fn bytes_per_particle(nodes: usize) -> usize {
        std::mem::size_of::<usize>()
            + std::mem::size_of::<u16>()
            + nodes
                * (std::mem::size_of::<u32>()
                    + std::mem::size_of::<f64>()
                    + std::mem::size_of::<SVector<f64, D>>())
    }
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
        cache.prepare(8, 2, x.len());
        cache.fill::<Linear>(&g, 0..x.len(), (&x, (&domains.0, &domains.1, &[])));
        let offsets = g.corner_offsets();
        for (i, x) in x.iter().enumerate() {
            let (base, xi) = g.locate(x);
            let w = linear(&xi, &g.inv_spacing);
            let s = cache.stencil(i);
            assert_eq!(cache.lowest(i), base);
            assert_eq!(s.node.len(), 8);
            for (k, offset) in offsets.iter().enumerate() {
                assert_eq!(s.node[k] as usize, base + offset);
                assert_eq!(s.n[k], w.n[k]);
                assert_eq!(s.grad[k], w.grad[k]);
            }
        }
    }
}
