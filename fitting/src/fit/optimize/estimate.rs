//! How many iterations a Levenberg-Marquardt run still needs, for a progress line. Its
//! stopping test (`lm`) is the relative decrease of the objective over an accepted step,
//! d_k = (S_{k−1} − S_k)/S_k < ftol. Near the optimum the decreases fall about
//! geometrically, d_{k+j} ≈ d_k q^j with q = d_k/d_{k−1} < 1, so the test is met after
//! j = ⌈ln(ftol/d_k)/ln q⌉ more accepted steps. An estimate, not a bound: none is given
//! while the decreases do not yet fall (q ≥ 1).

/// More accepted steps until the relative decrease drops below `ftol`, from the best
/// objective values after each iteration so far (`costs[0]` at the start). Iterations that
/// did not lower S (rejected steps) are skipped. `None` while fewer than two decreases are
/// known or they do not fall.
pub fn remaining_iterations(costs: &[f64], ftol: f64) -> Option<usize> {
    let mut accepted: Vec<f64> = Vec::new();
    for &c in costs.iter().filter(|c| c.is_finite()) {
        if accepted.last().is_none_or(|&last| c < last) {
            accepted.push(c);
        }
    }
    let [.., a, b, c] = accepted[..] else {
        return None;
    };
    let (d0, d1) = ((a - b) / b, (b - c) / c);
    if d1 < ftol {
        return Some(0);
    }
    let q = d1 / d0;
    if !(q > 0.0 && q < 1.0) {
        return None;
    }
    Some(((ftol / d1).ln() / q.ln()).ceil() as usize)
}

#[cfg(test)]
mod tests {
    use super::remaining_iterations;

    /// S_k = 1 + 0.3^k: the estimate after each iteration against the iterations the
    /// stopping test actually took.
    #[test]
    fn geometric_decrease_is_predicted_within_one_iteration() {
        let ftol = 1e-9;
        let costs: Vec<f64> = (0..40).map(|k| 1.0 + 0.3f64.powi(k)).collect();
        let stop = (1..costs.len())
            .find(|&k| (costs[k - 1] - costs[k]) / costs[k] < ftol)
            .unwrap();
        for k in 3..stop {
            let estimate = remaining_iterations(&costs[..=k], ftol).unwrap();
            let actual = stop - k;
            assert!(
                estimate.abs_diff(actual) <= 1,
                "after {k}: estimate {estimate}, actual {actual}"
            );
        }
    }

    #[test]
    fn rejected_steps_are_skipped_and_no_estimate_while_decreases_grow() {
        // Repeated values (rejected steps) do not change the estimate.
        let plain = [2.0, 1.5, 1.25, 1.125];
        let with_rejections = [2.0, 1.5, 1.5, 1.25, 1.25, 1.25, 1.125];
        assert_eq!(
            remaining_iterations(&plain, 1e-6),
            remaining_iterations(&with_rejections, 1e-6)
        );
        // Decreases that grow (0.1 then 0.5 of S) give no estimate.
        assert_eq!(remaining_iterations(&[1.21, 1.1, 1.1 / 1.5], 1e-6), None);
        assert_eq!(remaining_iterations(&[1.0, 0.5], 1e-6), None);
        // Converged: the last decrease is already below ftol.
        assert_eq!(
            remaining_iterations(&[1.0, 0.5, 0.5 - 1e-12], 1e-9),
            Some(0)
        );
    }
}
