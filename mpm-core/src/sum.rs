//! Parallel sums whose result does not depend on the number of threads: the index range
//! is cut into fixed chunks, each chunk is summed in order, and the chunk sums are added in
//! order. (Rayon's own `sum` splits adaptively, so its rounding depends on the threads.)

use crate::grain::{self, Cut};
use crate::warm;
use rayon::prelude::*;

const CHUNK: usize = 2048;

/// Σ_{i<n} f(i), bit-identical for any thread count.
pub fn fixed_sum<T, F>(n: usize, zero: T, f: F) -> T
where
    T: Copy + Send + Sync + std::ops::Add<Output = T>,
    F: Fn(usize) -> T + Sync,
{
    let cut = Cut {
        items: CHUNK,
        ..grain::light(n)
    };
    let range = (0..n).into_par_iter();
    warm::fold(range, cut, zero, |s, i| s + f(i), |s, x| s + x)
}
