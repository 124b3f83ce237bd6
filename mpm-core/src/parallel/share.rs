//! A worker's share of a team job: the pieces it has not claimed yet, `front..back`,
//! packed in one atomic u64 so that a claim is one compare-and-swap.
//!
//! Invariant: every piece index in the initial range is returned by exactly one `claim`,
//! whichever workers claim from which end and however their claims interleave; once
//! `front >= back` no claim succeeds. The owner claims from the front, thieves from the
//! back. Checked by the `loom` model checker: the owner and a thief under every
//! interleaving, the owner and two thieves with up to two preemptions (`RUSTFLAGS="--cfg
//! loom" cargo test -p mpm-core --lib parallel::share`, run by `.ci/run`).

#[cfg(loom)]
use loom::sync::atomic::{AtomicU64, Ordering};
#[cfg(not(loom))]
use std::sync::atomic::{AtomicU64, Ordering};

/// A worker's unclaimed pieces, on a cache line of its own (128 bytes: two 64-byte lines
/// where the prefetcher fetches pairs), so that claims by different workers do not
/// contend.
#[repr(align(128))]
pub(super) struct Share(AtomicU64);

impl Share {
    /// Pieces `front..back` (each below 2^32).
    pub(super) fn new(front: usize, back: usize) -> Share {
        debug_assert!(front <= back && back <= u32::MAX as usize);
        Share(AtomicU64::new(pack(front, back)))
    }

    /// Claim one unclaimed piece: the front one (`from_back` false) or the back one;
    /// `None` when none is left.
    pub(super) fn claim(&self, from_back: bool) -> Option<usize> {
        let mut now = self.0.load(Ordering::Acquire);
        loop {
            let (front, back) = ((now >> 32) as usize, (now & 0xffff_ffff) as usize);
            if front >= back {
                return None;
            }
            let (next, k) = if from_back {
                (pack(front, back - 1), back - 1)
            } else {
                (pack(front + 1, back), front)
            };
            match (self.0).compare_exchange_weak(now, next, Ordering::AcqRel, Ordering::Acquire) {
                Ok(_) => return Some(k),
                Err(seen) => now = seen,
            }
        }
    }
}

/// `front..back` as one u64: front in the high half.
fn pack(front: usize, back: usize) -> u64 {
    ((front as u64) << 32) | back as u64
}

#[cfg(all(test, not(loom)))]
mod tests {
    use super::*;

    #[test]
    fn front_and_back_meet_without_a_gap_or_a_repeat() {
        let share = Share::new(3, 8);
        let mut got = vec![];
        while let Some(k) = share.claim(got.len() % 2 == 1) {
            got.push(k);
        }
        assert_eq!(got, [3, 7, 4, 6, 5]);
        assert_eq!(share.claim(false), None);
        assert_eq!(Share::new(5, 5).claim(true), None);
    }
}

#[cfg(all(test, loom))]
mod loom_tests {
    use super::*;
    use loom::sync::Arc;

    /// `thieves` threads take from the back while the owner takes from the front; every
    /// piece of `0..pieces` is taken exactly once.
    fn claimed_once(pieces: usize, thieves: usize) {
        let share = Arc::new(Share::new(0, pieces));
        let handles: Vec<_> = (0..thieves)
            .map(|_| {
                let share = share.clone();
                loom::thread::spawn(move || {
                    let mut got = vec![];
                    while let Some(k) = share.claim(true) {
                        got.push(k);
                    }
                    got
                })
            })
            .collect();
        let mut all = vec![];
        while let Some(k) = share.claim(false) {
            all.push(k);
        }
        for h in handles {
            all.extend(h.join().unwrap());
        }
        all.sort_unstable();
        assert_eq!(all, (0..pieces).collect::<Vec<_>>());
    }

    /// The owner and a thief meeting in the middle, under every interleaving.
    #[test]
    fn owner_and_thief_claim_every_piece_once() {
        loom::model(|| claimed_once(3, 1));
    }

    /// The owner and two thieves, with up to two preemptions per execution.
    #[test]
    fn owner_and_two_thieves_claim_every_piece_once() {
        let mut model = loom::model::Builder::new();
        model.preemption_bound = Some(2);
        model.check(|| claimed_once(2, 2));
    }
}
