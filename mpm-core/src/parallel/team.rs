//! The warm team: a run's loops handed to threads that are already awake.
//!
//! While `with_warm_pool`'s body runs, up to `workers() - 1` other threads of the current
//! rayon pool (never more busy threads than the CPUs this process may use) wait for the
//! body's loops instead of sleeping in rayon, so that handing out a loop costs a few
//! hundred ns instead of a futex wake-up. A waiting thread spins for `SPIN_FOR`, then
//! parks until the next loop or the end of the body: a run that works alone for a while
//! (writing output) or a machine busy with other work does not pay for spinning threads.
//!
//! Each of the `W` workers (the caller and its helpers) owns a `W`-th of a loop's pieces,
//! contiguous, and takes them from the front; one that is done steals from the back of
//! another's (`share`). Loops over the points are therefore cut the same way every stage
//! and step, and a point's data mostly stays in one core's cache.

use super::cpus::workers;
use super::share::Share;
use std::any::Any;
use std::cell::Cell;
use std::hint::spin_loop;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

thread_local! {
    /// The team of the `with_warm_pool` running on this thread (null outside one).
    static TEAM: Cell<*const Team> = const { Cell::new(std::ptr::null()) };
}

/// How long the caller waits for its helpers to start before it runs the body without
/// them (the pool's threads busy with other work, e.g. other models of a parallel loop).
const START_WAIT: Duration = Duration::from_millis(20);

/// How long a thread spins for work (a helper for the next loop, the caller for a piece
/// that another thread holds) before it parks or yields its CPU. A step's loops follow
/// each other within a few µs; a longer gap is the body working alone, or a thread that
/// the operating system has taken off its CPU.
const SPIN_FOR: Duration = Duration::from_micros(50);

/// Spinning rounds between two looks at the clock (and, for a helper, at rayon's queue).
const ROUNDS: u32 = 64;

/// Whether the calling thread runs inside `with_warm_pool` with its helpers started.
pub fn is_warm() -> bool {
    TEAM.with(|t| !t.get().is_null())
}

/// Run `body` with helpers from the current pool waiting for its loops (see the module
/// notes); with one worker (`workers`), outside a pool, or when the helpers do not start
/// within `START_WAIT`, `body` runs as it is.
pub fn with_warm_pool<R>(body: impl FnOnce() -> R) -> R {
    let others = workers() - 1;
    if others == 0 || rayon::current_thread_index().is_none() || is_warm() {
        return body();
    }
    let team = Team::default();
    rayon::in_place_scope(|scope| {
        for _ in 0..others {
            scope.spawn(|_| team.help(others));
        }
        if team.wait_for(others) {
            TEAM.with(|t| t.set(&team));
        } else {
            // helpers that start later (or that this thread pops at the end of the scope)
            // return at once
            team.finish();
        }
        let result = catch_unwind(AssertUnwindSafe(body));
        TEAM.with(|t| t.set(std::ptr::null()));
        team.finish();
        result.unwrap_or_else(|panic| resume_unwind(panic))
    })
}

/// `work` on every item by the warm team of this thread, if it has one (`false` if not:
/// nothing ran).
pub(super) fn run_on_team<T: Send>(items: &mut [T], work: &(dyn Fn(&mut T) + Sync)) -> bool {
    let team = TEAM.with(Cell::get);
    if team.is_null() {
        return false;
    }
    // SAFETY: TEAM is set only by `with_warm_pool`, to its team, while its body runs on
    // this thread, and cleared before the team is dropped.
    unsafe { &*team }.run(items, work);
    true
}

/// The items of a team job, reached by index from every worker.
struct Items<T>(*mut T);

// SAFETY: each index is claimed by one worker only (`Share::claim`), so no item is
// reached from two threads.
unsafe impl<T: Send> Sync for Items<T> {}

impl<T> Items<T> {
    fn at(&self, k: usize) -> *mut T {
        self.0.wrapping_add(k)
    }
}

/// The caller's and the helpers' meeting point.
#[derive(Default)]
struct Team {
    /// helpers running (a helper's worker number is its place in this count)
    started: AtomicUsize,
    /// the body has returned: helpers return
    done: AtomicBool,
    /// bumped each time a job is published
    published: AtomicUsize,
    job: Mutex<Option<Arc<Job>>>,
    /// helpers parked on `bell` (with `job`'s lock)
    parked: AtomicUsize,
    bell: Condvar,
}

/// One loop: pieces `0..count`, worker w owning the w-th contiguous share.
struct Job {
    /// the piece function, its lifetime erased: called only for pieces claimed from
    /// `shares`, all of which finish before `Team::run` (which borrows it) returns
    piece: *const (dyn Fn(usize) + Sync),
    count: usize,
    shares: Vec<Share>,
    finished: AtomicUsize,
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

// SAFETY: `piece` is `Sync` and outlives every call made through it (see `piece`).
unsafe impl Send for Job {}
unsafe impl Sync for Job {}

impl Job {
    /// Worker `w`: its own pieces from the front, then the others' from the back; a
    /// panicking piece counts as finished and its panic goes to the caller.
    fn work(&self, w: usize) {
        let workers = self.shares.len();
        for victim in (0..workers).map(|v| (w + v) % workers) {
            while let Some(k) = self.shares[victim].claim(victim != w) {
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

/// Spins in rounds of `ROUNDS`; `true` once `SPIN_FOR` has passed since `start`.
struct Patience {
    start: Instant,
    rounds: u32,
}

impl Patience {
    fn new() -> Patience {
        Patience {
            start: Instant::now(),
            rounds: 0,
        }
    }

    /// One round of waiting; whether this is a round to look around (every `ROUNDS`).
    fn round(&mut self) -> bool {
        spin_loop();
        self.rounds = self.rounds.wrapping_add(1);
        self.rounds.is_multiple_of(ROUNDS)
    }

    fn exhausted(&self) -> bool {
        self.start.elapsed() > SPIN_FOR
    }
}

impl Team {
    /// `work` on every item, by the caller (worker 0) and the helpers; returns when all
    /// have finished, re-raising a piece's panic.
    fn run<T: Send>(&self, items: &mut [T], work: &(dyn Fn(&mut T) + Sync)) {
        let count = items.len();
        let items = Items(items.as_mut_ptr());
        // SAFETY: each index below `count` is claimed once (`Share`), so each `&mut` is
        // the only reference to its item; `items` stays borrowed until all have finished.
        let piece = |k: usize| work(unsafe { &mut *items.at(k) });
        let piece: *const (dyn Fn(usize) + Sync + '_) = &piece;
        // SAFETY: only the lifetime changes; see `Job::piece` for why no call outlives it.
        let piece: *const (dyn Fn(usize) + Sync + 'static) = unsafe { std::mem::transmute(piece) };
        let workers = self.started.load(Ordering::Acquire) + 1;
        let job = Arc::new(Job {
            piece,
            count,
            shares: (0..workers)
                .map(|w| Share::new(w * count / workers, (w + 1) * count / workers))
                .collect(),
            finished: AtomicUsize::new(0),
            panic: Mutex::new(None),
        });
        self.publish(Some(job.clone()));
        job.work(0);
        let mut patience = Patience::new();
        while job.finished.load(Ordering::Acquire) < job.count {
            if patience.round() && patience.exhausted() {
                // a helper holding a piece is off its CPU: let it have this one
                std::thread::yield_now();
            }
        }
        *self.slot() = None;
        let panic = (job.panic.lock().unwrap_or_else(PoisonError::into_inner)).take();
        if let Some(panic) = panic {
            resume_unwind(panic);
        }
    }

    fn slot(&self) -> MutexGuard<'_, Option<Arc<Job>>> {
        self.job.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Hand `job` to the helpers, waking the parked ones.
    fn publish(&self, job: Option<Arc<Job>>) {
        *self.slot() = job;
        self.published.fetch_add(1, Ordering::SeqCst);
        self.ring();
    }

    /// The body has returned: every helper returns.
    fn finish(&self) {
        self.done.store(true, Ordering::SeqCst);
        self.ring();
    }

    /// Wake the parked helpers. With `park`, sequentially consistent: either the helper's
    /// `parked` increment is seen here (and the lock orders the notification after its
    /// wait began), or its look at `published` and `done` comes after this change.
    fn ring(&self) {
        if self.parked.load(Ordering::SeqCst) > 0 {
            let _slot = self.slot();
            self.bell.notify_all();
        }
    }

    /// Sleep until a job after the `seen`-th is published or the body has returned.
    fn park(&self, seen: usize) {
        let mut slot = self.slot();
        self.parked.fetch_add(1, Ordering::SeqCst);
        while self.published.load(Ordering::SeqCst) == seen && !self.done.load(Ordering::SeqCst) {
            slot = (self.bell.wait(slot)).unwrap_or_else(PoisonError::into_inner);
        }
        self.parked.fetch_sub(1, Ordering::SeqCst);
    }

    /// Wait (spinning) until `others` helpers have started, at most `START_WAIT`.
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

    /// A helper: once all helpers have started (so that none takes another one as a
    /// rayon job), run the published jobs and the pool's pending rayon jobs until the body
    /// returns, parking when no job comes for `SPIN_FOR`.
    fn help(&self, others: usize) {
        let w = self.started.fetch_add(1, Ordering::AcqRel) + 1;
        while self.started.load(Ordering::Acquire) < others && !self.done.load(Ordering::Acquire) {
            spin_loop();
        }
        let mut seen = 0;
        let mut patience = Patience::new();
        while !self.done.load(Ordering::Acquire) {
            let published = self.published.load(Ordering::Acquire);
            if published != seen {
                seen = published;
                let job = self.slot().clone();
                if let Some(job) = job {
                    job.work(w);
                }
                patience = Patience::new();
            } else if patience.round() {
                if rayon::yield_now() == Some(rayon::Yield::Executed) {
                    patience = Patience::new();
                } else if patience.exhausted() {
                    self.park(seen);
                    patience = Patience::new();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{fold, for_each, test_pool as pool, Cut};
    use super::*;
    use rayon::prelude::*;

    /// A piece that panics on a helper reaches the caller, and the pool stays usable.
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
        let cut = Cut {
            items: 10,
            split: true,
        };
        let sum = || {
            fold(
                (0..100u32).into_par_iter(),
                cut,
                0,
                |s, i| s + i,
                |s, x| s + x,
            )
        };
        assert_eq!(p.install(|| with_warm_pool(sum)), 4950);
    }

    /// Loops separated by pauses longer than `SPIN_FOR` (the helpers park between them)
    /// still run every piece, and the team is never larger than the CPUs.
    #[test]
    fn parked_helpers_wake_for_the_next_loop() {
        pool(4).install(|| {
            with_warm_pool(|| {
                assert_eq!(is_warm(), workers() > 1);
                let cut = Cut {
                    items: 3,
                    split: true,
                };
                for round in 0..20u64 {
                    std::thread::sleep(SPIN_FOR * 4);
                    let items = (0..1000u32).into_par_iter();
                    let sum = fold(
                        items,
                        cut,
                        0u64,
                        |s, i| s + u64::from(i) * round,
                        |s, x| s + x,
                    );
                    assert_eq!(sum, 499_500 * round);
                }
            })
        });
    }
}
