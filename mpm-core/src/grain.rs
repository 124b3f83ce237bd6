//! How a parallel loop is cut (issue 15), for `warm::fold`: into pieces of a fixed number
//! of items, folded in order, so that no loop's arithmetic depends on the threads.
//!
//! Handing a loop to a parked rayon worker costs its wake-up, 10-20 µs on a 2-core VM, and
//! leaves it calling `sched_yield` until it parks again; the warm team
//! (`warm::with_warm_pool`) costs a few hundred ns. The light loops (weights, transfers
//! without the material, grid solve, advection, sums: 5-50 ns per item) of a model with
//! fewer than `LIGHT_PARALLEL_FROM` points (`WARM_LIGHT_PARALLEL_FROM` in a warm pool)
//! save less than that, so they run on the calling thread; the material update (≈ 0.1-1
//! µs per point) is always split.

use crate::warm;

/// How a loop is cut: pieces of `items` items; `split`: whether its pieces may run on
/// other threads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cut {
    pub items: usize,
    pub split: bool,
}

/// Points from which a model's light loops are split across a pool that is not warm.
pub const LIGHT_PARALLEL_FROM: usize = 20_000;

/// Points from which a model's light loops are split across a warm pool.
pub const WARM_LIGHT_PARALLEL_FROM: usize = 1_000;

/// The piece of a light loop over points [points].
pub const LIGHT_PIECE: usize = 256;

/// The piece of the material update (and of the point loop of a gather): its points'
/// material updates are one batch (`Material::update_batch`). Its cost is uneven (a
/// plastic return costs 5-10 elastic updates) and clustered (the plastic zone of a Taylor
/// bar is its impact end), so a thread that is done takes the rest of another's pieces.
/// Axisymmetric Taylor bar, 2 940 points, warm pool: 884 µs per step at 1 thread, 466 µs
/// at 2 (442 µs is half); 64 and 32 points were no better within the VM's noise.
pub const MATERIAL_PIECE: usize = 128;

/// The material update's loop, over pieces of `MATERIAL_PIECE` points: a piece at a time,
/// always split.
pub const MATERIAL: Cut = Cut {
    items: 1,
    split: true,
};

impl Cut {
    /// The same loop over items that are already pieces (chunks of points, slabs, node
    /// chunks): one piece per item.
    pub fn per_item(self) -> Cut {
        Cut { items: 1, ..self }
    }
}

/// A light loop over the points of a model of `points` points, in pieces of
/// `LIGHT_PIECE`.
pub fn light(points: usize) -> Cut {
    let from = if warm::is_warm() {
        WARM_LIGHT_PARALLEL_FROM
    } else {
        LIGHT_PARALLEL_FROM
    };
    Cut {
        items: LIGHT_PIECE,
        split: points >= from,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_models_keep_a_light_loop_on_one_thread() {
        assert!(!light(2_940).split);
        assert!(!light(LIGHT_PARALLEL_FROM - 1).split);
        assert!(light(LIGHT_PARALLEL_FROM).split);
        assert_eq!(light(LIGHT_PARALLEL_FROM).items, LIGHT_PIECE);
        assert_eq!(light(LIGHT_PARALLEL_FROM).per_item().items, 1);
    }
}
