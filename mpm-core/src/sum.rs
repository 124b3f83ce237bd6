//! Parallel sums whose result does not depend on the number of threads: the index range
//! is cut into fixed chunks, each chunk is summed in order, and the chunk sums are added in
//! order. (Rayon's own `sum` splits adaptively, so its rounding depends on the threads.)

use crate::grain;
use rayon::prelude::*;

const CHUNK: usize = 2048;

/// Σ_{i<n} f(i), bit-identical for any thread count.
pub fn fixed_sum<T, F>(n: usize, zero: T, f: F) -> T
where
    T: Copy + Send + Sync + std::ops::Add<Output = T>,
    F: Fn(usize) -> T + Sync,
{
    let chunks = n.div_ceil(CHUNK);
    let partial: Vec<T> = (0..chunks)
        .into_par_iter()
        .with_min_len(grain::light(n))
        .map(|c| (c * CHUNK..((c + 1) * CHUNK).min(n)).fold(zero, |s, i| s + f(i)))
        .collect();
    partial.into_iter().fold(zero, |s, x| s + x)
}
