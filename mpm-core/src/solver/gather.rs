//! Grid-to-particle transfer (algorithms 11-12): point velocities from the nodal
//! accelerations, the grid velocity ṽ for the position update, and the velocity gradient
//! L = Σ v_I ⊗ ∇N_I that updates F, V, σ and the material history (the out-of-plane
//! terms from `Kinematics::deformation`).

use super::Solver;
use crate::failure::{Cause, SimulationError};
use crate::grain;
use crate::grid::Grid;
use crate::kinematics::Kinematics;
use crate::sum::fixed_sum;
use crate::viscosity::BulkViscosity;
use crate::weights::Stencil;
use materials::{Material, State};
use nalgebra::{Matrix3, SMatrix, SVector};
use rayon::prelude::*;

/// Σ N v_I, Σ N a_I and L = Σ v_I ⊗ ∇N_I at one point.
#[inline]
fn interpolate<const D: usize>(
    grid: &Grid<D>,
    w: &Stencil<'_, D>,
) -> (SVector<f64, D>, SVector<f64, D>, SMatrix<f64, D, D>) {
    let mut vg = SVector::<f64, D>::zeros();
    let mut a = SVector::<f64, D>::zeros();
    let mut l = SMatrix::<f64, D, D>::zeros();
    for (c, offset) in w.offsets.iter().enumerate() {
        if w.n[c] == 0.0 && w.grad[c] == SVector::<f64, D>::zeros() {
            continue; // a stencil node the domain does not reach (`Stencil`)
        }
        let node = &grid.nodes[w.first + offset];
        vg += node.velocity * w.n[c];
        a += node.acceleration * w.n[c];
        l += node.velocity * w.grad[c].transpose();
    }
    (vg, a, l)
}

/// What the deformation update of every point of one block shares.
struct Deformation<'a> {
    material: &'a dyn Material,
    dt: f64,
    kinematics: Kinematics,
    viscosity: Option<BulkViscosity>,
    wave_speed: f64,
    cell: f64,
}

/// One point's deformation state, updated in place.
struct PointDeformation<'a> {
    f: &'a mut Matrix3<f64>,
    volume: &'a mut f64,
    sigma: &'a mut Matrix3<f64>,
    state: &'a mut State<f64>,
    work: &'a mut f64,
}

impl Deformation<'_> {
    /// F ← (I + L Δt) F (with the kinematics' out-of-plane terms), V = det F V0, σ and
    /// history from the material, bulk viscosity, and the stress work ½ (σV + σ'V') : D Δt.
    fn update<const D: usize>(
        &self,
        l: &SMatrix<f64, D, D>,
        vg: &SVector<f64, D>,
        (x, x_ref, v0): (&SVector<f64, D>, &SVector<f64, D>, f64),
        p: PointDeformation<'_>,
    ) -> Result<(), Cause> {
        let dt = self.dt;
        let (l3, f_new) = self.kinematics.deformation(l, vg, (x, x_ref), p.f, dt);
        let det = f_new.determinant();
        if !det.is_finite() {
            return Err(Cause::NonFinite {
                what: "deformation gradient",
            });
        }
        if det <= 0.0 {
            return Err(Cause::InvertedDeformation { det_f: det });
        }
        let (mut sigma_new, state_new) = self
            .material
            .update(&f_new, dt, p.state)
            .map_err(Cause::Material)?;
        let vol_new = det * v0;
        let d = (l3 + l3.transpose()) * 0.5;
        if let Some(q) = self.viscosity {
            let rho = self.material.density() / det;
            let q = q.pressure(rho, self.wave_speed, self.cell, d.trace());
            sigma_new -= Matrix3::identity() * q;
        }
        *p.work = 0.5 * (*p.sigma * *p.volume + sigma_new * vol_new).dot(&d) * dt;
        *p.f = f_new;
        *p.volume = vol_new;
        *p.sigma = sigma_new;
        *p.state = state_new;
        Ok(())
    }
}

impl<const D: usize> Solver<D> {
    /// Grid-to-particle transfer (algorithms 11-12). With `motion`: v_MP ← v_MP + a_MP Δt
    /// and ṽ stored for the position update. With `deformation`: F, V, σ and history.
    pub(super) fn gather(
        &mut self,
        motion: bool,
        deformation: bool,
    ) -> Result<(), SimulationError> {
        let dt = self.dt;
        let grid = &self.grid;
        let p = &mut self.particles;
        let s = &mut self.scratch;
        let weights = &s.weights;
        let mut first_failure: Option<(usize, Cause)> = None;
        for block in &mut self.blocks {
            let r = block.range.clone();
            // the material update is always split, finely; a velocity update alone is light
            let (least, most) = if deformation {
                (1, grain::MATERIAL_PIECE)
            } else {
                (grain::light(p.len()), usize::MAX)
            };
            let update = Deformation {
                material: &*block.material,
                dt,
                kinematics: self.settings.kinematics,
                viscosity: self.settings.bulk_viscosity,
                wave_speed: block.wave_speed(),
                cell: grid.min_spacing(),
            };
            // a failure travels boxed: the per-point Option stays one word wide instead of
            // a whole `Cause` copied through the reduction for every point (≈ 7 % of a
            // small model's step, issue 15)
            let failure = (
                &p.position[r.clone()],
                &p.reference_position[r.clone()],
                &mut p.velocity[r.clone()],
                &p.volume0[r.clone()],
                &mut p.volume[r.clone()],
                &mut p.deformation[r.clone()],
                &mut p.stress[r.clone()],
                &mut block.state[..],
                &mut s.grid_velocity[r.clone()],
                &mut s.work[r.clone()],
            )
                .into_par_iter()
                .enumerate()
                .with_min_len(least)
                .with_max_len(most)
                .filter_map(
                    |(j, (x, x_ref, v, v0, volume, f, sigma, state, v_grid, work))| {
                        let i = r.start + j;
                        let (vg, a, l) = interpolate(grid, &weights.stencil(i));
                        if motion {
                            *v += a * dt;
                            *v_grid = vg;
                            if !v.iter().all(|c| c.is_finite()) {
                                let cause = Cause::NonFinite { what: "velocity" };
                                return Some((i, Box::new(cause)));
                            }
                        }
                        if !deformation {
                            return None;
                        }
                        let point = PointDeformation {
                            f,
                            volume,
                            sigma,
                            state,
                            work,
                        };
                        update
                            .update(&l, &vg, (x, x_ref, *v0), point)
                            .err()
                            .map(|cause| (i, Box::new(cause)))
                    },
                )
                .min_by_key(|(i, _)| *i);
            if first_failure.is_none() {
                first_failure = failure.map(|(i, cause)| (i, *cause));
            }
        }
        if let Some((i, cause)) = first_failure {
            return Err(self.failure(Some(i), cause));
        }
        if deformation {
            let w = &self.scratch.work;
            self.energies.internal += fixed_sum(w.len(), 0.0, |i| w[i]);
        }
        Ok(())
    }
}
