//! Progress on standard error. On a terminal one line is rewritten in place (`\r`); off a
//! terminal (a log file, CI) each group of updates (`key`: a fit stage and start, a tenth
//! of the bootstrap samples) ends as one line with its last state, so that a log holds one
//! line per group instead of thousands of carriage returns.

use std::io::{IsTerminal, Write};
use std::sync::Mutex;

pub struct ProgressLine {
    terminal: bool,
    /// (key, text) of the last update not yet printed as a line (off a terminal).
    pending: Mutex<Option<(String, String)>>,
}

impl Default for ProgressLine {
    fn default() -> Self {
        ProgressLine {
            terminal: std::io::stderr().is_terminal(),
            pending: Mutex::new(None),
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
        if let Some((last, line)) = pending.as_ref() {
            if last != key {
                eprintln!("{line}");
            }
        }
        *pending = Some((key.to_string(), text.to_string()));
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
