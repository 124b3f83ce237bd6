//! Grid shape functions behind one interface, `Kernel` (thesis chapter 10 and appendix E):
//! linear (classic MPM), uGIMP, cpGIMP (the thesis's vertex form and the analytic form of
//! the literature) and CPDI1. Every kernel gives a point the list of nodes it reaches
//! (`Kernel::evaluate`), as the thesis and NairnMPM do: the 2ᴰ corners of its cell
//! (linear), the nodes of the cells that hold its domain's vertices, at most 4ᴰ (CPDI and
//! the thesis's cpGIMP, however far the domain stretches), or the nodes whose hats meet
//! its box (GIMP, a tensor product). The largest domain half-extent e [cells] of the step
//! (`Reach::of`) sizes the grid padding and the slab width of the lock-free parallel
//! scatter. Weights and gradients are evaluated once per particle and step into a
//! `WeightCache` and read by every transfer.
//!
//! The domain of a point is the box of reference half-widths a_k (`Particles::half_size`)
//! carried along by its deformation gradient F: not at all (uGIMP), by the diagonal of F
//! (cpGIMP) or by the whole F (CPDI1, domain vectors r_k = F a_k e_k, eq. 10.4); or, for
//! `CpdiHex`, any quadrilateral or hexahedron (`Particles::hex`, e.g. a mesh element)
//! carried by F. A point without a domain (a_k = 0) gets the linear weights from every
//! kernel.

pub(crate) mod cpdi;
pub mod domain;
pub(crate) mod gimp;
mod hex;
mod linear;

pub use cpdi::{CpGimp, Cpdi, Vertices};
pub use gimp::{CpGimpAnalytic, Gimp, UGimp};
pub use hex::{CpdiHex, FoldedDomain, Hex};
pub use linear::{linear, CellWeights, Linear};

use nalgebra::{Matrix3, SVector};

pub use crate::grid::corners;

/// Most nodes a GIMP point may reach, Π_k (⌈2 l_k⌉ + 2): in 3D a box of half-width
/// 4 cells along every axis. Vertex kernels reach at most 4ᴰ nodes.
pub const MAX_STENCIL_NODES: usize = 1000;

/// Most nodes a GIMP point may reach along one axis (the factors' fixed arrays): a
/// half-width of 15 cells.
pub const MAX_SUPPORT: usize = 32;

/// One point as a kernel sees it.
#[derive(Debug, Clone, Copy)]
pub struct Point<'a, const D: usize> {
    /// Local coordinates in the point's cell, in [0, 1)ᴰ.
    pub xi: SVector<f64, D>,
    /// Reference domain half-widths a_k [m].
    pub half: &'a SVector<f64, D>,
    /// Deformation gradient F (3×3 in every kinematics; the in-plane block is used).
    pub f: &'a Matrix3<f64>,
    /// Reference hexahedral domain (`CpdiHex` only; `None` elsewhere).
    pub hex: Option<&'a Hex<D>>,
    /// Inverse cell size 1/h_k [1/m].
    pub inv_h: &'a SVector<f64, D>,
}

/// How far the points of one step reach: at most `support` nodes per axis, starting at
/// most `pad` nodes below the lower corner of a point's cell (the grid's padding and the
/// scatter's slab width).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reach {
    pub support: usize,
    pub pad: usize,
}

impl Default for Reach {
    fn default() -> Self {
        Reach::CELL
    }
}

impl Reach {
    /// The linear kernel's reach: the 2ᴰ corners of the cell.
    pub const CELL: Reach = Reach { support: 2, pad: 0 };

    /// The reach of domains of half-extent up to `e` cells: a domain [ξ − e, ξ + e] meets
    /// the supports of the nodes ⌊ξ − e⌋ … ⌊ξ + e⌋ + 1, at most ⌈2e⌉ + 2 of them, the first
    /// at most ⌈e⌉ below the cell's lower corner.
    pub fn of(e: f64) -> Reach {
        Reach {
            support: (2.0 * e).ceil() as usize + 2,
            pad: e.ceil() as usize,
        }
    }

    /// Nodes of the box a domain of half-extents `e` [cells] meets, Π_k (⌈2 e_k⌉ + 2).
    #[inline]
    pub fn box_nodes<const D: usize>(e: &SVector<f64, D>) -> usize {
        let mut nodes = 1;
        for &e in e.iter() {
            nodes *= Reach::of(e).support;
        }
        nodes
    }
}

/// Where a kernel writes the nodes a point reaches.
pub trait Weights<const D: usize> {
    /// Node `offset` (per axis, in cells from the lower corner of the point's cell) with
    /// weight N_I and gradient ∇N_I [1/m].
    fn push(&mut self, offset: [i64; D], n: f64, grad: SVector<f64, D>);
}

/// A shape function: which nodes a point reaches and with what weights.
pub trait Kernel<const D: usize> {
    /// Whether the weights depend on a domain (false: the nodes are the point's cell's).
    const DOMAIN: bool;
    /// Half-extent of the point's current domain along each axis [cells] (`p.xi` unused).
    fn extent(p: &Point<'_, D>) -> SVector<f64, D>;
    /// Most nodes `evaluate` gives a point of domain half-extents `e` [cells].
    fn nodes(e: &SVector<f64, D>) -> usize;
    /// Weights N and gradients ∇N [1/m] of the nodes the point reaches, each node once,
    /// into `out`; nodes with N = 0 and ∇N = 0 may be left out. A node that a domain
    /// reaches only by rounding gets weights at the rounding level.
    fn evaluate(p: &Point<'_, D>, out: &mut impl Weights<D>);
}

/// The shape functions a model can choose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShapeFunction {
    /// Bi-/trilinear (classic MPM).
    #[default]
    Linear,
    /// Uniform GIMP: each point's reference domain, never deformed.
    UGimp,
    /// Convected-particle GIMP as the thesis runs it: CPDI's vertex form with the domain
    /// stretched by the diagonal of F.
    CpGimp,
    /// Convected-particle GIMP of the literature: the hat averaged over the domain
    /// stretched by the diagonal of F.
    CpGimpAnalytic,
    /// CPDI1: the domain deformed by the whole F (parallelogram / parallelepiped).
    Cpdi,
    /// CPDI1 on hexahedral (quadrilateral) domains of any shape, integrated numerically
    /// (`Particles::hex`; a point without one gets its box).
    CpdiHex,
}

impl ShapeFunction {
    /// The kernel of a scene, SHPB scene or fit level that names none: CPDI, the one that
    /// converges under refinement on the Taylor bar, the truss and the SHPB specimen at
    /// 1.2-3× linear's cost (docs/verification.md, "Default shape function"). Code that
    /// builds `Settings` itself gets `ShapeFunction::default()`, linear.
    pub const SCENE_DEFAULT: ShapeFunction = ShapeFunction::Cpdi;

    /// Every kernel, in the order of `NAMES`.
    pub const ALL: [ShapeFunction; 6] = [
        ShapeFunction::Linear,
        ShapeFunction::UGimp,
        ShapeFunction::CpGimp,
        ShapeFunction::CpGimpAnalytic,
        ShapeFunction::Cpdi,
        ShapeFunction::CpdiHex,
    ];

    /// The names of input files.
    pub const NAMES: [&'static str; 6] = [
        "linear",
        "ugimp",
        "cpgimp",
        "cpgimp-analytic",
        "cpdi",
        "cpdi-hex",
    ];

    /// The input-file name.
    pub fn name(&self) -> &'static str {
        Self::NAMES[*self as usize]
    }

    /// Whether points need their domains (`Particles::half_size`).
    pub fn needs_domains(&self) -> bool {
        *self != ShapeFunction::Linear
    }
}

impl std::str::FromStr for ShapeFunction {
    type Err = String;

    fn from_str(name: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .ok_or_else(|| {
                format!(
                    "\"{name}\", expected one of {}",
                    Self::NAMES.map(|n| format!("\"{n}\"")).join(", ")
                )
            })
    }
}

/// The nodes of a box of `dims[k]` nodes along axis k as per-axis indices, x fastest
/// (counted up digit by digit: no division per node).
#[inline]
pub(crate) fn box_indices<const D: usize>(dims: [usize; D]) -> impl Iterator<Item = [usize; D]> {
    let count: usize = dims.iter().product();
    let mut next = [0usize; D];
    (0..count).map(move |_| {
        let index = next;
        for k in 0..D {
            next[k] += 1;
            if next[k] < dims[k] {
                break;
            }
            next[k] = 0;
        }
        index
    })
}

#[cfg(test)]
mod tests;
