//! Regular Cartesian background grid (appendix E): cell lookup by floor((x − o)/h)
//! (eq. E.1), node coordinates o + n h (eq. E.2) and lexicographic node numbers with x
//! fastest (eq. E.3). The grid is refitted every step to the bounding box of the particles
//! on a lattice fixed by its origin o, so it grows (and shrinks) to hold them. The origin
//! may be displaced for one step by the grid shift of eq. E.8 (see `shift`).
//!
//! Nodal quantities (table 7.1): mass m [kg], momentum p [kg m/s], force f [N], and after
//! the grid solve the velocity v_{n+1/2} [m/s] and acceleration a_n [m/s²].

use materials::Scalar;
use nalgebra::SVector;

/// ⌊s⌋ as an integer, equal to `s.floor() as i64` for |s| < 2⁶³ (and 0 for NaN, as
/// `as` gives). `f64::floor` is a library call on the baseline x86-64 target (no SSE4.1
/// `roundsd`); this is a truncation and a compare, and the cell lookup runs several
/// times per particle and step.
#[inline]
pub fn floor_i64(s: f64) -> i64 {
    let t = s as i64;
    t - i64::from(s < t as f64)
}

/// Number of cell corners in `D` dimensions, 2^D.
pub const fn corners(d: usize) -> usize {
    1 << d
}

/// One grid node's temporary state, in any scalar (dual for the derivative pass of
/// `solver::tangent`).
#[derive(Debug, Clone, Copy)]
pub struct Node<const D: usize, T = f64> {
    pub mass: T,
    /// Mass of the heaviest point that reaches the node [kg] (for the mass cutoff).
    pub heaviest: f64,
    pub momentum: SVector<T, D>,
    pub force: SVector<T, D>,
    pub velocity: SVector<T, D>,
    pub acceleration: SVector<T, D>,
}

impl<const D: usize, T: Scalar> Node<D, T> {
    /// A node with nothing mapped to it.
    pub fn zero() -> Self {
        Node {
            mass: T::zero(),
            heaviest: 0.0,
            momentum: SVector::zeros(),
            force: SVector::zeros(),
            velocity: SVector::zeros(),
            acceleration: SVector::zeros(),
        }
    }
}

impl<const D: usize> Node<D> {
    pub const EMPTY: Self = Node {
        mass: 0.0,
        heaviest: 0.0,
        momentum: SVector::from_array_storage(nalgebra::ArrayStorage([[0.0; D]; 1])),
        force: SVector::from_array_storage(nalgebra::ArrayStorage([[0.0; D]; 1])),
        velocity: SVector::from_array_storage(nalgebra::ArrayStorage([[0.0; D]; 1])),
        acceleration: SVector::from_array_storage(nalgebra::ArrayStorage([[0.0; D]; 1])),
    };
}

#[derive(Debug, Clone)]
pub struct Grid<const D: usize> {
    /// Cell size h_i [m].
    pub spacing: SVector<f64, D>,
    pub inv_spacing: SVector<f64, D>,
    /// Origin of the lattice for the current step (shifted if grid shift is on) [m].
    pub origin: SVector<f64, D>,
    /// Lattice index of the first stored node in each direction.
    pub lo: [i64; D],
    /// Number of stored nodes in each direction.
    pub dims: [usize; D],
    /// Index stride of each direction (x fastest).
    pub strides: [usize; D],
    pub nodes: Vec<Node<D>>,
}

impl<const D: usize> Grid<D> {
    pub fn new(spacing: SVector<f64, D>, origin: SVector<f64, D>) -> Self {
        Grid {
            spacing,
            inv_spacing: spacing.map(|h| 1.0 / h),
            origin,
            lo: [0; D],
            dims: [0; D],
            strides: [0; D],
            nodes: Vec::new(),
        }
    }

    /// The same grid geometry without node storage.
    pub fn clone_meta(&self) -> Self {
        Grid {
            nodes: Vec::new(),
            ..*self
        }
    }

    /// Smallest cell dimension l_cr (eq. 7.22) [m].
    pub fn min_spacing(&self) -> f64 {
        self.spacing.min()
    }

    /// Lattice cell index of a position (eq. E.1).
    #[inline]
    pub fn cell_of(&self, x: &SVector<f64, D>) -> [i64; D] {
        std::array::from_fn(|i| floor_i64((x[i] - self.origin[i]) * self.inv_spacing[i]))
    }

    /// Refit the stored node block to hold the stencils of points in cells from
    /// `cell_min` to `cell_max` (inclusive) for a kernel reaching `support` nodes per axis
    /// from `pad` nodes below a cell's lower corner, and clear every node.
    pub fn fit(&mut self, cell_min: [i64; D], cell_max: [i64; D], pad: usize, support: usize) {
        let mut stride = 1;
        for i in 0..D {
            self.lo[i] = cell_min[i] - pad as i64;
            self.dims[i] = (cell_max[i] - cell_min[i]) as usize + support;
            self.strides[i] = stride;
            stride *= self.dims[i];
        }
        self.nodes.clear();
        self.nodes.resize(stride, Node::EMPTY);
    }

    /// Node number of the lower corner of `cell` (eq. E.3) and the local coordinates of `x`
    /// in that cell.
    #[inline]
    pub fn locate(&self, x: &SVector<f64, D>) -> (usize, SVector<f64, D>) {
        let mut index = 0;
        let mut xi = SVector::<f64, D>::zeros();
        for i in 0..D {
            let s = (x[i] - self.origin[i]) * self.inv_spacing[i];
            let c = floor_i64(s);
            xi[i] = s - c as f64;
            index += (c - self.lo[i]) as usize * self.strides[i];
        }
        (index, xi)
    }

    /// Offsets of the 2^D corners of a cell from its lower corner, in node numbers.
    #[inline]
    pub fn corner_offsets(&self) -> [usize; 8] {
        let mut offsets = [0; 8];
        for (k, offset) in offsets.iter_mut().enumerate().take(corners(D)) {
            for (i, stride) in self.strides.iter().enumerate() {
                if (k >> i) & 1 == 1 {
                    *offset += stride;
                }
            }
        }
        offsets
    }

    /// Lattice coordinates of node number `index`.
    #[inline]
    pub fn node_lattice(&self, index: usize) -> [i64; D] {
        std::array::from_fn(|i| self.lo[i] + ((index / self.strides[i]) % self.dims[i]) as i64)
    }

    /// Position of node number `index` (eq. E.2) [m].
    #[inline]
    pub fn node_position(&self, index: usize) -> SVector<f64, D> {
        let n = self.node_lattice(index);
        SVector::from_fn(|i, _| self.origin[i] + n[i] as f64 * self.spacing[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn floor_i64_agrees_with_floor() {
        for s in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            2.999,
            -2.999,
            -3.0,
            1e15 + 0.5,
            -1e15 - 0.5,
            f64::EPSILON,
            -f64::EPSILON,
            -1e-300,
            4503599627370497.0,
            -4503599627370497.0,
        ] {
            assert_eq!(floor_i64(s), s.floor() as i64, "{s}");
        }
        assert_eq!(floor_i64(f64::NAN), 0);
    }

    #[test]
    fn locate_finds_the_enclosing_cell_and_local_coordinates() {
        let mut g = Grid::new(Vector2::new(0.5, 0.25), Vector2::new(-1.0, 0.0));
        g.fit([0, 0], [3, 3], 0, 2);
        let x = Vector2::new(0.1, 0.3);
        let (base, xi) = g.locate(&x);
        assert_eq!(g.cell_of(&x), [2, 1]);
        assert_eq!(base, 2 + 5); // cell (2, 1) with 5 nodes per row
        assert!((xi - Vector2::new(0.2, 0.2)).norm() < 1e-12);
        let p = g.node_position(base + g.corner_offsets()[3]);
        assert!((p - Vector2::new(0.5, 0.5)).norm() < 1e-12);
    }
}
