//! One module per `mpw` subcommand: its clap `Args` and its `run`.

pub mod bench;
pub mod bench_derivatives;
pub mod bench_mpm;
pub mod bench_runs;
pub mod bench_small;
pub mod cut;
pub mod design;
pub mod drive;
pub mod executor_args;
pub mod export;
pub mod fit;
pub mod fit_choice;
pub mod interrupt;
pub mod kernels;
pub mod predict;
pub mod progress;
pub mod run_one;
pub mod shpb;
pub mod simulate;
pub mod simulate_shpb;
pub mod simulate_shpb_derivatives;
pub mod sweep;
pub mod synth;
pub mod verify;
