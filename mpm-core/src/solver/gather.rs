//! Grid-to-particle transfer (algorithms 11-12): point velocities from the nodal
//! accelerations, the grid velocity ṽ for the position update, and the velocity gradient
//! L = Σ v_I ⊗ ∇N_I that updates F, V, σ and the material history (the out-of-plane
//! terms from `Kinematics::deformation`).
//!
//! A block's points go a piece (`parallel::MATERIAL_PIECE`) at a time: the interpolation and
//! new F of every point of the piece, then one `Material::update_batch` for all of them
//! (the plastic returns four at a time in lockstep), then V, bulk viscosity and work.

use super::{Settings, Solver};
use crate::failure::{Cause, SimulationError};
use crate::grid::Grid;
use crate::grid::Node;
use crate::kinematics::Kinematics;
use crate::material_block::wave_speed;
use crate::parallel;
use crate::parallel::fixed_sum;
use crate::viscosity::BulkViscosity;
use crate::weights::WeightCache;
use materials::material::Converged;
use materials::Scalar;
use materials::{Material, State};
use nalgebra::{Matrix3, SMatrix, SVector};
use rayon::prelude::*;
use std::sync::Mutex;

/// Σ N v_I, Σ N a_I and L = Σ v_I ⊗ ∇N_I at a point that reaches the nodes `node` with
/// weights `n` and gradients `grad`, in any scalar (dual in the derivative pass,
/// `tangent`). Always inlined: a caller that reads only some of the three leaves the
/// others' sums out (for five dual directions the compiler would otherwise call it
/// and form all three).
#[inline(always)]
pub(super) fn interpolate<T: Scalar, const D: usize>(
    nodes: &[Node<D, T>],
    (node, n, grad): (&[u32], &[T], &[SVector<T, D>]),
) -> (SVector<T, D>, SVector<T, D>, SMatrix<T, D, D>) {
    let mut vg = SVector::<T, D>::zeros();
    let mut a = SVector::<T, D>::zeros();
    let mut l = SMatrix::<T, D, D>::zeros();
    // written out entry by entry: nalgebra's products with a scalar and its general
    // product are several times slower for dual scalars, and give the same numbers
    for (c, &index) in node.iter().enumerate() {
        let node = &nodes[index as usize];
        vg += SVector::<T, D>::from_fn(|i, _| node.velocity[i] * n[c]);
        a += SVector::<T, D>::from_fn(|i, _| node.acceleration[i] * n[c]);
        l += SMatrix::<T, D, D>::from_fn(|i, j| node.velocity[i] * grad[c][j]);
    }
    (vg, a, l)
}

/// What the deformation update of every point of one block shares.
pub(super) struct Deformation<'a> {
    material: &'a dyn Material,
    /// reference density ρ0 [kg/m³]
    rho0: f64,
    dt: f64,
    kinematics: Kinematics,
    viscosity: Option<BulkViscosity>,
    wave_speed: f64,
    cell: f64,
}

/// The points of one piece of a block (`parallel::MATERIAL_PIECE` or fewer), from point
/// `first` of the model on.
struct Piece<'a, const D: usize> {
    first: usize,
    x: &'a [SVector<f64, D>],
    x_ref: &'a [SVector<f64, D>],
    v: &'a mut [SVector<f64, D>],
    v0: &'a [f64],
    volume: &'a mut [f64],
    f: &'a mut [Matrix3<f64>],
    sigma: &'a mut [Matrix3<f64>],
    state: &'a mut [State<f64>],
    v_grid: &'a mut [SVector<f64, D>],
    work: &'a mut [f64],
}

impl<const D: usize> Piece<'_, D> {
    /// Point j's ṽ and L from the grid, and (with `motion` = Some(Δt)) v ← v + a Δt with ṽ
    /// stored for the position update; `None` if its velocity is not finite.
    fn advance(
        &mut self,
        j: usize,
        (grid, weights): (&Grid<D>, &WeightCache<D>),
        motion: Option<f64>,
        failure: &mut Failure,
    ) -> Option<(SVector<f64, D>, SMatrix<f64, D, D>)> {
        let i = self.first + j;
        let w = weights.stencil(i);
        let (vg, a, l) = interpolate(&grid.nodes, (w.node, w.n, w.grad));
        if let Some(dt) = motion {
            self.v[j] += a * dt;
            self.v_grid[j] = vg;
            if !self.v[j].iter().all(|c| c.is_finite()) {
                earliest(failure, i, Cause::NonFinite { what: "velocity" });
                return None;
            }
        }
        Some((vg, l))
    }
}

/// What the update after the material needs of a point's kinematics: its 3-D velocity
/// gradient and det F of the new F (which goes to the material on its own).
#[derive(Clone, Copy)]
struct Kinematic {
    l3: Matrix3<f64>,
    det: f64,
}

/// The earliest failing point of a piece (index in the model) and its cause.
pub(super) type Failure = Option<(usize, Box<Cause>)>;

/// The failure of the lower point index of `a` and `b`.
pub(super) fn earlier(a: Failure, b: Failure) -> Failure {
    match (&a, &b) {
        (Some((i, _)), Some((j, _))) if j < i => b,
        _ => a.or(b),
    }
}

/// Keep point `i`'s `cause` in `failure` if it is the earliest so far.
fn earliest(failure: &mut Failure, i: usize, cause: Cause) {
    *failure = earlier(failure.take(), Some((i, Box::new(cause))));
}

impl<'a> Deformation<'a> {
    /// The update of points of `material` over `dt` on a grid of smallest cell size
    /// `cell` [m].
    pub(super) fn of<const D: usize>(
        material: &'a dyn Material,
        settings: &Settings<D>,
        cell: f64,
        dt: f64,
    ) -> Self {
        Deformation {
            material,
            rho0: material.density(),
            dt,
            kinematics: settings.kinematics,
            viscosity: settings.bulk_viscosity,
            wave_speed: wave_speed(material),
            cell,
        }
    }

    /// σ − q I: the material stress `sigma` with the bulk viscosity's pressure (module
    /// `viscosity`) at the volumetric rate of deformation tr D = tr L of the velocity
    /// gradient `l3`, and det F `det`, in any scalar.
    #[inline]
    pub(super) fn with_viscosity<T: Scalar>(
        &self,
        sigma: Matrix3<T>,
        l3: &Matrix3<T>,
        det: T,
    ) -> Matrix3<T> {
        match self.viscosity {
            Some(q) => {
                let rho = materials::scalar::c::<T>(self.rho0) / det;
                let trace_d = l3[(0, 0)] + l3[(1, 1)] + l3[(2, 2)];
                sigma - Matrix3::identity() * q.pressure(rho, self.wave_speed, self.cell, trace_d)
            }
            None => sigma,
        }
    }

    /// F ← (I + L Δt) F (with the kinematics' out-of-plane terms), written to `f_new`, and
    /// its checks.
    fn kinematic<const D: usize>(
        &self,
        l: &SMatrix<f64, D, D>,
        vg: &SVector<f64, D>,
        x: (&SVector<f64, D>, &SVector<f64, D>),
        f: &Matrix3<f64>,
        f_new: &mut Matrix3<f64>,
    ) -> Result<Kinematic, Cause> {
        let l3;
        (l3, *f_new) = self.kinematics.deformation(l, vg, x, f, self.dt);
        let det = f_new.determinant();
        if !det.is_finite() {
            return Err(Cause::NonFinite {
                what: "deformation gradient",
            });
        }
        if det <= 0.0 {
            return Err(Cause::InvertedDeformation { det_f: det });
        }
        Ok(Kinematic { l3, det })
    }

    /// σ and history of the piece's points from the material (all at once, `update_batch`;
    /// with `kept`, `update_batch_keeping` into the points' slots, by point index), then
    /// V = det F V0, bulk viscosity and the stress work ½ (σV + σ'V') : D Δt.
    fn update<const D: usize>(
        &self,
        p: &mut Piece<'_, D>,
        (f_new, kinematic): (&[Matrix3<f64>], &[Option<Kinematic>]),
        kept: Option<&Mutex<&mut [Option<Converged>]>>,
        failure: &mut Failure,
    ) {
        let mut updated = [None; parallel::MATERIAL_PIECE];
        let mut deliver = |j: usize, result: Result<(Matrix3<f64>, State<f64>), _>| match result {
            Ok(new) => updated[j] = Some(new),
            Err(e) => earliest(failure, p.first + j, Cause::Material(e)),
        };
        if let (true, Some(kept)) = (kinematic.iter().all(Option::is_some), kept) {
            // the piece's returns gathered here, then written under one lock
            let mut returns = Vec::with_capacity(f_new.len());
            let first = p.first;
            let mut keep = |j: usize, c: &Converged| returns.push((first + j, *c));
            (self.material).update_batch_keeping(f_new, self.dt, p.state, &mut deliver, &mut keep);
            let mut slots = kept.lock().expect("no keeper panics");
            for (i, c) in returns {
                slots[i] = Some(c);
            }
        } else if kinematic.iter().all(Option::is_some) {
            self.material
                .update_batch(f_new, self.dt, p.state, &mut deliver);
        } else {
            // a piece with a failed point (the run stops): the others one by one
            for (j, k) in kinematic.iter().enumerate() {
                if k.is_some() {
                    deliver(j, self.material.update(&f_new[j], self.dt, &p.state[j]));
                }
            }
        }
        for (j, (k, new)) in kinematic.iter().zip(&updated).enumerate() {
            let (Some(k), Some((sigma, state))) = (k, new) else {
                continue;
            };
            let vol_new = k.det * p.v0[j];
            let d = (k.l3 + k.l3.transpose()) * 0.5;
            let sigma_new = self.with_viscosity(*sigma, &k.l3, k.det);
            p.work[j] = 0.5 * (p.sigma[j] * p.volume[j] + sigma_new * vol_new).dot(&d) * self.dt;
            p.f[j] = f_new[j];
            p.volume[j] = vol_new;
            p.sigma[j] = sigma_new;
            p.state[j] = *state;
        }
    }
}

/// What a grid-to-particle transfer updates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Gather {
    /// v_MP ← v_MP + a_MP Δt, and ṽ stored for the position update (algorithm 11).
    Velocity,
    /// F, V, σ and history (algorithm 12).
    Stress,
    /// Both, in one pass over the points (USL).
    VelocityAndStress,
}

impl<const D: usize> Solver<D> {
    /// Grid-to-particle transfer (algorithms 11-12) of what `what` names.
    pub(super) fn gather(&mut self, what: Gather) -> Result<(), SimulationError> {
        let motion = what != Gather::Stress;
        let deformation = what != Gather::Velocity;
        let dt = self.dt;
        let grid = &self.grid;
        let p = &mut self.particles;
        let s = &mut self.scratch;
        let kept = (s.keep_returns && deformation).then(|| {
            s.kept.clear();
            s.kept.resize(p.len(), None);
            Mutex::new(&mut s.kept[..])
        });
        let weights = &s.weights;
        let piece = parallel::MATERIAL_PIECE;
        let mut first_failure: Option<(usize, Cause)> = None;
        for block in &mut self.blocks {
            let r = block.range.clone();
            // the material update is always split, a piece at a time; a velocity update
            // alone is light
            let cut = if deformation {
                parallel::MATERIAL
            } else {
                parallel::light(p.len()).per_item()
            };
            let update = Deformation::of(&*block.material, &self.settings, grid.min_spacing(), dt);
            // a failure travels boxed: the per-piece Option stays one word wide instead of
            // a whole `Cause` copied through the reduction
            let pieces = (
                p.position[r.clone()].par_chunks(piece),
                p.reference_position[r.clone()].par_chunks(piece),
                p.velocity[r.clone()].par_chunks_mut(piece),
                p.volume0[r.clone()].par_chunks(piece),
                p.volume[r.clone()].par_chunks_mut(piece),
                p.deformation[r.clone()].par_chunks_mut(piece),
                p.stress[r.clone()].par_chunks_mut(piece),
                block.state.par_chunks_mut(piece),
                s.grid_velocity[r.clone()].par_chunks_mut(piece),
                s.work[r.clone()].par_chunks_mut(piece),
            )
                .into_par_iter()
                .enumerate();
            let piece_failure = |(c, (x, x_ref, v, v0, volume, f, sigma, state, v_grid, work))| {
                let mut points = Piece {
                    first: r.start + c * piece,
                    x,
                    x_ref,
                    v,
                    v0,
                    volume,
                    f,
                    sigma,
                    state,
                    v_grid,
                    work,
                };
                let (n, mut failure) = (points.v.len(), None);
                let (from, motion) = ((grid, weights), motion.then_some(dt));
                if !deformation {
                    for j in 0..n {
                        points.advance(j, from, motion, &mut failure);
                    }
                    return failure;
                }
                let mut f_new = [Matrix3::zeros(); parallel::MATERIAL_PIECE];
                let mut kinematic = [None; parallel::MATERIAL_PIECE];
                for j in 0..n {
                    if let Some((vg, l)) = points.advance(j, from, motion, &mut failure) {
                        let x = (&points.x[j], &points.x_ref[j]);
                        match update.kinematic(&l, &vg, x, &points.f[j], &mut f_new[j]) {
                            Ok(ok) => kinematic[j] = Some(ok),
                            Err(e) => earliest(&mut failure, points.first + j, e),
                        }
                    }
                }
                let batch = (&f_new[..n], &kinematic[..n]);
                update.update(&mut points, batch, kept.as_ref(), &mut failure);
                failure
            };
            let failure = parallel::fold(
                pieces,
                cut,
                None,
                |first, piece| earlier(first, piece_failure(piece)),
                earlier,
            );
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
