//! Grid shape functions behind one interface, `Kernel` (thesis chapter 10 and appendix E):
//! linear (classic MPM), uGIMP, cpGIMP (the thesis's vertex form and the analytic form of
//! the literature) and CPDI1. Every kernel maps a point to a box of
//! `support`ᴰ nodes (x fastest) that starts at most `pad` nodes below the lower corner of
//! the point's cell; both follow from the largest domain half-extent e [cells] of the step
//! (`Reach::of`), so the grid padding and the slab width of the lock-free parallel scatter
//! grow with stretched domains without changing anything else. Weights and gradients are
//! evaluated once per particle and step into a `WeightCache` and read by every transfer.
//!
//! The domain of a point is the box of reference half-widths a_k (`Particles::half_size`)
//! carried along by its deformation gradient F: not at all (uGIMP), by the diagonal of F
//! (cpGIMP) or by the whole F (CPDI1, domain vectors r_k = F a_k e_k, eq. 10.4); or, for
//! `CpdiHex`, any quadrilateral or hexahedron (`Particles::hex`, e.g. a mesh element)
//! carried by F. A point without a domain (a_k = 0) gets the linear weights from every
//! kernel.

mod cpdi;
pub mod domain;
mod gimp;
mod hex;
mod linear;

pub use cpdi::{CpGimp, Cpdi, Vertices};
pub use gimp::{CpGimpAnalytic, Gimp, UGimp};
pub use hex::{CpdiHex, FoldedDomain, Hex};
pub use linear::{linear, CellWeights, Linear};

use nalgebra::{Matrix3, SVector};

pub use crate::grid::corners;

/// Most stencil nodes a point may reach (`support`ᴰ): in 3D a domain half-extent of
/// 4 cells, in 2D 14.5 cells.
pub const MAX_STENCIL_NODES: usize = 1000;

/// Most stencil nodes along one axis (the GIMP factors' fixed arrays; in 2D and 3D
/// `MAX_STENCIL_NODES` is the tighter bound).
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

/// Stencil size of one step: `support` nodes per axis, starting at most `pad` nodes below
/// the lower corner of a point's cell.
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

    /// Stencil nodes per point, supportᴰ.
    pub fn nodes(&self, d: usize) -> usize {
        self.support.pow(d as u32)
    }

    /// Whether a `d`-dimensional stencil of this reach stays within `MAX_STENCIL_NODES`
    /// and `MAX_SUPPORT`.
    pub fn fits(&self, d: usize) -> bool {
        self.nodes(d) <= MAX_STENCIL_NODES && self.support <= MAX_SUPPORT
    }
}

/// A shape function: which nodes a point reaches and with what weights.
pub trait Kernel<const D: usize> {
    /// Whether the weights depend on a domain (false: the stencil is the point's cell).
    const DOMAIN: bool;
    /// Half-extent of the point's current domain along each axis [cells] (`p.xi` unused).
    fn extent(p: &Point<'_, D>) -> SVector<f64, D>;
    /// Weights N and gradients ∇N [1/m] of a stencil of `reach.support` nodes per axis
    /// (`n` and `grad` hold supportᴰ entries, x fastest); returns the first node of the
    /// stencil per axis, counted from the lower corner of the point's cell (−pad … 0).
    /// Nodes a domain would reach beyond the stencil are reached only by rounding and
    /// carry weights at the rounding level; they are left out.
    fn evaluate(
        p: &Point<'_, D>,
        reach: Reach,
        n: &mut [f64],
        grad: &mut [SVector<f64, D>],
    ) -> [i64; D];
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

/// Node `node` of a stencil of `support` nodes per axis as per-axis indices (x fastest).
#[inline]
fn node_index<const D: usize>(node: usize, support: usize) -> [usize; D] {
    let mut rest = node;
    std::array::from_fn(|_| {
        let k = rest % support;
        rest /= support;
        k
    })
}

#[cfg(test)]
mod tests;
