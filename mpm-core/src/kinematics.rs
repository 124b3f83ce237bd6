//! Which continuum the 2D or 3D grid represents. Materials always see a 3×3 F.
//!
//! - `PlaneStrain` (D = 2): F = [[F_2D, 0], [0, 1]], so F33 = 1 and L33 = 0.
//! - `Axisymmetric` (D = 2, coordinates (r, z)): the hoop stretch F_θθ = r/R of a point
//!   at radius r that started at R; the hoop strain rate v_r/r enters the stress power and
//!   the internal force gains the hoop term σ_θθ N_I / r in the radial direction
//!   (Sulsky & Schreyer 1996); particle volume is the ring 2π r A.
//! - `Solid` (D = 3): full 3D.

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kinematics {
    PlaneStrain,
    Axisymmetric,
    Solid,
}

impl Kinematics {
    /// Grid dimension this kinematics needs.
    pub fn dimension(self) -> usize {
        match self {
            Kinematics::PlaneStrain | Kinematics::Axisymmetric => 2,
            Kinematics::Solid => 3,
        }
    }
}
