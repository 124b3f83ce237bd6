//! The largest sizes that input data may ask for (`SizeLimit`): a count derived from data
//! (here: steps of a load path from a strain history; in mpm-core: particles, grid nodes
//! and time steps; in the readers of fitting: file sizes and signal samples) is checked
//! before anything of that size is allocated, so that one mistyped value gives an error
//! instead of exhausting memory. Each limit is far above what any shipped case or real
//! record needs and well below what would freeze a 24 GiB workstation; the error says
//! which.

use thiserror::Error;

/// A size bound: what is counted, its largest allowed value and what one item costs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SizeLimit {
    /// What is counted, e.g. "load-path steps".
    pub what: &'static str,
    pub max: usize,
    /// Approximate memory per item [bytes], for the message.
    pub bytes_each: usize,
}

/// Steps of a single-point load path (records of σ, F and the state per step; a fit keeps
/// their parameter sensitivities too). A tensile record of 10⁵ samples to 100 % strain
/// needs about 10⁵ + 400 steps.
pub const LOAD_PATH_STEPS: SizeLimit = SizeLimit {
    what: "load-path steps",
    max: 5_000_000,
    bytes_each: 400,
};

/// A count that broke its limit, or that is not a finite non-negative number.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{count:.4e} {what} asked for, more than the limit of {max} ({memory}); {cause}")]
pub struct TooLarge {
    pub what: &'static str,
    pub count: f64,
    pub max: usize,
    /// The limit's memory, e.g. "about 2.0 GB".
    pub memory: String,
    /// What in the input made the count, from the caller.
    pub cause: String,
}

impl SizeLimit {
    /// `count` (possibly fractional or non-finite, as computed from data) as a size, or
    /// the error with `cause` describing the input that produced it.
    pub fn check(&self, count: f64, cause: impl FnOnce() -> String) -> Result<usize, TooLarge> {
        if count.is_finite() && count >= 0.0 && count <= self.max as f64 {
            return Ok(count.ceil() as usize);
        }
        Err(TooLarge {
            what: self.what,
            count,
            max: self.max,
            memory: format!(
                "about {:.1} GB",
                self.max as f64 * self.bytes_each as f64 / 1e9
            ),
            cause: cause(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_within_the_limit_pass_and_others_name_the_cause() {
        assert_eq!(LOAD_PATH_STEPS.check(2.3, String::new), Ok(3));
        assert_eq!(
            LOAD_PATH_STEPS.check(LOAD_PATH_STEPS.max as f64, String::new),
            Ok(LOAD_PATH_STEPS.max)
        );
        for bad in [
            LOAD_PATH_STEPS.max as f64 + 1.0,
            4e19,
            f64::INFINITY,
            f64::NAN,
            -1.0,
        ] {
            let e = LOAD_PATH_STEPS
                .check(bad, || "strain 1e20 at row 211".into())
                .unwrap_err();
            let text = e.to_string();
            assert!(text.contains("load-path steps"), "{text}");
            assert!(text.contains("row 211"), "{text}");
            assert!(text.contains("about 2.0 GB"), "{text}");
        }
    }
}
