//! Fitting: truth recovery from the shipped synthetic set and the exact Jacobian.

use fitting::fit::verify::{jacobian_vs_fd, recovery_cases};

/// A and B within 2 %, N within 5 %, C and M within 10 % of the truth in the file headers.
#[test]
fn default_set_recovers_the_truth() {
    for row in recovery_cases().unwrap() {
        println!("{row}");
        assert!(row.passed, "{row}");
    }
}

/// Exact AD Jacobian against central differences: relative column error ≤ 1e-5.
#[test]
fn exact_jacobian_matches_central_differences() {
    let d = jacobian_vs_fd().unwrap();
    println!("worst column error {d:e}");
    assert!(d <= 1e-5, "{d:e}");
}
