//! The weights N_I and gradients ∇N_I of the nodes a point reaches, with their
//! derivatives along the parameter directions, for the kernels whose weights are smooth
//! functions of the point's x and F between cell crossings:
//!
//! - linear: the 2ᴰ corners of the point's cell, N = Π_k (1 − ξ_k or ξ_k);
//! - the vertex form (CPDI1, R = F diag(a), and the thesis's cpGIMP, R = diag(F_kk a_k);
//!   module `shape::cpdi`): N^I = 2^{−D} Σ_j N^I(x^j), ∇N^I = 2^{−D} Σ_j N^I(x^j) R^{−T} ξ^j
//!   with the vertices x^j = x + R ξ^j, so the derivatives carry both the vertices' motion
//!   and the domain's deformation.
//!
//! - uGIMP (module `shape::gimp`): N = Π_k S̄_k with S̄(r) = [Φ(r + l) − Φ(r − l)]/(2l)
//!   over the box of nodes the reference domain meets, its half-widths l fixed, so the
//!   derivatives carry the point's motion through r.
//!
//! Which cell holds the point or a vertex follows the real parts, as in the run. A node
//! appears once in a point's list: the vertices' shares of it are summed in vertex order,
//! as the run sums them (`shape::cpdi`), so a transfer does the work of each node once,
//! and the nodes come in the run's order, so the real parts of a linear, CPDI or cpGIMP
//! list are the run's weights, which the run takes from here (`real_weights`).

use super::Dual;
use crate::grid::{floor_i64, Grid};
use crate::parallel;
use crate::shape::cpdi::{four_node_box, reached};
use crate::shape::domain::{Deformed, Follow, Stretched};
use crate::shape::gimp::averaged_hat;
use crate::shape::{box_indices, corners, linear, Reach, ShapeFunction};
use crate::weights::NodeWeights;
use nalgebra::{Matrix3, SMatrix, SVector};
use rayon::prelude::*;
use std::ops::Range;

/// A kernel the derivative pass carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum SmoothKernel {
    Linear,
    Cpdi,
    CpGimp,
    UGimp,
}

impl SmoothKernel {
    /// The pass's form of `kernel`, `None` for one it does not carry.
    pub(super) fn of(kernel: ShapeFunction) -> Option<SmoothKernel> {
        match kernel {
            ShapeFunction::Linear => Some(SmoothKernel::Linear),
            ShapeFunction::Cpdi => Some(SmoothKernel::Cpdi),
            ShapeFunction::CpGimp => Some(SmoothKernel::CpGimp),
            ShapeFunction::UGimp => Some(SmoothKernel::UGimp),
            ShapeFunction::CpGimpAnalytic | ShapeFunction::CpdiHex => None,
        }
    }

    /// Whether the real parts of the entries are the run's weights of this kernel to the
    /// bit, in the run's order (`DualStencils::real_weights`); uGIMP's run evaluates
    /// point-sized domains by the hat function itself, which the pass does not.
    pub(super) fn gives_run_weights(self) -> bool {
        self != SmoothKernel::UGimp
    }

    /// Entries a point's list holds at most: 2ᴰ corners of one cell or of each of the 2ᴰ
    /// vertices' cells, or the `box_nodes` of the widest uGIMP box.
    pub(super) fn room(self, d: usize, box_nodes: usize) -> usize {
        match self {
            SmoothKernel::Linear => corners(d),
            SmoothKernel::Cpdi | SmoothKernel::CpGimp => corners(d) * corners(d),
            SmoothKernel::UGimp => box_nodes.max(corners(d)),
        }
    }
}

/// The entries of every point of one step, `room` per point.
pub(super) struct DualStencils<const D: usize, const P: usize> {
    room: usize,
    listed: Vec<Listed>,
    node: Vec<u32>,
    n: Vec<Dual<P>>,
    grad: Vec<SVector<Dual<P>, D>>,
}

/// What a point's list holds besides its entries.
#[derive(Debug, Clone, Copy)]
struct Listed {
    len: u8,
    /// Whether the entries are the vertex form's, of which the run lists only the nodes
    /// the vertices reach (N or ∇N not zero, `shape::cpdi`).
    vertex_form: bool,
    /// The lowest node number and the node rows (along the last axis) the entries span.
    lowest: u32,
    rows: u32,
}

/// One point's entries: node numbers, N and ∇N with derivatives.
pub(super) type Entries<'a, const D: usize, const P: usize> =
    (&'a [u32], &'a [Dual<P>], &'a [SVector<Dual<P>, D>]);

impl<const D: usize, const P: usize> DualStencils<D, P> {
    /// Room for `count` points with kernels `kernels` (the largest room of them), the
    /// widest uGIMP box meeting `box_nodes` nodes.
    pub(super) fn new(count: usize, kernels: &[SmoothKernel], box_nodes: usize) -> Self {
        let room = kernels
            .iter()
            .map(|k| k.room(D, box_nodes))
            .max()
            .unwrap_or(corners(D));
        DualStencils {
            room,
            listed: vec![
                Listed {
                    len: 0,
                    vertex_form: false,
                    lowest: 0,
                    rows: 1
                };
                count
            ],
            node: vec![0; count * room],
            n: vec![Dual::from_re(0.0); count * room],
            grad: vec![SVector::zeros(); count * room],
        }
    }

    /// Point `i`'s entries.
    #[inline]
    pub(super) fn of(&self, i: usize) -> Entries<'_, D, P> {
        let range = i * self.room..i * self.room + self.listed[i].len as usize;
        (
            &self.node[range.clone()],
            &self.n[range.clone()],
            &self.grad[range],
        )
    }

    /// Point `i`'s weights as the run lists them (`weights::WeightCache`): the real parts
    /// of its entries in their order, the vertex form's without the nodes its vertices do
    /// not reach; its lowest node, for a list left empty.
    pub(super) fn real_weights(&self, i: usize, out: &mut NodeWeights<'_, D>) -> usize {
        let (node, n, grad) = self.of(i);
        for k in 0..node.len() {
            let (n, grad) = (n[k].re, grad[k].map(|g| g.re));
            if !self.listed[i].vertex_form || reached(n, &grad) {
                out.push_node(node[k], n, grad);
            }
        }
        self.lowest(i)
    }

    /// Point `i`'s lowest node number.
    #[inline]
    pub(super) fn lowest(&self, i: usize) -> usize {
        self.listed[i].lowest as usize
    }

    /// Node rows (along the last axis) that any point's entries span, at most.
    pub(super) fn support(&self) -> usize {
        let rows = self.listed.iter().map(|l| l.rows as usize);
        rows.max().map_or(1, |r| r).max(2)
    }

    /// Evaluate the points `range`, all of kernel `kernel`, on `grid`, in parallel: point
    /// i at x with F and reference half-widths (`at(i)`).
    pub(super) fn fill(
        &mut self,
        range: Range<usize>,
        kernel: SmoothKernel,
        grid: &Grid<D>,
        at: impl Fn(usize) -> PointDomain<D, P> + Sync,
    ) {
        let (room, start, end) = (self.room, range.start, range.end);
        let cut = parallel::light(self.listed.len());
        let points = (self.listed[range].par_iter_mut())
            .zip(self.node[start * room..end * room].par_chunks_mut(room))
            .zip(self.n[start * room..end * room].par_chunks_mut(room))
            .zip(self.grad[start * room..end * room].par_chunks_mut(room))
            .enumerate();
        parallel::for_each(points, cut, |(k, (((listed, node), n), grad))| {
            let mut list = List {
                node,
                n,
                grad,
                len: 0,
                span: (u32::MAX, 0),
                vertex_form: false,
            };
            list.fill(kernel, grid, at(start + k));
            let ((low, high), stride) = (list.span, grid.strides[D - 1] as u32);
            let (lowest, rows) = match list.len {
                0 => (0, 1),
                _ => (low, high / stride - low / stride + 1),
            };
            *listed = Listed {
                len: list.len as u8,
                vertex_form: list.vertex_form,
                lowest,
                rows,
            };
        });
    }
}

/// A point's x and F with their derivatives, and its reference half-widths [m].
pub(super) type PointDomain<const D: usize, const P: usize> =
    (SVector<Dual<P>, D>, Matrix3<Dual<P>>, SVector<f64, D>);

/// One point's entries as they are filled, and the lowest and highest node among them.
struct List<'a, const D: usize, const P: usize> {
    node: &'a mut [u32],
    n: &'a mut [Dual<P>],
    grad: &'a mut [SVector<Dual<P>, D>],
    len: usize,
    span: (u32, u32),
    /// Whether the entries are the vertex form's.
    vertex_form: bool,
}

impl<const D: usize, const P: usize> List<'_, D, P> {
    /// The entries of a point of kernel `kernel` at x with F and half-widths `half`.
    fn fill(&mut self, kernel: SmoothKernel, grid: &Grid<D>, (x, f, half): PointDomain<D, P>) {
        let (corner, xi) = grid.locate(&x.map(|x| x.re));
        let xi =
            SVector::<Dual<P>, D>::from_fn(|k, _| Dual::new(xi[k], x[k].eps * grid.inv_spacing[k]));
        let domain = match kernel {
            SmoothKernel::Linear => None,
            SmoothKernel::Cpdi => edges_and_inverse::<Deformed, D, P>(&half, &f),
            SmoothKernel::CpGimp => edges_and_inverse::<Stretched, D, P>(&half, &f),
            SmoothKernel::UGimp if half.min() > 0.0 => {
                let l = half.component_mul(&grid.inv_spacing);
                for (node, n, grad) in gimp_box(&xi, &l, &grid.inv_spacing) {
                    let offset: i64 = (0..D).map(|k| node[k] * grid.strides[k] as i64).sum();
                    self.push((corner as i64 + offset) as u32, n, grad);
                }
                return;
            }
            SmoothKernel::UGimp => None,
        };
        match domain {
            None => {
                let w = linear(&xi, &grid.inv_spacing);
                let offsets = grid.corner_offsets();
                for k in 0..corners(D) {
                    self.push((corner + offsets[k]) as u32, w.n[k], w.grad[k]);
                }
            }
            Some(edges) => {
                self.vertex_form = true;
                add_vertices(self, (corner, &xi), edges, grid)
            }
        }
    }

    /// A new entry for `node`.
    #[inline(always)]
    fn push(&mut self, node: u32, n: Dual<P>, grad: SVector<Dual<P>, D>) {
        self.span = (self.span.0.min(node), self.span.1.max(node));
        self.node[self.len] = node;
        self.n[self.len] = n;
        self.grad[self.len] = grad;
        self.len += 1;
    }

    /// A vertex's share of `node`, added to the entry the node has already, as the run
    /// sums the shares (a new entry else).
    #[inline(always)]
    fn add(&mut self, node: u32, n: Dual<P>, grad: SVector<Dual<P>, D>) {
        let entries = &self.node[..self.len];
        match (0..entries.len()).find(|&k| entries[k] == node) {
            Some(k) => {
                self.n[k] += n;
                self.grad[k] += grad;
            }
            None => self.push(node, n, grad),
        }
    }
}

/// The vertex form's entries for a point at local coordinates `xi` in the cell whose
/// lowest node is `corner`, with half-edge vectors R and R⁻ᵀ (`edges`): each vertex
/// x + R ξʲ adds N(x^j)/2ᴰ and N(x^j) R⁻ᵀ ξʲ/2ᴰ to each corner of the cell that holds it.
/// The nodes come in the run's order (`shape::cpdi`): ascending where the vertices' cells
/// fit a box of 4 nodes per axis, else as the vertices first reach them.
fn add_vertices<const D: usize, const P: usize>(
    list: &mut List<'_, D, P>,
    (corner, xi): (usize, &SVector<Dual<P>, D>),
    (r, r_inv_t): (SMatrix<Dual<P>, D, D>, SMatrix<Dual<P>, D, D>),
    grid: &Grid<D>,
) {
    let vertices = corners(D);
    // the vertices x + R ξʲ [cells] and the cells that hold them
    let vertex: [SVector<Dual<P>, D>; 8] = std::array::from_fn(|j| match j < vertices {
        true => SVector::from_fn(|k, _| xi[k] + signed_sum(&r, j, k) * grid.inv_spacing[k]),
        false => SVector::zeros(),
    });
    let cell: [[i64; D]; 8] =
        std::array::from_fn(|j| std::array::from_fn(|k| floor_i64(vertex[j][k].re)));
    let node_of = |node: [i64; D]| {
        let offset: i64 = (0..D).map(|k| node[k] * grid.strides[k] as i64).sum();
        (corner as i64 + offset) as u32
    };
    let placed = (&vertex[..vertices], &cell, &r_inv_t);
    match (four_node_box(&cell[..vertices]), D) {
        (None, _) => each_share(placed, |node, n, grad| list.add(node_of(node), n, grad)),
        (Some(lo), 3) => summed_in_box::<D, P, 64>(list, lo, placed, node_of),
        (Some(lo), _) => summed_in_box::<D, P, 16>(list, lo, placed, node_of),
    }
}

/// A domain's vertices [cells], the cells that hold them and R⁻ᵀ.
type Placed<'a, const D: usize, const P: usize> = (
    &'a [SVector<Dual<P>, D>],
    &'a [[i64; D]; 8],
    &'a SMatrix<Dual<P>, D, D>,
);

/// Each vertex's share of each corner of its cell, N(x^j)/2ᴰ and N(x^j) R⁻ᵀ ξʲ/2ᴰ, to
/// `sink` with the corner's node [cell indices], in vertex order and corner order (x
/// fastest), as the run adds them (`shape::cpdi`).
#[inline(always)]
fn each_share<const D: usize, const P: usize>(
    (vertices, cell, r_inv_t): Placed<'_, D, P>,
    mut sink: impl FnMut([i64; D], Dual<P>, SVector<Dual<P>, D>),
) {
    let share = 1.0 / vertices.len() as f64;
    for (j, vertex) in vertices.iter().enumerate() {
        let g = SVector::<Dual<P>, D>::from_fn(|k, _| signed_sum(r_inv_t, j, k) * share);
        let local = SVector::from_fn(|k, _| vertex[k] - cell[j][k] as f64);
        let weight = corner_weights::<D, P>(&local);
        for (m, w) in weight.iter().enumerate().take(vertices.len()) {
            let node = std::array::from_fn(|k| cell[j][k] + ((m >> k) & 1) as i64);
            sink(node, *w * share, g * *w);
        }
    }
}

/// The vertices' shares summed in the box of 4 nodes per axis from `lo` (room for `MOST`
/// entries), given to `list` in entry order.
#[inline(always)]
fn summed_in_box<const D: usize, const P: usize, const MOST: usize>(
    list: &mut List<'_, D, P>,
    lo: [i64; D],
    placed: Placed<'_, D, P>,
    node_of: impl Fn([i64; D]) -> u32,
) {
    let mut n = [Dual::from_re(0.0); MOST];
    let mut grad = [SVector::<Dual<P>, D>::zeros(); MOST];
    let mut touched = 0u64;
    each_share(placed, |node, share_n, share_grad| {
        let k: usize = (0..D)
            .map(|i| ((node[i] - lo[i]) as usize) << (2 * i))
            .sum();
        touched |= 1 << k;
        n[k] += share_n;
        grad[k] += share_grad;
    });
    while touched != 0 {
        let k = touched.trailing_zeros() as usize;
        touched &= touched - 1;
        let node = std::array::from_fn(|i| lo[i] + ((k >> (2 * i)) & 3) as i64);
        list.push(node_of(node), n[k], grad[k]);
    }
}

/// The domain's half-edge vectors R and R^{−T} by rule `M`; `None` for a point without a
/// domain or with a degenerate one (the linear weights, as in the run).
fn edges_and_inverse<M: Follow, const D: usize, const P: usize>(
    half: &SVector<f64, D>,
    f: &Matrix3<Dual<P>>,
) -> Option<(SMatrix<Dual<P>, D, D>, SMatrix<Dual<P>, D, D>)> {
    if half.min() <= 0.0 {
        return None;
    }
    let r = M::edges(half, f);
    let inv = inverse(&r)?;
    Some((r, inv.transpose()))
}

/// R⁻¹ with its derivatives d(R⁻¹) = −R⁻¹ dR R⁻¹ (products with the real R⁻¹ as a
/// factor); its real part is the run's inverse of the real R, `None` where that is
/// singular.
fn inverse<const D: usize, const P: usize>(
    r: &SMatrix<Dual<P>, D, D>,
) -> Option<SMatrix<Dual<P>, D, D>> {
    let real = r.map(|x| x.re).try_inverse()?;
    // dR R⁻¹, then −R⁻¹ (dR R⁻¹)
    let right =
        SMatrix::<Dual<P>, D, D>::from_fn(|k, j| sum_over::<D, P>(|l| r[(k, l)] * real[(l, j)]));
    Some(SMatrix::from_fn(|i, j| {
        let change = sum_over::<D, P>(|k| right[(k, j)] * real[(i, k)]);
        Dual::new(real[(i, j)], -change.eps)
    }))
}

/// Σ_l m_kl ξʲ_l, ξʲ_l = ±1 by bit l of vertex number j: row k of m times the vertex's
/// signs.
#[inline]
fn signed_sum<const D: usize, const P: usize>(
    m: &SMatrix<Dual<P>, D, D>,
    j: usize,
    k: usize,
) -> Dual<P> {
    (0..D).fold(Dual::from_re(0.0), |sum, l| match (j >> l) & 1 {
        1 => sum + m[(k, l)],
        _ => sum - m[(k, l)],
    })
}

/// Σ_l term(l) over l < D, from the first term.
#[inline(always)]
fn sum_over<const D: usize, const P: usize>(term: impl Fn(usize) -> Dual<P>) -> Dual<P> {
    (1..D).fold(term(0), |sum, l| sum + term(l))
}

/// The linear weights of a cell's 2ᴰ corners at local coordinates `xi` (x fastest).
fn corner_weights<const D: usize, const P: usize>(xi: &SVector<Dual<P>, D>) -> [Dual<P>; 8] {
    let mut weight = [Dual::from_re(0.0); 8];
    (weight[0], weight[1]) = (Dual::from_re(1.0) - xi[0], xi[0]);
    for k in 1..D {
        let half = 1 << k;
        for m in 0..half {
            weight[m + half] = weight[m] * xi[k];
            weight[m] *= Dual::from_re(1.0) - xi[k];
        }
    }
    weight
}

/// The uGIMP weights of the box of nodes a domain of half-widths `l` [cells] meets, for a
/// point at local coordinates `xi` with their derivatives (module `shape::gimp`, the same
/// expressions): each node's cell offsets from the point's cell, N and ∇N.
fn gimp_box<const D: usize, const P: usize>(
    xi: &SVector<Dual<P>, D>,
    l: &SVector<f64, D>,
    inv_h: &SVector<f64, D>,
) -> impl Iterator<Item = ([i64; D], Dual<P>, SVector<Dual<P>, D>)> {
    let support: [usize; D] = std::array::from_fn(|k| Reach::of(l[k]).support);
    let first: [i64; D] = std::array::from_fn(|k| floor_i64(xi[k].re - l[k]));
    let (xi, l, inv_h) = (*xi, *l, *inv_h);
    box_indices(support).map(move |index| {
        let node: [i64; D] = std::array::from_fn(|k| first[k] + index[k] as i64);
        let factors: [(Dual<P>, Dual<P>); D] =
            std::array::from_fn(|k| averaged_hat(xi[k] - node[k] as f64, l[k]));
        let n = factors.iter().fold(Dual::from_re(1.0), |n, f| n * f.0);
        let grad = SVector::<Dual<P>, D>::from_fn(|j, _| {
            let others = (0..D)
                .filter(|&k| k != j)
                .fold(Dual::from_re(1.0), |n, k| n * factors[k].0);
            factors[j].1 * inv_h[j] * others
        });
        (node, n, grad)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::{CpGimp, Cpdi, Kernel, Linear, Point, Weights};
    use crate::weights::WeightCache;

    /// The run's weights of one point: node offsets from its cell's lower corner, N, ∇N.
    struct Collected<const D: usize>(Vec<([i64; D], f64, SVector<f64, D>)>);

    impl<const D: usize> Weights<D> for Collected<D> {
        fn push(&mut self, offset: [i64; D], n: f64, grad: SVector<f64, D>) {
            self.0.push((offset, n, grad));
        }
    }

    /// The pass's entries of a CPDI point at x with F, derivatives along x_0 and F_01.
    fn pass_entries(
        grid: &Grid<2>,
        x: &SVector<f64, 2>,
        f: &Matrix3<f64>,
        half: &SVector<f64, 2>,
    ) -> Vec<(u32, Dual<2>, SVector<Dual<2>, 2>)> {
        let mut stencils = DualStencils::<2, 2>::new(1, &[SmoothKernel::Cpdi], 0);
        let x_d = SVector::<Dual<2>, 2>::new(Dual::seeded(x[0], 0), Dual::from_re(x[1]));
        let mut f_d = f.map(Dual::from_re);
        f_d[(0, 1)] = Dual::seeded(f[(0, 1)], 1);
        stencils.fill(0..1, SmoothKernel::Cpdi, grid, |_| (x_d, f_d, *half));
        let (node, n, grad) = stencils.of(0);
        (0..node.len()).map(|k| (node[k], n[k], grad[k])).collect()
    }

    /// A sheared and stretched domain whose four vertices lie in three cells (nodes shared
    /// between vertices): the pass lists each node once, with the real N and ∇N of the
    /// run's own kernel (`shape::cpdi`) to the bit, and derivatives along x_0 and F_01
    /// that match central differences of the pass's own real parts.
    #[test]
    fn a_cpdi_point_lists_each_node_once_with_the_runs_weights() {
        let mut grid = Grid::<2>::new(SVector::from([0.5, 0.5]), SVector::zeros());
        grid.fit([0, 0], [8, 8], 2, 5);
        let (x, half) = (SVector::from([2.27, 2.04]), SVector::from([0.125, 0.125]));
        let f = Matrix3::new(1.3, 0.9, 0.0, 0.1, 0.8, 0.0, 0.0, 0.0, 1.0);
        let entries = pass_entries(&grid, &x, &f, &half);

        let (corner, xi) = grid.locate(&x);
        let point = Point {
            xi,
            half: &half,
            f: &f,
            hex: None,
            inv_h: &grid.inv_spacing,
        };
        let mut run = Collected(Vec::new());
        Cpdi::evaluate(&point, &mut run);
        assert!(
            run.0.len() > 4,
            "the vertices must reach more than one cell"
        );
        assert_eq!(
            entries.len(),
            run.0.len(),
            "one entry per node the run reaches"
        );
        for (offset, n, grad) in &run.0 {
            let node = corner as i64
                + (0..2)
                    .map(|k| offset[k] * grid.strides[k] as i64)
                    .sum::<i64>();
            let same: Vec<_> = entries.iter().filter(|e| e.0 as i64 == node).collect();
            assert_eq!(same.len(), 1, "node {node} once");
            let (_, n_d, grad_d) = same[0];
            assert_eq!(n_d.re, *n, "N of node {node}");
            assert_eq!(grad_d.map(|g| g.re), *grad, "∇N of node {node}");
        }

        // central differences of the real parts, h = 1e-6 of the cell along x_0 and of F_01
        let h = 1e-6;
        let moved = |dx: f64, df: f64| {
            let mut f = f;
            f[(0, 1)] += df;
            pass_entries(&grid, &(x + SVector::from([dx * 0.5, 0.0])), &f, &half)
        };
        for (direction, (plus, minus), step) in [
            (0, (moved(h, 0.0), moved(-h, 0.0)), h * 0.5),
            (1, (moved(0.0, h), moved(0.0, -h)), h),
        ] {
            for (node, n, grad) in &entries {
                let at = |list: &[(u32, Dual<2>, SVector<Dual<2>, 2>)]| {
                    let e = list.iter().find(|e| e.0 == *node).expect("the same nodes");
                    (e.1.re, e.2.map(|g| g.re))
                };
                let ((n_p, g_p), (n_m, g_m)) = (at(&plus), at(&minus));
                let dn = (n_p - n_m) / (2.0 * step);
                let dgrad = (g_p - g_m) / (2.0 * step);
                // N ~ 1, ∇N ~ 1/h = 2 per m; the differences' round-off ~1e-16/1e-6
                assert!(
                    (n.eps[direction] - dn).abs() < 1e-8,
                    "dN/d{direction} at {node}"
                );
                for k in 0..2 {
                    let gap = (grad[k].eps[direction] - dgrad[k]).abs();
                    assert!(gap < 1e-7, "d∇N_{k}/d{direction} at {node}: {gap:e}");
                }
            }
        }
    }

    /// Points: x [m], F and reference half-widths [m].
    type Points<'a> = (
        &'a [SVector<f64, 2>],
        &'a [Matrix3<f64>],
        &'a [SVector<f64, 2>],
    );

    /// Each point's list of (node, bits of N, bits of ∇N).
    type ListBits = Vec<Vec<(u32, u64, [u64; 2])>>;

    /// The run's weights of `kernel` at the points `x` with F `f`, and those the pass
    /// gives it (`DualStencils::real_weights`).
    fn run_and_given<K: Kernel<2>>(
        kernel: SmoothKernel,
        grid: &Grid<2>,
        (x, f, half): Points<'_>,
    ) -> [ListBits; 2] {
        let count = x.len();
        let (mut run, mut given) = (WeightCache::default(), WeightCache::default());
        run.prepare(16, 4, count);
        given.prepare(16, 4, count);
        run.fill::<K>(grid, 0..count, (x, (half, f, &[])));
        let mut stencils = DualStencils::<2, 1>::new(count, &[kernel], 0);
        let seeded = |i: usize| {
            let xd = SVector::from_fn(|k, _| Dual::seeded(x[i][k], 0));
            (
                xd,
                f[i].map(|v| Dual::new(v, SVector::from([0.1]))),
                half[i],
            )
        };
        stencils.fill(0..count, kernel, grid, seeded);
        given.fill_with(grid, 0..count, |i, out| stencils.real_weights(i, out));
        [run, given].map(|cache| {
            (0..count)
                .map(|i| {
                    let w = cache.stencil(i);
                    let bits = |k: usize| [w.grad[k][0].to_bits(), w.grad[k][1].to_bits()];
                    let entry = |k: usize| (w.node[k], w.n[k].to_bits(), bits(k));
                    (0..w.node.len()).map(entry).collect()
                })
                .collect()
        })
    }

    /// The pass's weights' real parts are the run's to the bit and in the run's order,
    /// without the nodes the run leaves out: linear weights; CPDI and cpGIMP domains whose
    /// vertices sit on cell faces (nodes of zero weight), sheared over three cells (the box
    /// of 4 nodes per axis) and stretched over twelve (the list); a CPDI point without a
    /// domain (the linear weights).
    #[test]
    fn the_real_parts_are_the_runs_weights_in_its_order() {
        let mut grid = Grid::<2>::new(SVector::from([0.5, 0.5]), SVector::zeros());
        grid.fit([0, 0], [12, 12], 2, 5);
        let x = [[2.375, 2.375], [2.27, 2.04], [3.1, 2.9], [2.6, 2.3]].map(SVector::from);
        let f = [
            Matrix3::identity(),
            Matrix3::new(1.3, 0.9, 0.0, 0.1, 0.8, 0.0, 0.0, 0.0, 1.0),
            Matrix3::new(24.0, 0.0, 0.0, 0.0, 0.3, 0.0, 0.0, 0.0, 1.0),
            Matrix3::identity(),
        ];
        let half = [0.125, 0.125, 0.125, 0.0].map(|h| SVector::from([h, h]));
        let at = (&x[..], &f[..], &half[..]);
        let [run, given] = run_and_given::<Cpdi>(SmoothKernel::Cpdi, &grid, at);
        assert_eq!(run, given, "CPDI");
        // the upper vertices on the lower faces of the next cells: 9 nodes, 5 of them with
        // N = 0 and ∇N = 0
        assert_eq!(run[0].len(), 4, "vertices on cell faces");
        assert_eq!(run[2].len(), 8, "two cells 12 apart");
        let [run, given] = run_and_given::<CpGimp>(SmoothKernel::CpGimp, &grid, at);
        assert_eq!(run, given, "cpGIMP");
        let [run, given] = run_and_given::<Linear>(SmoothKernel::Linear, &grid, at);
        assert_eq!(run, given, "linear");
    }
}
