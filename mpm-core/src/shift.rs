//! Grid shift (section 12.2, appendix E, eq. E.8): for one step the grid origin is
//! õ = ō + (d̃_x R_x, d̃_y R_y, d̃_z R_z) with R_i uniform in [−1, 1), drawn from a seeded
//! PCG generator so that the same seed gives the same run. The displacement is always
//! applied to the initial origin ō.

use nalgebra::SVector;
use rand::Rng;
use rand::SeedableRng;
use rand_pcg::Pcg64;

#[derive(Debug, Clone)]
pub struct GridShift<const D: usize> {
    /// Amplitudes d̃_i [m].
    pub amplitude: SVector<f64, D>,
    rng: Pcg64,
}

impl<const D: usize> GridShift<D> {
    pub fn new(amplitude: SVector<f64, D>, seed: u64) -> Self {
        GridShift {
            amplitude,
            rng: Pcg64::seed_from_u64(seed),
        }
    }

    /// The origin displacement for the next step [m].
    pub fn sample(&mut self) -> SVector<f64, D> {
        SVector::from_fn(|i, _| self.amplitude[i] * self.rng.gen_range(-1.0..1.0))
    }
}
