//! How a loop is cut, and which loops are worth splitting across threads.
//!
//! Handing a loop to a parked rayon worker costs its wake-up (a futex call, 10-20 µs on a
//! small VM); the warm team (`with_warm_pool`) costs a few hundred ns. The light loops of
//! a step (weights, transfers without the material, grid solve, advection, sums: 5-50 ns
//! per item) of a small model save less than that, so they run on the calling thread; the
//! material update (0.1-1 µs per point) is always split. This file is the one place that
//! says what a small model is.

use super::team;

/// How a loop is cut: pieces of `items` items; `split`: whether its pieces may run on
/// other threads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cut {
    pub items: usize,
    pub split: bool,
}

/// Points from which a model is large: its light loops are split across a pool that is
/// not warm, and a run among others (a fit's evaluation) is worth the caller's pool rather
/// than one thread of its own.
pub const LARGE_MODEL_FROM: usize = 20_000;

/// Points from which a model's light loops are split across a warm pool.
pub const WARM_LIGHT_PARALLEL_FROM: usize = 1_000;

/// The piece of a light loop over points [points].
pub const LIGHT_PIECE: usize = 256;

/// The piece of the material update (and of the point loop of a gather): its points'
/// material updates are one batch (`Material::update_batch`). Its cost is uneven (a
/// plastic return costs 5-10 elastic updates) and clustered (the plastic zone of a Taylor
/// bar is its impact end), so a thread that is done takes the rest of another's pieces.
/// 32, 64 and 128 points cost the same on an axisymmetric Taylor bar; 128 keeps the
/// per-piece overhead lowest (docs/performance.md).
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
    let from = if team::is_warm() {
        WARM_LIGHT_PARALLEL_FROM
    } else {
        LARGE_MODEL_FROM
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
        assert!(!light(LARGE_MODEL_FROM - 1).split);
        assert!(light(LARGE_MODEL_FROM).split);
        assert_eq!(light(LARGE_MODEL_FROM).items, LIGHT_PIECE);
        assert_eq!(light(LARGE_MODEL_FROM).per_item().items, 1);
    }
}
