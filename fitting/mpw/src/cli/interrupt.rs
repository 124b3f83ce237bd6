//! Ctrl-C, SIGTERM and SIGHUP: the first sets a flag that a long command polls so that it
//! stops at its next step and still writes what it has (a simulation its last state and
//! chart, a fit its partial report; a series of runs stops with the run under way); the
//! second ends the process at once (exit 130).

use anyhow::{Context, Result};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The process's flag, its handler installed on the first call; true after the first signal.
pub fn interrupt_flag() -> Result<Arc<AtomicBool>> {
    if let Some(flag) = FLAG.get() {
        return Ok(flag.clone());
    }
    let flag = Arc::new(AtomicBool::new(false));
    let set = flag.clone();
    ctrlc::set_handler(move || {
        if set.swap(true, Ordering::Relaxed) {
            eprintln!("\nsecond interrupt: quitting without writing");
            std::process::exit(130);
        }
        eprintln!("\ninterrupt: stopping at the next step and writing what there is (again to quit at once)");
    })
    .context("installing the Ctrl-C handler")?;
    Ok(FLAG.get_or_init(|| flag).clone())
}
