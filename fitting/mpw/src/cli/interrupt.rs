//! Ctrl-C, SIGTERM and SIGHUP: the first sets a flag that a long command polls so that it
//! stops at its next step and still writes what it has (a simulation its last state and
//! chart, a fit its partial report); the second ends the process at once (exit 130).

use anyhow::{Context, Result};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Install the handler; the returned flag turns true on the first signal.
pub fn interrupt_flag() -> Result<Arc<AtomicBool>> {
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
    Ok(flag)
}
