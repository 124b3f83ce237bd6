//! Vertex-form kernels: CPDI1 with parallelogram / parallelepiped domains (Sadeghirad et
//! al. 2011; thesis eq. 10.4 and reading §1.3), and cpGIMP as the thesis runs it, through
//! the same machinery with a shear-free domain. The domain of a point is spanned by the
//! half-edge vectors r_k (R [m], from the in-plane block of F), its 2ᴰ vertices are
//! x^j = x_p + R ξ^j with ξ^j ∈ {±1}ᴰ, and eq. 10.4 integrates to
//!
//!   N^I = 2^{−D} Σ_j N^I(x^j),   ∇N^I = 2^{−D} Σ_j N^I(x^j) R^{−T} ξ^j,
//!
//! with N^I the linear grid functions (appendix E): a point reaches every node of the
//! cells that hold its vertices. Σ_I N^I = 1 and Σ_I ∇N^I = 0 exactly; the weights
//! reproduce linear fields. A point without a domain gets the linear weights.

use super::domain::{Deformed, Follow, Stretched};
use super::{corners, Kernel, Linear, Point, Reach};
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

    fn evaluate(
        p: &Point<'_, D>,
        reach: Reach,
        n: &mut [f64],
        grad: &mut [SVector<f64, D>],
    ) -> [i64; D] {
        let r = M::edges(p.half, p.f);
        let r_inv = (p.half.min() > 0.0).then(|| r.try_inverse()).flatten();
        let Some(r_inv_t) = r_inv.map(|r_inv| r_inv.transpose()) else {
            return vertex_weights(p, &[], reach, n, grad);
        };
        let share = 1.0 / corners(D) as f64;
        let vertices: [Vertex<D>; 8] = std::array::from_fn(|j| {
            let sign =
                SVector::<f64, D>::from_fn(|k, _| if (j >> k) & 1 == 1 { 1.0 } else { -1.0 });
            (r * sign, share, r_inv_t * sign * share)
        });
        vertex_weights(p, &vertices[..corners(D)], reach, n, grad)
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

/// N^I = Σ_j (w_j / v) N^I(x^j) and ∇N^I = Σ_j (g_j / v) N^I(x^j) over `vertices`
/// (module docs); no vertices: the linear weights of the point's cell.
pub(super) fn vertex_weights<const D: usize>(
    p: &Point<'_, D>,
    vertices: &[Vertex<D>],
    reach: Reach,
    n: &mut [f64],
    grad: &mut [SVector<f64, D>],
) -> [i64; D] {
    if vertices.is_empty() {
        return Linear::evaluate(p, reach, n, grad);
    }
    let e = vertex_extent(vertices.iter().map(|v| &v.0), p.inv_h);
    let first: [i64; D] = std::array::from_fn(|k| floor_i64(p.xi[k] - e[k]));
    n.fill(0.0);
    grad.fill(SVector::zeros());
    for (offset, share, g) in vertices {
        let vertex = p.xi + offset.component_mul(p.inv_h);
        let cell: [i64; D] = std::array::from_fn(|k| floor_i64(vertex[k]));
        let local = SVector::<f64, D>::from_fn(|k, _| vertex[k] - cell[k] as f64);
        for corner in 0..corners(D) {
            let mut node = 0;
            let mut weight = 1.0;
            for k in (0..D).rev() {
                let upper = (corner >> k) & 1;
                let index = cell[k] + upper as i64 - first[k];
                if index < 0 || index >= reach.support as i64 {
                    weight = 0.0; // reached by rounding only (see `Kernel::evaluate`)
                }
                node = node * reach.support + index.clamp(0, reach.support as i64 - 1) as usize;
                weight *= if upper == 1 { local[k] } else { 1.0 - local[k] };
            }
            n[node] += share * weight;
            grad[node] += g * weight;
        }
    }
    first
}
