//! Vertex-form kernels: CPDI1 with parallelogram / parallelepiped domains (Sadeghirad et
//! al. 2011; thesis eq. 10.4 and reading §1.3), and cpGIMP as the thesis runs it, through
//! the same machinery with a shear-free domain. The domain of a point is spanned by the
//! half-edge vectors r_k (R [m], from the in-plane block of F), its 2ᴰ vertices are
//! x^j = x_p + R ξ^j with ξ^j ∈ {±1}ᴰ, and eq. 10.4 integrates to
//!
//!   N^I = 2^{−D} Σ_j N^I(x^j),   ∇N^I = 2^{−D} Σ_j N^I(x^j) R^{−T} ξ^j,
//!
//! with N^I the linear grid functions (appendix E): a point reaches every node of the
//! cells that hold its vertices, at most 4ᴰ however far the domain stretches (the
//! vertices' shares are summed per node). Σ_I N^I = 1 and Σ_I ∇N^I = 0 exactly; the
//! weights reproduce linear fields. A point without a domain gets the linear weights.

use super::domain::{Deformed, Follow, Stretched};
use super::{corners, Kernel, Linear, Point, Reach, Weights};
use crate::grid::floor_i64;
use nalgebra::SVector;
use std::marker::PhantomData;

/// The vertex form with the domain of rule `M`.
pub struct Vertices<M>(PhantomData<M>);

/// CPDI1: the domain deformed by the whole F, R = F diag(a).
pub type Cpdi = Vertices<Deformed>;

/// cpGIMP as the thesis runs it, "a CPDI category" (§10.1): the vertex form with the
/// domain stretched by the diagonal of F only, R = diag(F_kk a_k) (shear neglected).
pub type CpGimp = Vertices<Stretched>;

impl<M: Follow, const D: usize> Kernel<D> for Vertices<M> {
    const DOMAIN: bool = true;

    fn extent(p: &Point<'_, D>) -> SVector<f64, D> {
        let r = M::edges(p.half, p.f);
        SVector::from_fn(|i, _| r.row(i).abs().sum() * p.inv_h[i])
    }

    fn nodes(e: &SVector<f64, D>) -> usize {
        vertex_nodes(e)
    }

    fn evaluate(p: &Point<'_, D>, out: &mut impl Weights<D>) {
        let r = M::edges(p.half, p.f);
        let r_inv = (p.half.min() > 0.0).then(|| r.try_inverse()).flatten();
        let Some(r_inv_t) = r_inv.map(|r_inv| r_inv.transpose()) else {
            return vertex_weights(p, &[], out);
        };
        let share = 1.0 / corners(D) as f64;
        let vertices: [Vertex<D>; 8] = std::array::from_fn(|j| {
            let sign =
                SVector::<f64, D>::from_fn(|k, _| if (j >> k) & 1 == 1 { 1.0 } else { -1.0 });
            (r * sign, share, r_inv_t * sign * share)
        });
        vertex_weights(p, &vertices[..corners(D)], out)
    }
}

/// One vertex of a domain: its offset from the point x^j − x_p [m], its share w_j / v of
/// the weight [-] and its gradient vector g_j / v [1/m] (eq. 10.4).
pub(super) type Vertex<const D: usize> = (SVector<f64, D>, f64, SVector<f64, D>);

/// e_i = max_j |x^j_i − x_p,i| / h_i: the vertices' largest distance from the point per
/// axis [cells].
pub(super) fn vertex_extent<'a, const D: usize>(
    offsets: impl IntoIterator<Item = &'a SVector<f64, D>>,
    inv_h: &SVector<f64, D>,
) -> SVector<f64, D> {
    offsets
        .into_iter()
        .fold(SVector::<f64, D>::zeros(), |e, d| e.sup(&d.abs()))
        .component_mul(inv_h)
}

/// Most nodes the vertices of a domain of half-extents `e` [cells] reach: those of the box
/// it meets, and at most the 2ᴰ corners of each of the 2ᴰ vertices' cells.
pub(super) fn vertex_nodes<const D: usize>(e: &SVector<f64, D>) -> usize {
    Reach::box_nodes(e).min(corners(D) * corners(D))
}

/// N^I = Σ_j (w_j / v) N^I(x^j) and ∇N^I = Σ_j (g_j / v) N^I(x^j) over `vertices`
/// (module docs); no vertices: the linear weights of the point's cell. The shares are
/// summed per node in a box of 4 nodes per axis when the vertices' cells lie within 3
/// cells along every axis (every domain stretched less than about a cell), else in a list
/// searched on each share.
pub(super) fn vertex_weights<const D: usize>(
    p: &Point<'_, D>,
    vertices: &[Vertex<D>],
    out: &mut impl Weights<D>,
) {
    if vertices.is_empty() {
        return Linear::evaluate(p, out);
    }
    // room for the most nodes a vertex kernel reaches, 4ᴰ
    match D {
        3 => summed::<D, 64>(p, vertices, out),
        _ => summed::<D, 16>(p, vertices, out),
    }
}

/// `vertex_weights` for at least one vertex, the shares summed in room for `MOST` nodes.
#[inline(always)]
fn summed<const D: usize, const MOST: usize>(
    p: &Point<'_, D>,
    vertices: &[Vertex<D>],
    out: &mut impl Weights<D>,
) {
    let mut cell = [[0i64; D]; 8];
    let mut local = [SVector::<f64, D>::zeros(); 8];
    for (j, (offset, ..)) in vertices.iter().enumerate() {
        let x = p.xi + offset.component_mul(p.inv_h);
        cell[j] = std::array::from_fn(|k| floor_i64(x[k]));
        local[j] = SVector::from_fn(|k, _| x[k] - cell[j][k] as f64);
    }
    let mut sums = [Sums::ZERO; MOST];
    let at = (vertices, &cell, &local);
    if let Some(lo) = four_node_box(&cell[..vertices.len()]) {
        // node m of the box of 4 nodes per axis from `lo` is entry Σ_k (m_k − lo_k) 4^k;
        // the entries touched are marked, and given in entry order (x fastest)
        let corner: [usize; 8] =
            std::array::from_fn(|c| (0..D).map(|k| ((c >> k) & 1) << (2 * k)).sum());
        let mut touched = 0u64;
        let at_box = |cell: &[i64; D], c: usize| {
            let base: usize = (0..D)
                .map(|k| ((cell[k] - lo[k]) as usize) << (2 * k))
                .sum();
            touched |= 1 << (base + corner[c]);
            base + corner[c]
        };
        spread(at, at_box, &mut sums);
        while touched != 0 {
            let k = touched.trailing_zeros() as usize;
            touched &= touched - 1;
            let node = std::array::from_fn(|i| lo[i] + ((k >> (2 * i)) & 3) as i64);
            emit(node, &sums[k], out);
        }
    } else {
        let mut nodes: Vec<[i64; D]> = Vec::with_capacity(MOST);
        let at_list = |cell: &[i64; D], c: usize| {
            let node = std::array::from_fn(|k| cell[k] + ((c >> k) & 1) as i64);
            nodes.iter().position(|m| *m == node).unwrap_or_else(|| {
                nodes.push(node);
                nodes.len() - 1
            })
        };
        spread(at, at_list, &mut sums);
        for (k, node) in nodes.iter().enumerate() {
            emit(*node, &sums[k], out);
        }
    }
}

/// The lowest corner of the box of 4 nodes per axis that holds every node of the cells
/// `cells` [cell indices], `None` if they lie more than 3 cells apart along some axis. In
/// the box, node m is entry Σ_k (m_k − lo_k) 4^k: ascending entries are ascending node
/// numbers on a grid numbered x fastest.
pub(crate) fn four_node_box<const D: usize>(cells: &[[i64; D]]) -> Option<[i64; D]> {
    let lo: [i64; D] = std::array::from_fn(|k| cells.iter().map(|c| c[k]).min().unwrap_or(0));
    let fits = (0..D).all(|k| cells.iter().all(|c| c[k] - lo[k] <= 2));
    fits.then_some(lo)
}

/// The vertices, the cells that hold them and their local coordinates in those cells.
type Placed<'a, const D: usize> = (&'a [Vertex<D>], &'a [[i64; D]; 8], &'a [SVector<f64, D>; 8]);

/// One entry's sums (N, ∇N_1, ..., ∇N_D, then zeros), the four numbers one 256-bit
/// operation updates.
#[derive(Clone, Copy)]
#[repr(align(32))]
struct Sums([f64; 4]);

impl Sums {
    const ZERO: Sums = Sums([0.0; 4]);

    /// A vertex's weight share w and gradient vector g (`Vertex`) as one entry's sums.
    #[inline(always)]
    fn of_vertex<const D: usize>(share: f64, g: &SVector<f64, D>) -> Sums {
        Sums(std::array::from_fn(|l| match l {
            0 => share,
            _ if l <= D => g[l - 1],
            _ => 0.0,
        }))
    }

    /// self += v w, lane by lane (the products and sums of N += w_j N_c and
    /// ∇N += g_j N_c).
    #[inline(always)]
    fn add_scaled(&mut self, v: &Sums, w: f64) {
        for l in 0..4 {
            self.0[l] += v.0[l] * w;
        }
    }
}

/// Add the share of each vertex, weight share w and gradient vector g (`Vertex`) times the
/// linear weight of each corner c of its cell, to the entries `slot(cell, c)`.
#[inline(always)]
fn spread<const D: usize>(
    (vertices, cell, local): Placed<'_, D>,
    mut slot: impl FnMut(&[i64; D], usize) -> usize,
    sums: &mut [Sums],
) {
    const { assert!(D <= 3, "N and the D entries of ∇N fill at most four lanes") };
    for (j, (_, share, g)) in vertices.iter().enumerate() {
        let vertex = Sums::of_vertex(*share, g);
        // corner weights Π_k (1 − ξ_k or ξ_k), built axis by axis (x fastest)
        let mut weight = [0.0; 8];
        weight[0] = 1.0;
        for k in 0..D {
            let half = 1 << k;
            for c in 0..half {
                weight[c + half] = weight[c] * local[j][k];
                weight[c] *= 1.0 - local[j][k];
            }
        }
        for (c, &w) in weight.iter().enumerate().take(corners(D)) {
            sums[slot(&cell[j], c)].add_scaled(&vertex, w);
        }
    }
}

/// Whether the vertices reach a node whose sums are N and ∇N: not both zero. The vertex
/// form's lists hold only the nodes reached (the derivative pass keeps the others, whose
/// derivatives need not be zero, and leaves them out of the weights it gives the run).
#[inline]
pub(crate) fn reached<const D: usize>(n: f64, grad: &SVector<f64, D>) -> bool {
    n != 0.0 || *grad != SVector::<f64, D>::zeros()
}

/// Node `offset` with N and ∇N (`sums`) to `out`, if the vertices reach it.
#[inline]
fn emit<const D: usize>(offset: [i64; D], sums: &Sums, out: &mut impl Weights<D>) {
    let (n, grad) = (sums.0[0], SVector::<f64, D>::from_fn(|k, _| sums.0[k + 1]));
    if reached(n, &grad) {
        out.push(offset, n, grad);
    }
}
