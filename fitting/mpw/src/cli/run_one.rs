//! `mpw run-one DESCRIPTION DIR`: run one task (a run description, `runs::description`)
//! into its folder, writing its outcome and then its manifest (`runs::task::run_one`). The
//! executors start it; it may be run by hand to repeat a task.
//!
//! It installs no Ctrl-C handler: a task stopped from outside (SIGTERM from the process
//! pool or `scancel`) ends at once and leaves no manifest, so that it counts as unfinished
//! and may be started again.

use anyhow::Result;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The run description (TOML).
    pub description: PathBuf,
    /// The task folder: outcome.toml, manifest.toml and the run's output in run/.
    pub dir: PathBuf,
}

/// mpw as the manifests name it.
pub fn program() -> runs::Program<'static> {
    runs::Program {
        name: "mpw",
        version: env!("CARGO_PKG_VERSION"),
        commit: env!("MPW_COMMIT").trim_start_matches("commit "),
    }
}

pub fn run(args: Args) -> Result<()> {
    let execute =
        |d: &runs::RunDescription, dir: &std::path::Path| crate::tasks::execute(d, dir, None);
    let manifest = runs::task::run_one(program(), &args.description, &args.dir, &execute)?;
    println!(
        "{}: done in {:.3} s on {} thread(s)",
        args.dir.display(),
        manifest.wall_seconds,
        manifest.threads
    );
    Ok(())
}
