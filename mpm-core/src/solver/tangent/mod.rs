//! Exact derivatives of an explicit run with respect to material parameters, in forward
//! mode: beside every point's x, v, ṽ, F, σ, V and history and every node's m, p, f, v, a,
//! the pass carries their derivatives along `P` directions (the free parameters of a fit)
//! as the dual parts of `Dual<P>` numbers.
//!
//! Each stage's derivative runs just before the stage itself and reads the state the
//! stage reads (its contract, `Stage::reads`): real parts from the solver, dual parts from
//! here, through the same generic code as the stage (the weights, `PointShare`,
//! `NodeSolve`, `interpolate`, `Kinematics::deformation`, `Deformation::with_viscosity`,
//! the contact forces and the material's update in dual arithmetic, `SeededModel`). The
//! part of a derivative that needs the stage's own decisions runs just after it: contact
//! after its candidate search, the contact loads after the force map has the masses, the
//! grid-to-particle transfer after the run's material update (whose return it starts
//! from; the real F and history before the update are kept for it). Its
//! real parts are the stage's own numbers, so it takes every branch the run takes: the
//! cell that holds a point, the nodes above the mass cutoff, where a one-sided wall acts,
//! whether a point yields, whether a contact point sticks. What it gives is the
//! derivative of the discrete run at a fixed sequence of Δt and of those decisions: exact
//! between events, and at an event (first yield, a point crossing a cell face, a wall
//! letting go) the one-sided derivative of the branch the run took, where the run itself
//! has a kink.
//!
//! A point whose update gives a non-finite derivative stops the run, naming the point
//! and step (`Cause::NonFinite`), with the output up to there kept.
//!
//! Cost: one dual update per point and step (the return mapping by the implicit function
//! theorem at the run's converged return, dy = −K⁻¹ dr, with y* and K⁻¹ as the run's
//! batched return kept them while a pass runs, `Solver::step_with`) and the transfers in
//! P + 1 lanes. The weights are evaluated once a step, by the pass: their real parts are
//! the run's own to the bit and in its order (linear, CPDI, cpGIMP), and the run takes
//! them instead of evaluating its kernels again (`Solver::step_with`). Memory: (P + 1)
//! numbers for each real one of the state; no tape.
//!
//! Carried: linear, CPDI and cpGIMP weights (module `stencil`), penalty contact with
//! rigid bodies of prescribed motion and with faces on elastic bars, whose displacement
//! follows the contact force (module `contact`), point conditions whose force on a
//! point depends on its position alone (springs: df = (∂f/∂x) dx, with ∂f/∂x from
//! `PointCondition::position_jacobian`), a fraction of PIC in the velocity update
//! (module `pic_blend`), and uGIMP weights. Held fixed, and so refused as
//! free parameters: anything that changes ρ0 (the masses) or the wave speed (Δt). Not
//! carried yet, and refused with the reason: analytic cpGIMP and hexahedral CPDI, and
//! other point conditions.

mod contact;
mod node_sums;
mod stencil;

use super::gather::{earlier, interpolate, Deformation, Failure};
use super::grid_solve::{NodalUpdate, NodeSolve};
use super::scatter::{PointShare, Transfer};
use super::slabs::Slabs;
use super::{Solver, Stage};
use crate::failure::{Cause, SimulationError};
use crate::grid::{Grid, Node};
use crate::material_block::MaterialBlock;
use crate::parallel;
use crate::shape::{Reach, ShapeFunction};
use crate::weights::WeightCache;
use contact::{DualLoad, FaceDerivatives};
use materials::scalar::c;
use materials::seeded::{Dual, SeededModel};
use materials::tensor::{det, det_in};
use materials::State;
use nalgebra::{Matrix3, SMatrix, SVector};
use rayon::prelude::*;
use stencil::{DualStencils, SmoothKernel};

/// Why a run cannot carry exact derivatives (yet).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("exact derivatives: {0}")]
pub struct Unsupported(pub String);

/// The derivatives of a run's state along `P` parameter directions. Invariant: only the
/// dual parts of the stored numbers are kept; a stage's derivative reads the real parts
/// from the solver (`join`), so the pass never drifts from the run it differentiates.
pub struct Tangent<const D: usize, const P: usize> {
    /// One seeded model per material block of the solver.
    models: Vec<Box<dyn SeededModel<P>>>,
    position: Vec<SVector<Dual<P>, D>>,
    velocity: Vec<SVector<Dual<P>, D>>,
    grid_velocity: Vec<SVector<Dual<P>, D>>,
    deformation: Vec<Matrix3<Dual<P>>>,
    stress: Vec<Matrix3<Dual<P>>>,
    volume: Vec<Dual<P>>,
    /// History of every point (by point index; a block's points are contiguous).
    state: Vec<State<Dual<P>>>,
    /// The real F and history of every point before this step's update of the stress,
    /// which the update's derivative reads after the update has replaced them.
    before_update: (Vec<Matrix3<f64>>, Vec<State<f64>>),
    nodes: Vec<Node<D, Dual<P>>>,
    /// Each block's kernel.
    kernels: Vec<SmoothKernel>,
    /// The weights of this step, evaluated by its first transfer.
    stencils: DualStencils<D, P>,
    /// The points in slabs by the lowest node of their weights, for the transfers.
    slabs: Slabs,
    /// Attachment point of each point in contact with each rigid body (by body, then
    /// point index; body frame), real parts the run's as the contact stage left them.
    attachment: Vec<Vec<Option<SVector<Dual<P>, D>>>>,
    /// The contact loads of this step.
    loads: Vec<DualLoad<D, P>>,
    /// Each rigid body's total contact force of this step.
    contact_force: Vec<SVector<Dual<P>, D>>,
    /// Each rigid body's displacement along its elastic bar and the mean velocity v_s
    /// of its contact springs (module `bar`; zero for a body of prescribed motion).
    faces: Vec<FaceDerivatives<P>>,
    /// ∂f/∂x of the point conditions' forces on each point, summed over the conditions
    /// (by point index; empty without conditions).
    condition_stiffness: Vec<SMatrix<f64, D, D>>,
}

/// ∂f/∂x of the point conditions' forces on each point, or why a condition is not carried.
fn condition_stiffness<const D: usize>(
    solver: &Solver<D>,
) -> Result<Vec<SMatrix<f64, D, D>>, String> {
    if solver.conditions.is_empty() {
        return Ok(Vec::new());
    }
    let mut k = vec![SMatrix::zeros(); solver.particles.len()];
    for condition in &solver.conditions {
        let Some(jacobian) = condition.position_jacobian() else {
            return Err(format!(
                "the point condition `{}` does not say how its forces change with the positions",
                condition.describe()
            ));
        };
        for (i, dfdx) in jacobian {
            k[i] += dfdx;
        }
    }
    Ok(k)
}

/// Store the derivatives of `new` in `kept`, entry by entry: the pass keeps only dual
/// parts (`Tangent`), and whole dual matrices went through a call to memcpy.
#[inline]
fn keep_derivatives<const P: usize>(kept: &mut Matrix3<Dual<P>>, new: &Matrix3<Dual<P>>) {
    for (k, n) in kept.iter_mut().zip(new.iter()) {
        k.eps = n.eps;
    }
}

/// `re` with the derivatives of `d`.
#[inline]
fn join<const P: usize>(re: f64, d: Dual<P>) -> Dual<P> {
    Dual::new(re, d.eps)
}

/// Every entry of `re` with the derivatives of the same entry of `d`.
#[inline]
fn join_all<const R: usize, const C: usize, const P: usize>(
    re: &SMatrix<f64, R, C>,
    d: &SMatrix<Dual<P>, R, C>,
) -> SMatrix<Dual<P>, R, C> {
    re.zip_map(d, join)
}

/// `re` with the derivatives of `d`.
fn join_state<const P: usize>(re: &State<f64>, d: &State<Dual<P>>) -> State<Dual<P>> {
    State {
        fp_inv: join_all(&re.fp_inv, &d.fp_inv),
        alpha: join(re.alpha, d.alpha),
        theta: join(re.theta, d.theta),
        dalpha: join(re.dalpha, d.dalpha),
    }
}

/// Whether the derivatives of a point's update are finite, probed on tr σ + α + θ: a
/// non-finite derivative anywhere in the update reaches σ or α and θ within the step, and
/// the probe is one sum where a check of every entry costs the pass time.
fn finite_derivatives<const P: usize>(sigma: &Matrix3<Dual<P>>, state: &State<Dual<P>>) -> bool {
    let probe = sigma.trace() + state.alpha + state.theta;
    probe.eps.iter().all(|d| d.is_finite())
}

/// Nodes of the widest box a uGIMP point's domain meets (0 without uGIMP blocks).
fn widest_gimp_box<const D: usize>(solver: &Solver<D>, kernels: &[SmoothKernel]) -> usize {
    let p = &solver.particles;
    let inv_h = solver.grid.inv_spacing;
    (solver.blocks.iter().zip(kernels))
        .filter(|(_, k)| **k == SmoothKernel::UGimp)
        .flat_map(|(block, _)| block.range.clone())
        .map(|i| Reach::box_nodes(&p.half_size[i].component_mul(&inv_h)))
        .max()
        .unwrap_or(0)
}

/// Whether the pass carries shape functions `kernel`.
pub fn carries(kernel: ShapeFunction) -> bool {
    SmoothKernel::of(kernel).is_some()
}

impl<const D: usize, const P: usize> Tangent<D, P> {
    /// Start the derivative pass of `solver` before its first step, with `models[b]` the
    /// model of block b with its free parameters seeded (`materials::seeded::seeded`).
    pub fn new(
        solver: &Solver<D>,
        models: Vec<Box<dyn SeededModel<P>>>,
    ) -> Result<Self, Unsupported> {
        let refuse = |why: String| Err(Unsupported(why));
        if solver.step != 0 {
            return refuse(format!(
                "the pass starts with the run, and this one is at step {}",
                solver.step
            ));
        }
        if models.len() != solver.blocks.len() {
            return refuse(format!(
                "{} seeded models for {} material blocks",
                models.len(),
                solver.blocks.len()
            ));
        }
        let mut kernels = Vec::with_capacity(models.len());
        for (b, (block, model)) in solver.blocks.iter().zip(&models).enumerate() {
            let kernel = solver.kernel_of(b);
            let Some(smooth) = SmoothKernel::of(kernel) else {
                return refuse(format!(
                    "body `{}` runs {} shape functions; the pass carries linear, cpdi, cpgimp and ugimp",
                    block.name,
                    kernel.name()
                ));
            };
            kernels.push(smooth);
            let (rho, modulus) = (model.density(), model.p_wave_modulus());
            if rho.re != block.material.density() || modulus.re != block.material.p_wave_modulus() {
                return refuse(format!(
                    "the seeded model of body `{}` is not its material (ρ0 {} against {}, Λ+2G {} against {})",
                    block.name, rho.re, block.material.density(), modulus.re, block.material.p_wave_modulus()
                ));
            }
            let depends = |x: Dual<P>| x.eps.iter().any(|d| *d != 0.0);
            if depends(rho) || depends(modulus) {
                return refuse(format!(
                    "a free parameter of body `{}` changes ρ0 or the wave speed, which set the masses and Δt; free only the flow-stress and thermal parameters",
                    block.name
                ));
            }
        }
        let n = solver.particles.len();
        let condition_stiffness = condition_stiffness(solver).map_err(Unsupported)?;
        let zero = SVector::zeros();
        let mut state = Vec::with_capacity(n);
        for (block, model) in solver.blocks.iter().zip(&models) {
            state.extend(std::iter::repeat_n(
                model.initial_state(),
                block.range.len(),
            ));
        }
        Ok(Tangent {
            models,
            position: vec![zero; n],
            velocity: vec![zero; n],
            grid_velocity: vec![zero; n],
            deformation: vec![Matrix3::zeros(); n],
            stress: vec![Matrix3::zeros(); n],
            volume: vec![Dual::from_re(0.0); n],
            state,
            before_update: (Vec::with_capacity(n), Vec::with_capacity(n)),
            nodes: Vec::new(),
            stencils: DualStencils::new(n, &kernels, widest_gimp_box(solver, &kernels)),
            slabs: Slabs::default(),
            kernels,
            attachment: vec![vec![None; n]; solver.rigid.len()],
            loads: Vec::new(),
            contact_force: vec![SVector::zeros(); solver.rigid.len()],
            faces: vec![FaceDerivatives::at_rest(); solver.rigid.len()],
            condition_stiffness,
        })
    }

    /// Position of point `i` with its derivatives.
    pub fn position(&self, solver: &Solver<D>, i: usize) -> SVector<Dual<P>, D> {
        join_all(&solver.particles.position[i], &self.position[i])
    }

    /// Velocity of point `i` with its derivatives.
    pub fn velocity(&self, solver: &Solver<D>, i: usize) -> SVector<Dual<P>, D> {
        join_all(&solver.particles.velocity[i], &self.velocity[i])
    }

    /// F of point `i` with its derivatives.
    pub fn deformation(&self, solver: &Solver<D>, i: usize) -> Matrix3<Dual<P>> {
        join_all(&solver.particles.deformation[i], &self.deformation[i])
    }

    /// σ of point `i` with its derivatives.
    pub fn stress(&self, solver: &Solver<D>, i: usize) -> Matrix3<Dual<P>> {
        join_all(&solver.particles.stress[i], &self.stress[i])
    }

    /// Volume of point `i` with its derivatives.
    pub fn volume(&self, solver: &Solver<D>, i: usize) -> Dual<P> {
        join(solver.particles.volume[i], self.volume[i])
    }

    /// The derivative of `stage`, from the state before it.
    fn before(&mut self, stage: Stage, s: &Solver<D>) -> Result<(), SimulationError> {
        use Stage::*;
        match stage {
            MapMassMomentumForce => self.map(s, Transfer::ALL),
            MapMassMomentum => self.map(s, Transfer::MASS_MOMENTUM),
            MapForce => self.map(s, Transfer::FORCE),
            MapMomentum => self.map(s, Transfer::MOMENTUM),
            SolveMomentum => self.solve(s, NodalUpdate::Accelerate),
            NodalVelocity => self.solve(s, NodalUpdate::VelocityOnly),
            UpdateStress | UpdateVelocityAndStress => self.keep_before_update(s),
            Advect => self.advect(s),
            // the grid's lattice and the forces applied to points do not depend on the
            // parameters; Δt is held; contact, the bar faces and the grid-to-particle
            // transfers follow their stages (`after`)
            FitGrid | AppliedForces | ContactForces | BarFaces | AdvanceTime | CheckEnergy
            | CheckTimeStep | UpdateVelocity => {}
        }
        Ok(())
    }

    /// The part of `stage`'s derivative that needs the stage's own decisions: contact the
    /// candidates its search found, the contact loads of a force map the nodal masses it
    /// mapped (which nodes share a load), the material update the run's own return
    /// (solved once, in the stage).
    fn after(&mut self, stage: Stage, s: &Solver<D>) -> Result<(), SimulationError> {
        match stage {
            Stage::ContactForces => self.contact(s),
            Stage::BarFaces => self.bar_faces(s),
            Stage::MapMassMomentumForce | Stage::MapForce => self.add_surface_loads(s),
            Stage::UpdateVelocity => self.gather::<true, false>(s)?,
            Stage::UpdateStress => self.gather::<false, true>(s)?,
            Stage::UpdateVelocityAndStress => self.gather::<true, true>(s)?,
            _ => {}
        }
        Ok(())
    }

    /// Keep the real F and history that the stress update is about to replace.
    fn keep_before_update(&mut self, s: &Solver<D>) {
        let (f, state) = &mut self.before_update;
        f.clear();
        f.extend_from_slice(&s.particles.deformation);
        state.clear();
        for block in &s.blocks {
            state.extend_from_slice(&block.state);
        }
    }

    /// The weights of every point at the start of the step, from x and F with their
    /// derivatives, on the grid the run has just fitted (in parallel).
    fn evaluate_weights(&mut self, s: &Solver<D>) {
        let (position, deformation, p) = (&self.position, &self.deformation, &s.particles);
        let at = |i: usize| {
            let x = join_all(&p.position[i], &position[i]);
            (
                x,
                join_all(&p.deformation[i], &deformation[i]),
                p.half_size[i],
            )
        };
        for (b, block) in s.blocks.iter().enumerate() {
            (self.stencils).fill(block.range.clone(), self.kernels[b], &s.grid, at);
        }
    }

    /// Write the real parts of this step's weights into the run's cache for the bodies
    /// whose kernels give the run's own weights (`SmoothKernel::gives_run_weights`); the
    /// run evaluates the others' itself.
    fn give_weights(&self, s: (&Grid<D>, &[MaterialBlock]), cache: &mut WeightCache<D>) {
        let (grid, blocks) = s;
        for (b, block) in blocks.iter().enumerate() {
            if self.kernels[b].gives_run_weights() {
                let range = block.range.clone();
                cache.fill_with(grid, range, |i, out| self.stencils.real_weights(i, out));
            }
        }
    }

    /// Derivatives of the transfer `t` (algorithm 9), in parallel by slabs of node rows,
    /// each slab's points in index order (module `slabs`: the same sums on any number of
    /// threads).
    fn map(&mut self, s: &Solver<D>, t: Transfer) {
        if t.mass {
            self.nodes.clear();
            self.nodes.resize(s.grid.nodes.len(), Node::zero());
            let stride = s.grid.strides[D - 1];
            let rows = (s.grid.dims[D - 1], self.stencils.support());
            let stencils = &self.stencils;
            (self.slabs).bucket(s.particles.len(), rows, |i| stencils.lowest(i) / stride);
        }
        for n in &mut self.nodes {
            if t.momentum {
                n.momentum = SVector::zeros();
            }
            if t.force {
                n.force = SVector::zeros();
            }
        }
        let mut nodes = std::mem::take(&mut self.nodes);
        for colour in 0..2 {
            let parts = self.slabs.parts(&mut nodes, colour, s.grid.strides[D - 1]);
            parallel::for_each(
                parts.into_par_iter(),
                parallel::MATERIAL,
                |(k, start, nodes)| {
                    for &i in self.slabs.points(k) {
                        let i = i as usize;
                        let share = match t.force {
                            true => self.share(s, i),
                            false => PointShare::without_forces(
                                s.particles.mass[i],
                                &self.velocity(s, i),
                            ),
                        };
                        let (node, n, grad) = self.stencils.of(i);
                        for k in 0..node.len() {
                            let node_k = &mut nodes[node[k] as usize - start];
                            share.add_derivatives_to(node_k, t, &n[k], &grad[k]);
                        }
                    }
                },
            );
        }
        self.nodes = nodes;
    }

    /// What point `i` brings to the nodes, with its derivatives.
    fn share(&self, s: &Solver<D>, i: usize) -> PointShare<D, Dual<P>> {
        let p = &s.particles;
        let x = self.position(s, i);
        let mut external = (s.scratch.force[i] + s.settings.body_force * p.mass[i]).map(c);
        if let Some(k) = self.condition_stiffness.get(i) {
            external += k.map(c) * self.position[i].map(|x| Dual::new(0.0, x.eps));
        }
        PointShare::new(
            p.mass[i],
            &self.velocity(s, i),
            external,
            (&self.stress(s, i), self.volume(s, i), &x),
            s.settings.kinematics,
        )
    }

    /// Derivatives of the grid solve (algorithm 10) and the velocity conditions.
    fn solve(&mut self, s: &Solver<D>, update: NodalUpdate) {
        let (time, dt) = (s.time, s.dt);
        let damping = s.settings.damping;
        let solve = NodeSolve::new(&s.velocity_bcs, (time, dt), damping, s.mass_cutoff, update);
        let mut work = (0.0, 0.0, 0.0);
        for (index, (node, real)) in self.nodes.iter_mut().zip(&s.grid.nodes).enumerate() {
            if real.mass <= 0.0 {
                node.velocity = SVector::zeros();
                node.acceleration = SVector::zeros();
                continue;
            }
            node.mass = join(real.mass, node.mass);
            node.heaviest = real.heaviest;
            node.momentum = join_all(&real.momentum, &node.momentum);
            node.force = join_all(&real.force, &node.force);
            let v_old = solve.solve(node, &mut work);
            if !s.velocity_bcs.is_empty() {
                let x = s.grid.node_position(index);
                solve.constrain(node, &x, &s.grid.spacing, &v_old, &mut work);
            }
        }
    }

    /// Derivatives of the grid-to-particle transfer (algorithms 11-12): v and ṽ with
    /// `MOTION`, F, σ, V and history with `DEFORMATION`, point by point in parallel, after
    /// the transfer itself: the nodes are as it read them, the real F and history before
    /// it are kept (`keep_before_update`), and the material's update takes the return the
    /// run solved (`SeededModel::update`). (Constants, so that the interpolation forms
    /// only what the transfer reads.)
    fn gather<const MOTION: bool, const DEFORMATION: bool>(
        &mut self,
        s: &Solver<D>,
    ) -> Result<(), SimulationError> {
        let cell = s.grid.min_spacing();
        let updates: Vec<Deformation<'_>> = (s.blocks.iter())
            .map(|b| Deformation::of(&*b.material, &s.settings, cell, s.dt))
            .collect();
        let Tangent {
            models,
            position,
            velocity,
            grid_velocity,
            deformation: f,
            stress,
            volume,
            state,
            before_update: (f_before, state_before),
            nodes,
            stencils,
            ..
        } = self;
        let dt = s.dt;
        let points = (
            velocity.par_iter_mut(),
            grid_velocity.par_iter_mut(),
            f.par_iter_mut(),
            stress.par_iter_mut(),
            volume.par_iter_mut(),
            state.par_iter_mut(),
        );
        let failure =
            points
                .into_par_iter()
                .enumerate()
                .map(|(i, (v, vg, f, sigma, vol, st))| -> Failure {
                    let x = join_all(&s.particles.position[i], &position[i]);
                    let (v_grid, a, l) = interpolate(nodes, stencils.of(i));
                    if MOTION {
                        *v = join_all(&s.particles.velocity[i], v) + a.map(|a| a * dt);
                        let beta = s.settings.pic_fraction;
                        if beta > 0.0 {
                            *v = v.map(|v| v * (1.0 - beta)) + v_grid.map(|v| v * beta);
                        }
                        *vg = v_grid;
                    }
                    if !DEFORMATION {
                        return None;
                    }
                    let b = s
                        .blocks
                        .iter()
                        .position(|b| b.range.contains(&i))
                        .expect("every point has a block");
                    let block = &s.blocks[b];
                    let (l3, f_new) = s.settings.kinematics.deformation(
                        &l,
                        &v_grid,
                        (&x, &s.particles.reference_position[i]),
                        &join_all(&f_before[i], f),
                        s.dt,
                    );
                    let old = join_state(&state_before[i], st);
                    let real = &block.state[i - block.range.start];
                    let kept = s.scratch.kept.get(i).and_then(Option::as_ref);
                    let (sigma_new, state_new) =
                        match models[b].update(&f_new, s.dt, &old, (real, kept)) {
                            Ok(new) => new,
                            Err(e) => return Some((i, Box::new(Cause::Material(e)))),
                        };
                    if !finite_derivatives(&sigma_new, &state_new) {
                        let what = "derivative of the material update (σ or history)";
                        return Some((i, Box::new(Cause::NonFinite { what })));
                    }
                    // a plane model's F keeps the z axis
                    let j = match D {
                        2 => det_in::<true, _>(&f_new),
                        _ => det(&f_new),
                    };
                    let sigma_new = updates[b].with_viscosity(sigma_new, &l3, j);
                    *vol = j * s.particles.volume0[i];
                    keep_derivatives(sigma, &sigma_new);
                    keep_derivatives(f, &f_new);
                    keep_derivatives(&mut st.fp_inv, &state_new.fp_inv);
                    st.alpha = state_new.alpha;
                    st.theta = state_new.theta;
                    st.dalpha = state_new.dalpha;
                    None
                });
        match failure.reduce(|| None, earlier) {
            Some((i, cause)) => Err(SimulationError {
                step: s.step,
                time: s.time,
                particle: Some(i),
                cause: *cause,
            }),
            None => Ok(()),
        }
    }

    /// Derivative of x ← x + ṽ Δt.
    fn advect(&mut self, s: &Solver<D>) {
        let dt = c::<Dual<P>>(s.dt);
        for (x, vg) in self.position.iter_mut().zip(&self.grid_velocity) {
            *x += vg * dt;
        }
    }
}

impl<const D: usize> Solver<D> {
    /// `step`, carrying the derivatives of `tangent` along; the stress update keeps its
    /// returns for the pass to differentiate.
    pub fn step_with<const P: usize>(
        &mut self,
        tangent: &mut Tangent<D, P>,
    ) -> Result<(), SimulationError> {
        self.scratch.keep_returns = true;
        for &stage in self.settings.scheme.stages() {
            tangent.before(stage, self)?;
            match stage {
                // the pass's weights' real parts are the run's (module `stencil`)
                Stage::FitGrid => {
                    self.fit_grid_to_points()?;
                    tangent.evaluate_weights(self);
                    tangent.give_weights((&self.grid, &self.blocks), &mut self.scratch.weights);
                    self.evaluate_weights(|b| !tangent.kernels[b].gives_run_weights());
                }
                _ => self.run_stage(stage)?,
            }
            tangent.after(stage, self)?;
        }
        Ok(())
    }
}
