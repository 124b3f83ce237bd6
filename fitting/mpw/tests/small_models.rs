//! Small models: every `mpw` command now runs on a worker of one thread pool;
//! its results must not depend on the thread count, and the small-model bench cases
//! (one Taylor bar alone, one per thread at once) must run to their rows.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn mpw(threads: usize, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mpw"))
        .current_dir(root())
        .env("RAYON_NUM_THREADS", threads.to_string())
        .args(args)
        .output()
        .unwrap()
}

/// The colliding disks (plane strain, two bodies, contact through the grid) give
/// byte-identical results and history with 1, 2 and 4 threads.
#[test]
fn simulate_gives_the_same_numbers_on_any_thread_count() {
    let dir = std::env::temp_dir().join(format!("mpw-small-{}", std::process::id()));
    let run = |threads: usize| {
        let out = dir.join(format!("t{threads}"));
        let done = mpw(
            threads,
            &[
                "simulate",
                "data/scenes/colliding_disks.toml",
                "--out",
                out.to_str().unwrap(),
            ],
        );
        assert!(
            done.status.success(),
            "{}",
            String::from_utf8_lossy(&done.stderr)
        );
        let read = |f: &str| std::fs::read_to_string(out.join(f)).unwrap();
        (read("results.csv"), read("history.csv"))
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(4));
}

/// `mpw bench-mpm --cases c,n` prints the Taylor bar alone at 1 and 2 threads and two
/// bars at once, with their system time.
#[test]
fn small_model_bench_cases_run() {
    let done = mpw(
        2,
        &[
            "bench-mpm",
            "--cases",
            "c,n",
            "--steps",
            "1",
            "--warm-up",
            "1",
        ],
    );
    let text = String::from_utf8_lossy(&done.stdout);
    assert!(
        done.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&done.stderr)
    );
    assert_eq!(
        text.matches("(c) axisymmetric Taylor bar").count(),
        2,
        "{text}"
    );
    assert!(text.contains("(n) 2 Taylor bars at once"), "{text}");
}
