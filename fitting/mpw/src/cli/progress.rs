//! Progress on standard error. On a terminal one line is rewritten in place (`\r`); off a
//! terminal (a log file, CI) each group of updates (`key`: a fit stage and start, a tenth
//! of the bootstrap samples) ends as one line with its last state, so that a log holds one
//! line per group instead of thousands of carriage returns, plus a line at least every
//! `HEARTBEAT` while a group runs (a fit with the MPM level in the loop takes minutes).

use std::io::{IsTerminal, Write};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Off a terminal, the longest silence while a group runs.
const HEARTBEAT: Duration = Duration::from_secs(30);

pub struct ProgressLine {
    terminal: bool,
    /// (key, text) of the last update not yet printed as a line (off a terminal).
    pending: Mutex<Option<(String, String)>>,
    /// When the last line was printed (off a terminal).
    printed: Mutex<Instant>,
}

impl Default for ProgressLine {
    fn default() -> Self {
        ProgressLine {
            terminal: std::io::stderr().is_terminal(),
            pending: Mutex::new(None),
            printed: Mutex::new(Instant::now()),
        }
    }
}

impl ProgressLine {
    /// Show `text`, an update of group `key`.
    pub fn show(&self, key: &str, text: &str) {
        if self.terminal {
            eprint!("\r{text}   ");
            let _ = std::io::stderr().flush();
            return;
        }
        let mut pending = self.pending.lock().unwrap();
        let mut printed = self.printed.lock().unwrap();
        if let Some((last, line)) = pending.as_ref() {
            if last != key {
                eprintln!("{line}");
                *printed = Instant::now();
            }
        }
        if printed.elapsed() >= HEARTBEAT {
            // printed now: not again when the group ends
            eprintln!("{text}");
            *printed = Instant::now();
            *pending = None;
        } else {
            *pending = Some((key.to_string(), text.to_string()));
        }
    }

    /// End the line (terminal) or print the last group's line.
    pub fn finish(&self) {
        match self.pending.lock().unwrap().take() {
            Some((_, line)) => eprintln!("{line}"),
            None if self.terminal => eprintln!(),
            None => {}
        }
    }
}
