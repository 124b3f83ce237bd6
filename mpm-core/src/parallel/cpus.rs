//! How many CPUs this process may use, and so how many threads may be busy at once.

use std::num::NonZeroUsize;
use std::sync::OnceLock;

/// The CPUs this process may use: the operating system's count for it (on Linux the CPU
/// affinity mask, e.g. `taskset`, and a cgroup CPU quota, e.g. a container's or a batch
/// job's, as `std::thread::available_parallelism` reads them), and no more than
/// `SLURM_CPUS_PER_TASK` inside a Slurm job step. Read once per process; at least 1.
pub fn cpus() -> usize {
    static CPUS: OnceLock<usize> = OnceLock::new();
    *CPUS.get_or_init(|| {
        let os = std::thread::available_parallelism().map_or(1, NonZeroUsize::get);
        let slurm = std::env::var("SLURM_CPUS_PER_TASK").ok();
        within_slurm(os, slurm.as_deref())
    })
}

/// `os` CPUs, capped by a Slurm job's `SLURM_CPUS_PER_TASK` when it is a positive count.
fn within_slurm(os: usize, slurm: Option<&str>) -> usize {
    let task = slurm.and_then(|s| s.trim().parse::<usize>().ok());
    task.filter(|&n| n > 0).map_or(os, |n| n.min(os)).max(1)
}

/// The threads that may work on one loop at once: the current rayon pool's threads (the
/// global pool's outside a pool), no more than `cpus`.
pub(super) fn workers() -> usize {
    rayon::current_num_threads().min(cpus()).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slurm_task_caps_the_cpus_and_a_bad_value_is_ignored() {
        assert_eq!(within_slurm(8, None), 8);
        assert_eq!(within_slurm(8, Some("2")), 2);
        assert_eq!(within_slurm(2, Some("16")), 2);
        assert_eq!(within_slurm(4, Some("0")), 4);
        assert_eq!(within_slurm(4, Some("two")), 4);
        assert!(cpus() >= 1);
    }
}
