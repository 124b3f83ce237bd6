//! One row of the `mpw verify` table: a verification case with its measured value,
//! reference value, tolerance and verdict. Every part of the catalogue (materials, SHPB,
//! fitting, MPM) contributes its own rows. A row's name says which case it is, never what
//! was measured (that goes in its `note`), so that two builds' tables compare row by row.

use std::fmt;

/// A row's verdict: asserted (pass or fail) or reported only.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    Pass,
    Fail,
    /// Reported only: a known gap, or a value without a reference.
    Info,
}

impl Verdict {
    fn asserted(ok: bool) -> Verdict {
        if ok {
            Verdict::Pass
        } else {
            Verdict::Fail
        }
    }
}

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Row {
    /// Case name, e.g. `j2/tangent-vs-fd`.
    pub name: String,
    pub measured: f64,
    pub reference: f64,
    /// What `measured` is compared with `reference` by, in words (e.g. `rel 1e-6`).
    pub tolerance: String,
    pub verdict: Verdict,
    /// What else the case measured, in words (e.g. "slip 0.116 m"); empty if nothing.
    pub note: String,
}

/// A tolerance in the fewest significant digits (one to three) that still show its value
/// to 1 %: 1e-9, 2.5e-3, 1.6e-2, 1.27e-2.
fn short(tol: f64) -> String {
    (0..3)
        .map(|digits| format!("{tol:.digits$e}"))
        .find(|text| {
            text.parse::<f64>()
                .is_ok_and(|v| (v - tol).abs() <= 0.01 * tol.abs())
        })
        .unwrap_or_else(|| format!("{tol:.2e}"))
}

impl Row {
    /// Pass if |measured − reference| ≤ tol · |reference|.
    pub fn relative(name: impl Into<String>, measured: f64, reference: f64, tol: f64) -> Self {
        let passed = (measured - reference).abs() <= tol * reference.abs() && measured.is_finite();
        Row {
            name: name.into(),
            measured,
            reference,
            tolerance: format!("rel {}", short(tol)),
            verdict: Verdict::asserted(passed),
            note: String::new(),
        }
    }

    /// Pass if |measured − reference| ≤ tol.
    pub fn absolute(name: impl Into<String>, measured: f64, reference: f64, tol: f64) -> Self {
        let passed = (measured - reference).abs() <= tol && measured.is_finite();
        Row {
            name: name.into(),
            measured,
            reference,
            tolerance: format!("abs {}", short(tol)),
            verdict: Verdict::asserted(passed),
            note: String::new(),
        }
    }

    /// Pass if measured ≤ bound (an error measure against zero).
    pub fn at_most(name: impl Into<String>, measured: f64, bound: f64) -> Self {
        let passed = measured <= bound && measured.is_finite();
        Row {
            name: name.into(),
            measured,
            reference: 0.0,
            tolerance: format!("<= {}", short(bound)),
            verdict: Verdict::asserted(passed),
            note: String::new(),
        }
    }

    /// Pass if measured ≥ bound.
    pub fn at_least(name: impl Into<String>, measured: f64, bound: f64) -> Self {
        Row {
            tolerance: format!(">= {}", short(bound)),
            verdict: Verdict::asserted(measured >= bound && measured.is_finite()),
            ..Self::at_most(name, measured, bound)
        }
    }

    /// The same row with `note` (what else the case measured).
    pub fn with_note(self, note: impl Into<String>) -> Self {
        Row {
            note: note.into(),
            ..self
        }
    }

    /// A yes/no check reported as 1 (true) against 1.
    pub fn holds(name: impl Into<String>, ok: bool) -> Self {
        Row {
            name: name.into(),
            measured: if ok { 1.0 } else { 0.0 },
            reference: 1.0,
            tolerance: "holds".into(),
            verdict: Verdict::asserted(ok),
            note: String::new(),
        }
    }
}

impl Row {
    /// Convergence of a value over three levels, each refining the one before by 2: the
    /// rows `{name} step ratio` (|u2 − u1| / |u1 − u0| ≤ `max_ratio`, asserted) and
    /// `{name} observed order` (log2 of its inverse, reported).
    pub fn convergence(name: &str, u: [f64; 3], max_ratio: f64) -> [Row; 2] {
        let ratio = ((u[2] - u[1]) / (u[1] - u[0])).abs();
        [
            Self::at_most(format!("{name} step ratio"), ratio, max_ratio),
            Self::reported(format!("{name} observed order"), -ratio.log2()),
        ]
    }

    /// A value reported without a reference or a verdict (its reference column reads NaN).
    pub fn reported(name: impl Into<String>, measured: f64) -> Self {
        Self::info(name, measured, f64::NAN)
    }

    /// A value reported against its reference without a pass/fail verdict.
    pub fn info(name: impl Into<String>, measured: f64, reference: f64) -> Self {
        Row {
            name: name.into(),
            measured,
            reference,
            tolerance: "-".into(),
            verdict: Verdict::Info,
            note: String::new(),
        }
    }
}

impl fmt::Display for Row {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:<60} {:>14.6e} {:>14.6e} {:>12} {}",
            self.name,
            self.measured,
            self.reference,
            self.tolerance,
            match self.verdict {
                Verdict::Info => "info",
                Verdict::Pass => "pass",
                Verdict::Fail => "FAIL",
            }
        )?;
        match self.note.is_empty() {
            true => Ok(()),
            false => write!(f, "  ({})", self.note),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::short;

    #[test]
    fn tolerances_print_as_short_as_their_value_allows() {
        assert_eq!(short(1e-9), "1e-9");
        assert_eq!(short(2.5e-3), "2.5e-3");
        assert_eq!(short(0.016093), "1.6e-2");
        assert_eq!(short(0.2218), "2.2e-1");
        assert_eq!(short(0.0127), "1.27e-2");
    }
}
