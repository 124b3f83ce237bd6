//! A signal of time: piecewise-linear through samples (t_k, v_k), constant beyond its ends.
//! One type serves the driver's load ramps, rigid-body translation and rotation, and
//! prescribed velocities; the value may be a scalar or a vector. A lookup is a binary
//! search (O(log n)), so a 20 000-sample measured record costs about 15 comparisons per
//! evaluation. Samples are checked once, when the signal is made.
//!
//! Between samples k−1 and k: v(t) = v_{k−1} (1 − s) + v_k s, s = (t − t_{k−1})/(t_k − t_{k−1}).

use crate::limits::TooLarge;
use std::ops::{Add, Mul};
use thiserror::Error;

/// What a signal's value needs: copy, scale by a weight, add, and say if it is finite.
pub trait SignalValue: Copy + Mul<f64, Output = Self> + Add<Output = Self> {
    fn is_finite_value(&self) -> bool;
}

impl SignalValue for f64 {
    fn is_finite_value(&self) -> bool {
        self.is_finite()
    }
}

impl<const D: usize> SignalValue for nalgebra::SVector<f64, D> {
    fn is_finite_value(&self) -> bool {
        self.iter().all(|x| x.is_finite())
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct TimeSignal<T> {
    t: Vec<f64>,
    v: Vec<T>,
}

#[derive(Debug, Error, PartialEq)]
pub enum SignalError {
    #[error(
        "a signal needs at least one sample and as many times as values (got {0} times, {1} values)"
    )]
    Shape(usize, usize),
    #[error("signal times must be finite and strictly increasing (sample {0})")]
    NotIncreasing(usize),
    #[error("signal value of sample {0} is not finite")]
    NonFinite(usize),
    /// A path built from a signal would be too long (`limits`).
    #[error(transparent)]
    TooLarge(#[from] TooLarge),
}

impl<T: SignalValue> TimeSignal<T> {
    /// A signal through the samples (t[k], v[k]); times strictly increasing.
    pub fn new(t: Vec<f64>, v: Vec<T>) -> Result<Self, SignalError> {
        if t.is_empty() || t.len() != v.len() {
            return Err(SignalError::Shape(t.len(), v.len()));
        }
        if let Some(k) = (0..t.len()).find(|&k| !t[k].is_finite() || (k > 0 && t[k] <= t[k - 1])) {
            return Err(SignalError::NotIncreasing(k));
        }
        if let Some(k) = v.iter().position(|x| !x.is_finite_value()) {
            return Err(SignalError::NonFinite(k));
        }
        Ok(TimeSignal { t, v })
    }

    /// A signal from (t, v) samples.
    pub fn from_samples(samples: impl IntoIterator<Item = (f64, T)>) -> Result<Self, SignalError> {
        let (t, v) = samples.into_iter().unzip();
        Self::new(t, v)
    }

    /// The same value at every time.
    pub fn constant(v: T) -> Self {
        TimeSignal {
            t: vec![0.0],
            v: vec![v],
        }
    }

    #[inline]
    pub fn at(&self, time: f64) -> T {
        let k = self.t.partition_point(|&tk| tk < time);
        if k == 0 {
            return self.v[0];
        }
        if k == self.t.len() {
            return self.v[k - 1];
        }
        let s = (time - self.t[k - 1]) / (self.t[k] - self.t[k - 1]);
        self.v[k - 1] * (1.0 - s) + self.v[k] * s
    }

    /// The running integral ∫ v dt from the first sample, by the trapezoid rule at the
    /// samples (a displacement from a velocity record): exact at the samples for a
    /// piecewise-linear v, linear between them (error ≤ |Δv| Δt / 8 per segment).
    pub fn integrated(&self) -> TimeSignal<T> {
        let mut u = Vec::with_capacity(self.v.len());
        let mut sum = self.v[0] * 0.0;
        u.push(sum);
        for k in 1..self.t.len() {
            sum = sum + (self.v[k - 1] + self.v[k]) * (0.5 * (self.t[k] - self.t[k - 1]));
            u.push(sum);
        }
        TimeSignal {
            t: self.t.clone(),
            v: u,
        }
    }

    /// Sample times [s].
    pub fn times(&self) -> &[f64] {
        &self.t
    }

    /// Sample values.
    pub fn values(&self) -> &[T] {
        &self.v
    }

    /// Time of the last sample [s].
    pub fn end(&self) -> f64 {
        self.t[self.t.len() - 1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn values_interpolate_between_samples_and_hold_beyond_the_ends() {
        let s = TimeSignal::new(vec![0.0, 1.0, 3.0], vec![0.0, 2.0, -2.0]).unwrap();
        assert_eq!(s.at(-1.0), 0.0);
        assert_eq!(s.at(0.5), 1.0);
        assert_eq!(s.at(1.0), 2.0);
        assert_eq!(s.at(2.0), 0.0);
        assert_eq!(s.at(9.0), -2.0);
        let v = TimeSignal::from_samples([
            (0.0, Vector2::new(0.0, 1.0)),
            (2.0, Vector2::new(4.0, 1.0)),
        ])
        .unwrap();
        assert_eq!(v.at(0.5), Vector2::new(1.0, 1.0));
    }

    /// The binary search agrees with a scan of every segment on a long record.
    #[test]
    fn a_long_record_is_looked_up_exactly() {
        let t: Vec<f64> = (0..20_000)
            .map(|k| k as f64 * 1e-7 + (k as f64).sin() * 1e-9)
            .collect();
        let v: Vec<f64> = (0..20_000).map(|k| (k as f64 * 1e-3).cos()).collect();
        let s = TimeSignal::new(t.clone(), v.clone()).unwrap();
        for q in [0.0, 3.3e-5, 1.2345e-3, 1.9998e-3] {
            let k = t.windows(2).position(|w| q <= w[1]).unwrap();
            let a = (q - t[k]) / (t[k + 1] - t[k]);
            let scan = v[k] * (1.0 - a) + v[k + 1] * a;
            assert_eq!(s.at(q).to_bits(), scan.to_bits(), "{q}");
        }
    }

    /// A velocity ramp integrates to the parabola at every sample.
    #[test]
    fn the_integral_of_a_ramp_is_exact_at_the_samples() {
        let t: Vec<f64> = (0..=100).map(|k| k as f64 * 0.01).collect();
        let v = TimeSignal::new(t.clone(), t.iter().map(|t| 3.0 * t).collect()).unwrap();
        let u = v.integrated();
        for (k, tk) in t.iter().enumerate() {
            assert!((u.values()[k] - 1.5 * tk * tk).abs() < 1e-14, "{tk}");
        }
    }

    #[test]
    fn bad_samples_are_named() {
        assert_eq!(
            TimeSignal::new(vec![0.0, 1.0, 1.0], vec![0.0; 3]),
            Err(SignalError::NotIncreasing(2))
        );
        assert_eq!(
            TimeSignal::new(vec![0.0, f64::NAN], vec![0.0; 2]),
            Err(SignalError::NotIncreasing(1))
        );
        assert_eq!(
            TimeSignal::new(vec![0.0, 1.0], vec![0.0, f64::INFINITY]),
            Err(SignalError::NonFinite(1))
        );
        assert_eq!(
            TimeSignal::<f64>::new(vec![], vec![]),
            Err(SignalError::Shape(0, 0))
        );
    }
}
