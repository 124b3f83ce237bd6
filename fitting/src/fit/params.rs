//! Free parameters of a fit: names, bounds, and the transformation that makes a bounded
//! problem unconstrained for the optimizers.
//!
//! For a parameter x with bounds [l, h]:
//! - both finite: x = l + (h − l) s(u), s(u) = 1/(1 + e^(−u)) (logistic), dx/du = (h − l) s (1 − s);
//! - lower only:  x = l + e^u, dx/du = e^u;
//! - none:        x = u.
//!
//! Values are SI (Pa for A and B, dimensionless for N, C, M).

use anyhow::{bail, Result};

/// One free parameter: material-parameter name, bounds and start value (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct FreeParam {
    pub name: String,
    pub lower: f64,
    pub upper: f64,
    pub start: f64,
}

impl FreeParam {
    pub fn new(name: &str, lower: f64, upper: f64, start: f64) -> Result<Self> {
        if lower.is_nan() || upper.is_nan() || !(lower < upper) {
            bail!("parameter `{name}`: bounds [{lower}, {upper}] must satisfy lower < upper");
        }
        if !(start > lower && start < upper) || !start.is_finite() {
            bail!("parameter `{name}`: start {start} must lie strictly inside [{lower}, {upper}]");
        }
        Ok(FreeParam {
            name: name.to_string(),
            lower,
            upper,
            start,
        })
    }

    /// This parameter started at `x`, moved just inside the bounds if it lies on or
    /// outside them.
    pub fn starting_at(&self, x: f64) -> FreeParam {
        let span = self.upper - self.lower;
        let start = x.clamp(self.lower + 1e-6 * span, self.upper - 1e-6 * span);
        FreeParam {
            start,
            ..self.clone()
        }
    }

    /// x(u).
    pub fn to_bounded(&self, u: f64) -> f64 {
        match (self.lower.is_finite(), self.upper.is_finite()) {
            (true, true) => self.lower + (self.upper - self.lower) * logistic(u),
            (true, false) => self.lower + u.exp(),
            (false, true) => self.upper - (-u).exp(),
            (false, false) => u,
        }
    }

    /// u(x), the inverse of `to_bounded` (x strictly inside the bounds).
    pub fn to_unbounded(&self, x: f64) -> f64 {
        match (self.lower.is_finite(), self.upper.is_finite()) {
            (true, true) => {
                let s = (x - self.lower) / (self.upper - self.lower);
                (s / (1.0 - s)).ln()
            }
            (true, false) => (x - self.lower).ln(),
            (false, true) => -(self.upper - x).ln(),
            (false, false) => x,
        }
    }

    /// dx/du at u.
    pub fn derivative(&self, u: f64) -> f64 {
        match (self.lower.is_finite(), self.upper.is_finite()) {
            (true, true) => {
                let s = logistic(u);
                (self.upper - self.lower) * s * (1.0 - s)
            }
            (true, false) => u.exp(),
            (false, true) => (-u).exp(),
            (false, false) => 1.0,
        }
    }
}

fn logistic(u: f64) -> f64 {
    1.0 / (1.0 + (-u).exp())
}

/// The free parameters of one fit, in a fixed order.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamSpace {
    pub params: Vec<FreeParam>,
}

impl ParamSpace {
    pub fn new(params: Vec<FreeParam>) -> Result<Self> {
        if params.is_empty() {
            bail!("no free parameters");
        }
        for (k, p) in params.iter().enumerate() {
            if params[..k].iter().any(|q| q.name == p.name) {
                bail!("parameter `{}` is listed twice", p.name);
            }
        }
        Ok(ParamSpace { params })
    }

    pub fn len(&self) -> usize {
        self.params.len()
    }

    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    pub fn names(&self) -> Vec<&str> {
        self.params.iter().map(|p| p.name.as_str()).collect()
    }

    pub fn starts(&self) -> Vec<f64> {
        self.params.iter().map(|p| p.start).collect()
    }

    pub fn to_bounded(&self, u: &[f64]) -> Vec<f64> {
        self.params
            .iter()
            .zip(u)
            .map(|(p, &u)| p.to_bounded(u))
            .collect()
    }

    pub fn to_unbounded(&self, x: &[f64]) -> Vec<f64> {
        self.params
            .iter()
            .zip(x)
            .map(|(p, &x)| p.to_unbounded(x))
            .collect()
    }

    /// dx_k/du_k (the transformation is diagonal).
    pub fn derivatives(&self, u: &[f64]) -> Vec<f64> {
        self.params
            .iter()
            .zip(u)
            .map(|(p, &u)| p.derivative(u))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transforms_invert_and_differentiate() {
        let cases = [
            FreeParam::new("A", 1e8, 2e9, 7e8).unwrap(),
            FreeParam::new("C", 0.0, f64::INFINITY, 0.02).unwrap(),
            FreeParam::new("M", f64::NEG_INFINITY, 3.0, 1.2).unwrap(),
            FreeParam::new("X", f64::NEG_INFINITY, f64::INFINITY, -4.0).unwrap(),
        ];
        for p in &cases {
            let u = p.to_unbounded(p.start);
            // Round trip to 1e-12 relative.
            let back = p.to_bounded(u);
            assert!(
                (back - p.start).abs() <= 1e-12 * p.start.abs(),
                "{}: {back}",
                p.name
            );
            // Analytic derivative against a central difference, 1e-7 relative.
            let h = 1e-5;
            let fd = (p.to_bounded(u + h) - p.to_bounded(u - h)) / (2.0 * h);
            let d = p.derivative(u);
            assert!((d - fd).abs() <= 1e-7 * d.abs(), "{}: {d} vs {fd}", p.name);
        }
    }

    #[test]
    fn bad_bounds_are_errors() {
        assert!(FreeParam::new("A", 2.0, 1.0, 1.5).is_err());
        assert!(FreeParam::new("A", 1.0, 2.0, 2.0).is_err());
    }
}
