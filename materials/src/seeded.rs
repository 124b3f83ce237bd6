//! Models with seeded parameters for the derivative pass of an MPM run: each free
//! parameter carries a unit dual part in its own direction, and an update in dual
//! arithmetic returns σ and the new state with their total derivatives along the
//! directions, given the dual parts of F and of the old state (forward mode; the return
//! mapping differentiates by the implicit function theorem, module `plasticity`).

use crate::ad::seed_named;
pub use crate::dual::Dual;
use crate::error::MaterialError;
use crate::material::{Converged, Model, RealUpdate, State};
use crate::tensor::M3;

/// A model whose free parameters carry unit dual parts, one direction each: an update in
/// dual arithmetic gives σ and the new state with their total derivatives along the
/// directions, given the inputs' own dual parts (the derivative pass through an MPM run,
/// `mpm_core::solver::Tangent`). Object-safe, so that blocks of different models share
/// one pass.
pub trait SeededModel<const P: usize>: Send + Sync {
    /// `Model::update_from_real` in dual arithmetic: `real` is the new state the run's
    /// own update gave for the real parts of `f` and `old`, with the local problem it
    /// converged to where the run kept it (`Model::update_batch_keeping`).
    fn update(
        &self,
        f: &M3<Dual<P>>,
        dt: f64,
        old: &State<Dual<P>>,
        real: (&State<f64>, Option<&Converged>),
    ) -> Result<(M3<Dual<P>>, State<Dual<P>>), MaterialError>;
    /// The initial state with its derivatives (nonzero when e.g. θ0 is free).
    fn initial_state(&self) -> State<Dual<P>>;
    /// ρ0 with its derivatives.
    fn density(&self) -> Dual<P>;
    /// Λ + 2G with its derivatives.
    fn p_wave_modulus(&self) -> Dual<P>;
}

impl<const P: usize, M: Model<Dual<P>>> SeededModel<P> for M {
    fn update(
        &self,
        f: &M3<Dual<P>>,
        dt: f64,
        old: &State<Dual<P>>,
        (state, converged): (&State<f64>, Option<&Converged>),
    ) -> Result<(M3<Dual<P>>, State<Dual<P>>), MaterialError> {
        let in_plane = keeps_z_axis(f) && keeps_z_axis(&old.fp_inv);
        let real = RealUpdate {
            state,
            converged,
            in_plane,
        };
        Model::update_from_real(self, f, dt, old, real)
    }
    fn initial_state(&self) -> State<Dual<P>> {
        Model::initial_state(self)
    }
    fn density(&self) -> Dual<P> {
        Model::density(self)
    }
    fn p_wave_modulus(&self) -> Dual<P> {
        Model::p_wave_modulus(self)
    }
}

/// Whether `m` and its derivatives keep the z axis: xz, yz, zx and zy zero (±0). The
/// bits of those numbers ORed, sign bit dropped: a few instructions where a test of each
/// number costs the pass time.
#[inline]
fn keeps_z_axis<const P: usize>(m: &M3<Dual<P>>) -> bool {
    let mut bits = 0u64;
    for (i, j) in [(0, 2), (1, 2), (2, 0), (2, 1)] {
        let x = &m[(i, j)];
        bits |= x.re.to_bits();
        for d in x.eps.iter() {
            bits |= d.to_bits();
        }
    }
    bits << 1 == 0
}

/// `model` with parameter `free[k]` seeded in direction k; `Err` names a parameter the
/// model does not have.
pub fn seeded<M, const P: usize>(
    model: &M,
    free: &[&str; P],
) -> Result<Box<dyn SeededModel<P>>, String>
where
    M: Model<f64>,
    M::With<Dual<P>>: 'static,
{
    let names = model.param_names();
    if let Some(missing) = free.iter().find(|n| !names.contains(n)) {
        return Err(format!(
            "the model has no parameter `{missing}` (it has {})",
            names.join(", ")
        ));
    }
    Ok(seeded_where_present(model, free))
}

/// `model` with those parameters of `free` that it has seeded (`free[k]` in direction
/// k), the others constant: a body of another material in the same run (a Neo-Hooke
/// anvil under a Johnson-Cook bar) does not depend on the bar's parameters.
pub fn seeded_where_present<M, const P: usize>(
    model: &M,
    free: &[&str; P],
) -> Box<dyn SeededModel<P>>
where
    M: Model<f64>,
    M::With<Dual<P>>: 'static,
{
    Box::new(model.map_params(|name, v| seed_named::<P>(free, name, v)))
}

/// Most directions a derivative pass carries (`for_directions`).
pub const MAX_DIRECTIONS: usize = 6;

/// Work done with a number of directions fixed at compile time (`for_directions`).
pub trait ForDirections {
    type Output;
    /// Run with the `P` directions `free`.
    fn run<const P: usize>(self, free: [&str; P]) -> Self::Output;
}

/// `job` with the directions `free` as an array of their number, 1 to `MAX_DIRECTIONS`;
/// `Err` for another count.
pub fn for_directions<J: ForDirections>(free: &[&str], job: J) -> Result<J::Output, String> {
    fn array<'a, const P: usize>(free: &[&'a str]) -> [&'a str; P] {
        std::array::from_fn(|k| free[k])
    }
    Ok(match free.len() {
        1 => job.run(array::<1>(free)),
        2 => job.run(array::<2>(free)),
        3 => job.run(array::<3>(free)),
        4 => job.run(array::<4>(free)),
        5 => job.run(array::<5>(free)),
        6 => job.run(array::<6>(free)),
        n => {
            return Err(format!(
                "{n} parameters to carry derivatives along; give 1 to {MAX_DIRECTIONS}"
            ))
        }
    })
}
