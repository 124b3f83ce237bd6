//! Johnson-Cook first yield with N < 1 (infinite slope of α^N at α = 0): the local solve
//! converges for increments from 3e-4 to 0.1 in random directions, never NaN.

mod common;
use common::aisi_4340;
use materials::conformance::Rng;
use materials::{Model, ReturnMap};
use nalgebra::Matrix3;

#[test]
fn first_yield_with_n_below_one_converges_for_all_increments() {
    // AISI 4340 has N = 0.26: α^N has an infinite slope at α = 0.
    for rm in [ReturnMap::Principal, ReturnMap::Reference] {
        let mut m = aisi_4340();
        m.return_map = rm;
        let mut rng = Rng(13);
        for k in 0..60 {
            let size = 10f64.powf(-3.5 + 2.5 * (k as f64 / 59.0)); // 3e-4 .. 0.1
            let dir = rng.deformation(1.0) - Matrix3::identity();
            let f = Matrix3::identity() + dir * (size / dir.norm());
            for dt in [1e-6, 1.0] {
                let (sigma, state) = m
                    .update(&f, dt, &m.initial_state())
                    .unwrap_or_else(|e| panic!("increment {size:e}, dt {dt}: {e}"));
                assert!(sigma.iter().all(|s| s.is_finite()) && state.alpha.is_finite());
            }
        }
    }
}
