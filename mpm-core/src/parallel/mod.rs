//! Parallel loops whose results do not depend on the threads.
//!
//! A loop is cut into pieces of a fixed number of items (`Cut`); each piece is folded in
//! item order and the pieces' results are combined in piece order (`fold` and the helpers
//! built on it, `fixed_sum` among them). The arithmetic is therefore the same on one thread
//! or many, whichever thread takes a piece: a run gives the same bits on any thread count
//! and on any machine of the same instruction set.
//!
//! Where the pieces run:
//! - on the calling thread, when the loop is not split (`Cut::split`, see `cut` for the
//!   small-model policy) or when only one CPU or one thread is available;
//! - through rayon, in a cold pool;
//! - through the warm team of `with_warm_pool` (`team`): the pool's other threads, at most
//!   one fewer than the CPUs this process may use (`cpus`), wait for the run's loops by
//!   spinning briefly, then park, so that handing out a loop costs a few hundred ns while
//!   the loops come quickly and nothing spins while the run works alone or the machine is
//!   busy with something else.
//!
//! The only `unsafe` code of the library crates is in `team` (a piece closure shared with
//! the team's threads, items reached by index); the claim protocol it relies on (`share`)
//! is checked by the `loom` model checker (`RUSTFLAGS="--cfg loom"`).

mod cpus;
mod cut;
mod fold;
mod share;
mod team;

pub use cpus::cpus;
pub use cut::{light, Cut, LARGE_MODEL_FROM, MATERIAL, MATERIAL_PIECE};
pub use fold::{filter_map, fixed_sum, fold, for_each, map};
pub use team::{is_warm, with_warm_pool};

/// A rayon pool of `threads` threads, for the tests of every way of running.
#[cfg(test)]
fn test_pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a test pool")
}
