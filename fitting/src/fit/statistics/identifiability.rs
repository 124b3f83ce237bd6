//! Which parameter combinations a fit's data do not identify: pairs whose correlation at
//! the optimum (from JᵀJ, `run::statistics`) reaches `LIMIT` in magnitude, each with the
//! kind of data that would separate them. A correlation near ±1 means the objective is
//! nearly flat along one combination of the two: the data fix that combination, not each.

/// |r| at or above which a pair counts as not identified separately.
pub const LIMIT: f64 = 0.95;

/// What data separate a pair that contains `name`.
fn remedy(name: &str) -> &'static str {
    match name {
        "C" | "C2" | "D_cs" | "p_cs" => {
            "tests at a second, distant strain-rate band (decades apart, at one temperature)"
        }
        "M" | "theta_m" | "lambda_theta" => "tests at another temperature (pre-heated), at a rate already covered",
        "alpha_dot0" => "fix the reference rate at the lowest test rate instead of fitting it",
        _ => "a wider strain range at one rate and temperature (hardening seen from yield to large strain)",
    }
}

/// One line per pair of `free` with |correlation| ≥ `LIMIT`.
pub fn warnings(free: &[String], correlation: &[Vec<f64>]) -> Vec<String> {
    if correlation.iter().flatten().any(|r| r.is_nan()) {
        return vec!["the correlations are undefined (the Jacobian is singular: a parameter does not change the prediction, for example because it sits on a bound)".into()];
    }
    let mut out = Vec::new();
    for i in 0..free.len() {
        for j in i + 1..free.len() {
            let r = correlation[i][j];
            if r.abs() >= LIMIT {
                // The remedy of the rate or temperature parameter when the pair has one.
                let key = if remedy(&free[j]) != remedy("A") {
                    &free[j]
                } else {
                    &free[i]
                };
                out.push(format!(
                    "the data do not identify {} and {} separately (r = {r:.3}); what would: {}",
                    free[i],
                    free[j],
                    remedy(key)
                ));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strongly_correlated_pairs_are_named_with_a_remedy() {
        let free: Vec<String> = ["A", "B", "C"].iter().map(|s| s.to_string()).collect();
        let corr = vec![
            vec![1.0, 0.6, 0.977],
            vec![0.6, 1.0, -0.951],
            vec![0.977, -0.951, 1.0],
        ];
        let w = warnings(&free, &corr);
        assert_eq!(w.len(), 2, "{w:?}");
        assert!(w[0].starts_with("the data do not identify A and C separately (r = 0.977)"));
        assert!(
            w[0].contains("second, distant strain-rate band"),
            "{}",
            w[0]
        );
        assert!(w[1].contains("B and C") && w[1].contains("r = -0.951"));
        let calm = vec![vec![1.0, 0.949], vec![0.949, 1.0]];
        assert!(warnings(&free[..2], &calm).is_empty());
    }
}
