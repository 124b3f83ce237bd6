//! Loops in fixed pieces: `fold` and the loops built on it.
//!
//! Invariant: a loop's result depends only on its items and its `Cut`, never on where its
//! pieces ran (the calling thread, rayon or the warm team) nor on the thread count.

use super::{cpus, team, Cut};
use rayon::iter::plumbing::{Producer, ProducerCallback};
use rayon::prelude::*;

/// The piece of `fixed_sum`.
const SUM_PIECE: usize = 2048;

/// `f` on every item of `iter`, cut as `cut` says.
pub fn for_each<I>(iter: I, cut: Cut, f: impl Fn(I::Item) + Sync)
where
    I: IndexedParallelIterator,
{
    fold(iter, cut, (), |(), item| f(item), |(), ()| ());
}

/// `f`'s values, in item order.
pub fn map<I, T>(iter: I, cut: Cut, f: impl Fn(I::Item) -> T + Sync) -> Vec<T>
where
    I: IndexedParallelIterator,
    T: Clone + Send + Sync,
{
    filter_map(iter, cut, |item| Some(f(item)))
}

/// `f`'s values that are not `None`, in item order.
pub fn filter_map<I, T>(iter: I, cut: Cut, f: impl Fn(I::Item) -> Option<T> + Sync) -> Vec<T>
where
    I: IndexedParallelIterator,
    T: Clone + Send + Sync,
{
    let push = |mut kept: Vec<T>, item| {
        kept.extend(f(item));
        kept
    };
    fold(iter, cut, Vec::new(), push, |mut kept, more| {
        kept.extend(more);
        kept
    })
}

/// Σ_{i<n} f(i) over a model of `n` points, in pieces of `SUM_PIECE` (rayon's own `sum`
/// splits adaptively, so its rounding would depend on the threads).
pub fn fixed_sum<T, F>(n: usize, zero: T, f: F) -> T
where
    T: Copy + Send + Sync + std::ops::Add<Output = T>,
    F: Fn(usize) -> T + Sync,
{
    let cut = Cut {
        items: SUM_PIECE,
        ..super::light(n)
    };
    fold(
        (0..n).into_par_iter(),
        cut,
        zero,
        |s, i| s + f(i),
        |s, x| s + x,
    )
}

/// The items of `iter` folded piece by piece from `init` (`fold`, in item order), the
/// pieces' results then combined in piece order from `init` (`combine`).
pub fn fold<I, R, F>(iter: I, cut: Cut, init: R, fold: F, combine: impl FnMut(R, R) -> R) -> R
where
    I: IndexedParallelIterator,
    R: Clone + Send + Sync,
    F: Fn(R, I::Item) -> R + Sync,
{
    let len = iter.len();
    let parts = iter.with_producer(Cutter {
        len,
        cut,
        init: &init,
        fold: &fold,
    });
    parts.into_iter().fold(init, combine)
}

/// Cuts a producer into pieces and folds them (the callback of `with_producer`).
struct Cutter<'a, R, F> {
    len: usize,
    cut: Cut,
    init: &'a R,
    fold: &'a F,
}

impl<T, R, F> ProducerCallback<T> for Cutter<'_, R, F>
where
    R: Clone + Send + Sync,
    F: Fn(R, T) -> R + Sync,
{
    type Output = Vec<R>;

    fn callback<P: Producer<Item = T>>(self, producer: P) -> Vec<R> {
        let size = self.cut.items.max(1);
        let mut pieces: Vec<(Option<P>, Option<R>)> = Vec::with_capacity(self.len / size + 1);
        let (mut rest, mut left) = (producer, self.len);
        while left > size {
            let (piece, tail) = rest.split_at(size);
            pieces.push((Some(piece), None));
            (rest, left) = (tail, left - size);
        }
        pieces.push((Some(rest), None));
        let work = |(piece, result): &mut (Option<P>, Option<R>)| {
            let items = piece.take().expect("each piece is folded once").into_iter();
            *result = Some(items.fold(self.init.clone(), self.fold));
        };
        if !self.cut.split || pieces.len() == 1 || cpus::workers() == 1 {
            pieces.iter_mut().for_each(work);
        } else if !team::run_on_team(&mut pieces, &work) {
            pieces.par_iter_mut().with_max_len(1).for_each(work);
        }
        (pieces.into_iter())
            .map(|(_, r)| r.expect("every piece folded"))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::{test_pool as pool, with_warm_pool};
    use super::*;

    /// A sum whose rounding shows the order of its terms: the same bits on the calling
    /// thread, through rayon and through the warm team, on 1-4 threads.
    #[test]
    fn a_fold_does_not_depend_on_where_its_pieces_run() {
        let x: Vec<f64> = (0..10_007).map(|i| 1.0 / (1.0 + i as f64).sqrt()).collect();
        let sum = |split| {
            let cut = Cut { items: 97, split };
            fold(x.par_iter(), cut, 0.0, |s, v| s + v, |s, v| s + v)
        };
        let alone = sum(false);
        let serial = (x.chunks(97))
            .map(|c| c.iter().fold(0.0, |s, v| s + v))
            .fold(0.0, |s, v| s + v);
        assert_eq!(alone.to_bits(), serial.to_bits());
        for threads in 1..=4 {
            let (cold, warm) = pool(threads).install(|| (sum(true), with_warm_pool(|| sum(true))));
            assert_eq!(cold.to_bits(), alone.to_bits(), "{threads} threads");
            assert_eq!(warm.to_bits(), alone.to_bits(), "{threads} threads, warm");
        }
    }

    /// Every item is visited once, mutably, in every way of running; `filter_map` keeps
    /// the item order.
    #[test]
    fn every_item_once_and_in_order() {
        for threads in [1, 2, 3] {
            pool(threads).install(|| {
                with_warm_pool(|| {
                    let mut seen = vec![0u32; 1000];
                    let cut = Cut {
                        items: 7,
                        split: true,
                    };
                    for_each(seen.par_iter_mut(), cut, |n| *n += 1);
                    assert!(seen.iter().all(|&n| n == 1));
                    let odd = filter_map((0..1000usize).into_par_iter(), cut, |i| {
                        (i % 2 == 1).then_some(i)
                    });
                    assert_eq!(odd, (1..1000).step_by(2).collect::<Vec<_>>());
                })
            });
        }
    }
}
