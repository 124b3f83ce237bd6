//! How finely a parallel loop is cut (issue 15). A fork-join costs the wake-up of an idle
//! worker, 10-20 µs on a 2-core VM, and leaves it spinning in `sched_yield` until it
//! sleeps again. The light loops (weights, transfers without the material, grid solve,
//! advection, sums: 5-50 ns per item) of a model with fewer than `LIGHT_PARALLEL_FROM`
//! points save less than that, so they run whole on the calling thread; the material
//! update (≈ 0.1-1 µs per point) is always split, in pieces of at most `MATERIAL_PIECE`
//! points. Either way the results are the same to the bit: no loop's arithmetic depends on
//! how it is cut.

/// Points from which a model's light loops are split across the pool.
pub const LIGHT_PARALLEL_FROM: usize = 20_000;

/// The piece of the material update (and of the point loop of a gather): its points'
/// material updates are one batch (`Material::update_batch`). Its cost is uneven (a plastic return costs
/// 5-10 elastic updates) and clustered (the plastic zone of a Taylor bar is its impact
/// end), so the few large pieces of rayon's adaptive split leave one thread with most of
/// the plastic points; pieces of 128 points (8-90 µs) let an idle thread steal the rest.
/// Axisymmetric Taylor bar, 2 940 points, 2 threads: material stage 724 → 656 µs per step
/// (597 µs is half the 1-thread time); 512 points gave 677 µs, 32 points 656 µs.
pub const MATERIAL_PIECE: usize = 128;

/// The least piece (`with_min_len`) of a light loop in a model of `points` points: the
/// whole loop (`usize::MAX`: never split) below `LIGHT_PARALLEL_FROM`, else rayon's
/// adaptive split.
pub fn light(points: usize) -> usize {
    if points < LIGHT_PARALLEL_FROM {
        usize::MAX
    } else {
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_models_keep_a_light_loop_whole() {
        assert_eq!(light(2_940), usize::MAX);
        assert_eq!(light(LIGHT_PARALLEL_FROM - 1), usize::MAX);
        assert_eq!(light(LIGHT_PARALLEL_FROM), 1);
    }
}
