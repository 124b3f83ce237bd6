//! One row of the `mpw verify` table: a verification case with its measured value,
//! reference value and tolerance. Every part of the catalogue (materials, SHPB, fitting,
//! MPM) contributes its own rows.

use std::fmt;

#[derive(Debug, Clone)]
pub struct CaseResult {
    /// Case name, e.g. `j2/tangent-vs-fd`.
    pub name: String,
    pub measured: f64,
    pub reference: f64,
    /// What `measured` is compared with `reference` by, in words (e.g. `rel 1e-6`).
    pub tolerance: String,
    pub passed: bool,
    /// Reported only: neither a pass nor a failure (a known gap, or a value without a
    /// reference).
    pub info: bool,
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

impl CaseResult {
    /// Pass if |measured − reference| ≤ tol · |reference|.
    pub fn relative(name: impl Into<String>, measured: f64, reference: f64, tol: f64) -> Self {
        let passed = (measured - reference).abs() <= tol * reference.abs() && measured.is_finite();
        CaseResult {
            name: name.into(),
            measured,
            reference,
            tolerance: format!("rel {}", short(tol)),
            passed,
            info: false,
        }
    }

    /// Pass if |measured − reference| ≤ tol.
    pub fn absolute(name: impl Into<String>, measured: f64, reference: f64, tol: f64) -> Self {
        let passed = (measured - reference).abs() <= tol && measured.is_finite();
        CaseResult {
            name: name.into(),
            measured,
            reference,
            tolerance: format!("abs {}", short(tol)),
            passed,
            info: false,
        }
    }

    /// Pass if measured ≤ bound (an error measure against zero).
    pub fn at_most(name: impl Into<String>, measured: f64, bound: f64) -> Self {
        let passed = measured <= bound && measured.is_finite();
        CaseResult {
            name: name.into(),
            measured,
            reference: 0.0,
            tolerance: format!("<= {}", short(bound)),
            passed,
            info: false,
        }
    }

    /// Pass if measured ≥ bound.
    pub fn at_least(name: impl Into<String>, measured: f64, bound: f64) -> Self {
        CaseResult {
            tolerance: format!(">= {}", short(bound)),
            passed: measured >= bound && measured.is_finite(),
            ..Self::at_most(name, measured, bound)
        }
    }

    /// A yes/no check reported as 1 (true) against 1.
    pub fn holds(name: impl Into<String>, ok: bool) -> Self {
        CaseResult {
            name: name.into(),
            measured: if ok { 1.0 } else { 0.0 },
            reference: 1.0,
            tolerance: "holds".into(),
            passed: ok,
            info: false,
        }
    }
}

impl CaseResult {
    /// Convergence of a value over three levels, each refining the one before by 2: the
    /// rows `{name} step ratio` (|u2 − u1| / |u1 − u0| ≤ `max_ratio`, asserted) and
    /// `{name} observed order` (log2 of its inverse, reported).
    pub fn convergence(name: &str, u: [f64; 3], max_ratio: f64) -> [CaseResult; 2] {
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
        CaseResult {
            name: name.into(),
            measured,
            reference,
            tolerance: "-".into(),
            passed: true,
            info: true,
        }
    }
}

impl fmt::Display for CaseResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:<60} {:>14.6e} {:>14.6e} {:>12} {}",
            self.name,
            self.measured,
            self.reference,
            self.tolerance,
            match (self.info, self.passed) {
                (true, _) => "info",
                (false, true) => "pass",
                (false, false) => "FAIL",
            }
        )
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
