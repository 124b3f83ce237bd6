//! Parallel loops in pieces, and a warm pool to run them (issue 15).
//!
//! `fold` cuts a loop into pieces of a fixed number of items (`grain::Cut`), folds each
//! piece in order and combines the pieces' results in order: the arithmetic is the same on
//! any number of threads, whichever thread takes a piece. The pieces run on the calling
//! thread, through rayon, or through the warm team of `with_warm_pool`.
//!
//! While `with_warm_pool`'s body runs, the other threads of the current rayon pool spin
//! for work instead of parking, so that handing out a loop costs a few hundred ns instead
//! of waking a parked thread (10-20 µs, a futex call), and no thread calls `sched_yield`
//! while it waits (system time). Each of the `W` workers (the caller and its spinners)
//! owns a `W`-th of a loop's pieces, contiguous, and takes them from the front; one that
//! is done steals from the back of another's. Loops over the points are therefore cut the
//! same way every stage and step, and a point's data mostly stays in one core's cache.
//! The warm pool pays where a step is a few hundred µs of short loops (models of a few
//! thousand points) and keeps a core busy while the body works alone (output), so a run
//! asks for it (`Solver::run_until`) rather than every step.

use crate::grain::Cut;
use rayon::iter::plumbing::{Producer, ProducerCallback};
use rayon::prelude::*;
use std::any::Any;
use std::cell::Cell;
use std::hint::spin_loop;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

thread_local! {
    /// The team of the `with_warm_pool` running on this thread (null outside one).
    static TEAM: Cell<*const Team> = const { Cell::new(std::ptr::null()) };
}

/// How long the caller waits for the spinners to start before it runs the body without
/// them (the pool's threads busy with other work, e.g. other models of a parallel loop).
const START_WAIT: Duration = Duration::from_millis(20);

/// An idle spinner looks for rayon jobs once in this many rounds, and otherwise only
/// reads `published` and pauses (`spin_loop`), leaving the core's shared resources to the
/// other thread where the two are hardware threads of one core.
const RAYON_EVERY: u32 = 64;

/// Whether the calling thread runs inside `with_warm_pool` with its spinners started.
pub fn is_warm() -> bool {
    TEAM.with(|t| !t.get().is_null())
}

/// Run `body` with the current pool's other threads spinning for work (see the module
/// notes); on a one-thread pool, outside a pool or when the spinners do not start within
/// `START_WAIT`, `body` runs as it is.
pub fn with_warm_pool<R>(body: impl FnOnce() -> R) -> R {
    let others = rayon::current_num_threads().saturating_sub(1);
    if others == 0 || rayon::current_thread_index().is_none() || is_warm() {
        return body();
    }
    let team = Team::default();
    rayon::in_place_scope(|scope| {
        for _ in 0..others {
            scope.spawn(|_| team.spin(others));
        }
        if team.wait_for(others) {
            TEAM.with(|t| t.set(&team));
        } else {
            // spinners that start later (or that this thread pops at the end of the
            // scope) return at once
            team.done.store(true, Ordering::Release);
        }
        let result = catch_unwind(AssertUnwindSafe(body));
        TEAM.with(|t| t.set(std::ptr::null()));
        team.done.store(true, Ordering::Release);
        result.unwrap_or_else(|panic| resume_unwind(panic))
    })
}

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
        let team = TEAM.with(Cell::get);
        if !self.cut.split || pieces.len() == 1 {
            pieces.iter_mut().for_each(work);
        } else if team.is_null() {
            pieces.par_iter_mut().with_max_len(1).for_each(work);
        } else {
            // SAFETY: TEAM holds the team of the enclosing `with_warm_pool` while its body
            // runs on this thread.
            unsafe { &*team }.run(&mut pieces, &work);
        }
        (pieces.into_iter())
            .map(|(_, r)| r.expect("every piece folded"))
            .collect()
    }
}

/// The items of a team job, reached by index from every worker.
struct Items<T>(*mut T);

// SAFETY: the team hands each index to one worker only (`Job`).
unsafe impl<T: Send> Sync for Items<T> {}

impl<T> Items<T> {
    fn at(&self, k: usize) -> *mut T {
        self.0.wrapping_add(k)
    }
}

/// The caller's and the spinners' meeting point.
#[derive(Default)]
struct Team {
    /// spinners running (a spinner's worker number is its place in this count)
    started: AtomicUsize,
    /// the body has returned: spinners return
    done: AtomicBool,
    /// bumped each time a job is published
    published: AtomicUsize,
    job: Mutex<Option<Arc<Job>>>,
}

/// One loop: pieces `0..count`, worker w owning the w-th contiguous share.
struct Job {
    /// the piece function, its lifetime erased: called only for pieces claimed from
    /// `shares`, all of which finish before `Team::run` (which borrows it) returns
    piece: *const (dyn Fn(usize) + Sync),
    count: usize,
    /// each worker's unclaimed pieces, front and back packed (`span`)
    shares: Vec<Share>,
    finished: AtomicUsize,
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

// SAFETY: `piece` is `Sync` and outlives every call made through it (see `piece`).
unsafe impl Send for Job {}
unsafe impl Sync for Job {}

/// A worker's unclaimed pieces, on a cache line of its own (128 bytes: two 64-byte lines
/// where the prefetcher fetches pairs), so that claims by different workers do not
/// contend.
#[repr(align(128))]
struct Share(AtomicU64);

/// Pieces `front..back` packed in a u64.
fn span(front: usize, back: usize) -> u64 {
    ((front as u64) << 32) | back as u64
}

/// Claim a piece of `share`: its front (`from_back` false) or its back.
fn claim(share: &AtomicU64, from_back: bool) -> Option<usize> {
    let mut now = share.load(Ordering::Acquire);
    loop {
        let (front, back) = ((now >> 32) as usize, (now & 0xffff_ffff) as usize);
        if front >= back {
            return None;
        }
        let (next, k) = if from_back {
            (span(front, back - 1), back - 1)
        } else {
            (span(front + 1, back), front)
        };
        match share.compare_exchange_weak(now, next, Ordering::AcqRel, Ordering::Acquire) {
            Ok(_) => return Some(k),
            Err(seen) => now = seen,
        }
    }
}

impl Job {
    /// Worker `w`: its own pieces from the front, then the others' from the back; a
    /// panicking piece counts as finished and its panic goes to the caller.
    fn work(&self, w: usize) {
        let workers = self.shares.len();
        for victim in (0..workers).map(|v| (w + v) % workers) {
            while let Some(k) = claim(&self.shares[victim].0, victim != w) {
                // SAFETY: piece k was claimed by this worker alone, and `Team::run` does
                // not return while a claimed piece is unfinished.
                let run = catch_unwind(AssertUnwindSafe(|| unsafe { (*self.piece)(k) }));
                if let Err(panic) = run {
                    let mut first = self.panic.lock().unwrap_or_else(PoisonError::into_inner);
                    first.get_or_insert(panic);
                }
                self.finished.fetch_add(1, Ordering::Release);
            }
        }
    }
}

impl Team {
    /// `work` on every item, by the caller (worker 0) and the spinners; returns when all
    /// have finished (waiting by spinning), re-raising a piece's panic.
    fn run<T: Send>(&self, items: &mut [T], work: &(dyn Fn(&mut T) + Sync)) {
        let count = items.len();
        let items = Items(items.as_mut_ptr());
        // SAFETY: each index below `count` is claimed once (`Job`), so each `&mut` is the
        // only reference to its item; `items` stays borrowed until all have finished.
        let piece = |k: usize| work(unsafe { &mut *items.at(k) });
        let piece: *const (dyn Fn(usize) + Sync + '_) = &piece;
        // SAFETY: only the lifetime changes; see `Job::piece` for why no call outlives it.
        let piece: *const (dyn Fn(usize) + Sync + 'static) = unsafe { std::mem::transmute(piece) };
        let workers = self.started.load(Ordering::Acquire) + 1;
        let job = Arc::new(Job {
            piece,
            count,
            shares: (0..workers)
                .map(|w| span(w * count / workers, (w + 1) * count / workers))
                .map(|s| Share(AtomicU64::new(s)))
                .collect(),
            finished: AtomicUsize::new(0),
            panic: Mutex::new(None),
        });
        *self.slot() = Some(job.clone());
        self.published.fetch_add(1, Ordering::Release);
        job.work(0);
        while job.finished.load(Ordering::Acquire) < job.count {
            spin_loop();
        }
        *self.slot() = None;
        let panic = job
            .panic
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take();
        if let Some(panic) = panic {
            resume_unwind(panic);
        }
    }

    fn slot(&self) -> MutexGuard<'_, Option<Arc<Job>>> {
        self.job.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Wait (spinning) until `others` spinners have started, at most `START_WAIT`.
    fn wait_for(&self, others: usize) -> bool {
        let since = Instant::now();
        while self.started.load(Ordering::Acquire) < others {
            if since.elapsed() > START_WAIT {
                return false;
            }
            spin_loop();
        }
        true
    }

    /// A spinner: once all spinners have started (so that none takes another one as a
    /// rayon job), run the published jobs and the pool's pending rayon jobs until `done`.
    fn spin(&self, others: usize) {
        let w = self.started.fetch_add(1, Ordering::AcqRel) + 1;
        while self.started.load(Ordering::Acquire) < others && !self.done.load(Ordering::Acquire) {
            spin_loop();
        }
        let (mut seen, mut idle) = (0, 0u32);
        while !self.done.load(Ordering::Acquire) {
            let published = self.published.load(Ordering::Acquire);
            if published != seen {
                seen = published;
                let job = self.slot().clone();
                if let Some(job) = job {
                    job.work(w);
                }
                idle = 0;
            } else if idle % RAYON_EVERY == 0 && rayon::yield_now() == Some(rayon::Yield::Executed)
            {
                idle = 0;
            } else {
                idle = idle.wrapping_add(1);
                spin_loop();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    }

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
            let (cold, warm) = pool(threads).install(|| {
                let cold = sum(true);
                let warm = with_warm_pool(|| {
                    assert_eq!(is_warm(), threads > 1);
                    sum(true)
                });
                (cold, warm)
            });
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

    /// A piece that panics on a spinner reaches the caller, and the pool stays usable.
    #[test]
    fn a_panicking_piece_reaches_the_caller() {
        let p = pool(2);
        let caught = p.install(|| {
            with_warm_pool(|| {
                catch_unwind(AssertUnwindSafe(|| {
                    let cut = Cut {
                        items: 1,
                        split: true,
                    };
                    for_each((0..64usize).into_par_iter(), cut, |i| {
                        assert!(i != 63, "piece 63");
                    })
                }))
            })
        });
        assert!(caught.is_err());
        let total = p.install(|| {
            let cut = Cut {
                items: 10,
                split: true,
            };
            with_warm_pool(|| {
                fold(
                    (0..100u32).into_par_iter(),
                    cut,
                    0,
                    |s, i| s + i,
                    |s, x| s + x,
                )
            })
        });
        assert_eq!(total, 4950);
    }
}
