//! Driver records and their CSV form.

use crate::material::State;
use crate::scalar::Scalar;
use crate::tensor::{von_mises, M3};
use nalgebra::SymmetricEigen;
use std::io::Write;
use std::path::Path;

/// The material point at one time.
#[derive(Debug, Clone, Copy)]
pub struct Record<D = f64> {
    pub time: f64,
    /// Deformation gradient.
    pub f: M3<D>,
    /// Cauchy stress [Pa].
    pub sigma: M3<D>,
    pub state: State<D>,
}

impl<D: Scalar> Record<D> {
    /// Axial force on an SHPB specimen of initial cross-section `a0` [m²] loaded along
    /// x: F = σ_xx A0 L0 / L (plastically incompressible, elastic volume change
    /// neglected) [N].
    pub fn shpb_force(&self, a0: f64) -> D {
        self.sigma[(0, 0)] * D::from(a0) / self.f[(0, 0)]
    }

    /// Logarithmic (Hencky) strain ½ ln(F Fᵀ).
    pub fn hencky_strain(&self) -> M3<f64> {
        let f = self.f.map(|x| x.re());
        let eig = SymmetricEigen::new(f * f.transpose());
        let v = eig.eigenvectors;
        v * M3::from_diagonal(&eig.eigenvalues.map(|l| 0.5 * l.ln())) * v.transpose()
    }
}

pub const CSV_HEADER: &str = "time_s,strain_xx,strain_yy,strain_zz,strain_xy,strain_yz,strain_xz,stress_xx_pa,stress_yy_pa,stress_zz_pa,stress_xy_pa,stress_yz_pa,stress_xz_pa,von_mises_pa,alpha,theta_k";

/// Write records as CSV: time, Hencky strains, Cauchy stresses, von Mises stress, α, θ,
/// and with `shpb_area` = Some(A0 [m²]) the specimen force `force_n`.
pub fn write_csv<D: Scalar>(
    path: &Path,
    records: &[Record<D>],
    shpb_area: Option<f64>,
) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(
        w,
        "{CSV_HEADER}{}",
        if shpb_area.is_some() { ",force_n" } else { "" }
    )?;
    for r in records {
        let e = r.hencky_strain();
        let s = r.sigma.map(|x| x.re());
        write!(
            w,
            "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            r.time,
            e[(0, 0)],
            e[(1, 1)],
            e[(2, 2)],
            e[(0, 1)],
            e[(1, 2)],
            e[(0, 2)],
            s[(0, 0)],
            s[(1, 1)],
            s[(2, 2)],
            s[(0, 1)],
            s[(1, 2)],
            s[(0, 2)],
            von_mises(&s),
            r.state.alpha.re(),
            r.state.theta.re()
        )?;
        match shpb_area {
            Some(a0) => writeln!(w, ",{:e}", r.shpb_force(a0).re())?,
            None => writeln!(w)?,
        }
    }
    w.flush()
}
