//! Pochhammer-Chree dispersion of the bar waves, and its correction when a pulse is moved
//! between a gauge and a specimen face.
//!
//! The fundamental longitudinal mode of a solid cylinder of radius a travels at a phase
//! velocity c(f) below the rod speed c0 = √(E/ρ) once its wavelength Λ = c/f is not much
//! longer than the bar is wide. With wavenumber k, x = k a, γ = c/c_S (c_S the shear
//! speed), P² = 1 − γ² c_S²/c_L², Q² = γ² − 1 (for c_S < c < c_L), the frequency equation
//! (Pochhammer 1876, Chree 1889; Graff, Wave Motion in Elastic Solids, 8.2) reads
//!   −(2P/x)(Q² + 1) I1(Px) J1(Qx) − (Q² − 1)² I0(Px) J1(Qx) + 4 P Q I1(Px) J0(Qx) = 0,
//! whose root nearest below γ0 = c0/c_S = √(2(1 + ν)) is the fundamental mode. As x → 0 it
//! tends to c0, as c/c0 ≈ 1 − ν² π² (a/Λ)² (Rayleigh-Love).
//!
//! Correction (`correct`): a gauge record shifted by the distance z (positive: toward
//! the specimen, the incident pulse; negative: back from it, the reflected and the
//! transmitted pulses) gets, per frequency, the phase of the dispersive part of the
//! travel time, e^{−iω z (1/c(ω) − 1/c0)}; the non-dispersive part z/c0 stays with the
//! geometric time shift. Beyond the frequency at which c falls to c_S (the equation's
//! range above) the phase of that frequency is kept.

use rustfft::num_complex::Complex;
use rustfft::FftPlanner;
use std::f64::consts::PI;

/// J0, J1, I0, I1 by their power series (arguments up to ≈ 10, far beyond the ones
/// here: P x ≤ x and Q x ≤ 1.3 x with x = k a ≤ 4 in the corrected range).
fn bessel(x: f64, order: u32, modified: bool) -> f64 {
    let sign = if modified { 1.0 } else { -1.0 };
    let q = 0.25 * x * x;
    let mut term = (0.5 * x).powi(order as i32);
    let mut sum = term;
    for m in 1..60 {
        term *= sign * q / (m as f64 * (m + order) as f64);
        sum += term;
        if term.abs() < 1e-17 * sum.abs() {
            break;
        }
    }
    sum
}

/// The frequency equation at γ = c/c_S for x = k a and Poisson's ratio ν.
fn frequency_equation(gamma: f64, x: f64, nu: f64) -> f64 {
    let s = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu));
    let p = (1.0 - gamma * gamma * s).sqrt();
    let q = (gamma * gamma - 1.0).sqrt();
    let (i0, i1) = (bessel(p * x, 0, true), bessel(p * x, 1, true));
    let (j0, j1) = (bessel(q * x, 0, false), bessel(q * x, 1, false));
    -(2.0 * p / x) * (q * q + 1.0) * i1 * j1 - (q * q - 1.0).powi(2) * i0 * j1
        + 4.0 * p * q * i1 * j0
}

/// Step of a/Λ in the continuation of the fundamental root.
const STEP: f64 = 0.002;

/// The root of the frequency equation at `x` first met going down from `from` (just above
/// the root at a slightly smaller x, so that the fundamental mode is followed and not the
/// second, which enters (c_S, c0) at short waves), or `None` above γ = 1.
fn next_root(from: f64, x: f64, nu: f64) -> Option<f64> {
    let f = |g: f64| frequency_equation(g, x, nu);
    let steps = 400;
    let step = (from - 1.0) / steps as f64;
    let (mut hi, mut f_hi) = (from, f(from));
    for k in 1..steps {
        let lo = from - k as f64 * step;
        let f_lo = f(lo);
        if f_lo.signum() != f_hi.signum() {
            let (mut a, mut b) = (lo, hi);
            for _ in 0..60 {
                let m = 0.5 * (a + b);
                if f(m).signum() == f_lo.signum() {
                    a = m;
                } else {
                    b = m;
                }
            }
            return Some(0.5 * (a + b));
        }
        (hi, f_hi) = (lo, f_lo);
    }
    None
}

/// The fundamental branch c/c0 at a/Λ = STEP, 2 STEP, ... up to `last` (or until it
/// would fall below the shear speed).
fn branch(nu: f64, last: f64) -> Vec<(f64, f64)> {
    let gamma0 = (2.0 * (1.0 + nu)).sqrt();
    let mut gamma = gamma0;
    let mut out = Vec::new();
    let mut r = STEP;
    while r <= last + 1e-12 {
        match next_root(gamma * (1.0 + 1e-9), 2.0 * PI * r, nu) {
            Some(g) => {
                gamma = g;
                out.push((r, g / gamma0));
            }
            None => break,
        }
        r += STEP;
    }
    out
}

/// Phase velocity of the fundamental mode over c0, at radius over wavelength
/// `a_over_lambda` and Poisson's ratio `nu`; `None` where it would fall below the shear
/// speed.
pub fn phase_velocity_ratio(a_over_lambda: f64, nu: f64) -> Option<f64> {
    if a_over_lambda <= 0.0 {
        return Some(1.0);
    }
    let gamma0 = (2.0 * (1.0 + nu)).sqrt();
    let below = branch(nu, a_over_lambda - STEP);
    let start = below.last().map_or(gamma0, |b| b.1 * gamma0);
    next_root(start * (1.0 + 1e-9), 2.0 * PI * a_over_lambda, nu).map(|g| g / gamma0)
}

/// Phase velocity c(f) [m/s] of a bar (rod speed `c0`, `radius` [m], Poisson's ratio
/// `nu`), tabulated along the fundamental branch: at a/Λ = r, f = r c / a.
pub struct PhaseVelocity {
    c0: f64,
    /// (f [Hz], c [m/s]), f increasing.
    table: Vec<(f64, f64)>,
}

impl PhaseVelocity {
    pub fn new(c0: f64, radius: f64, nu: f64) -> PhaseVelocity {
        let mut table = vec![(0.0, c0)];
        table.extend(
            branch(nu, 2.0)
                .into_iter()
                .map(|(r, ratio)| (r * ratio * c0 / radius, ratio * c0)),
        );
        PhaseVelocity { c0, table }
    }

    /// c at frequency `f` [Hz] (linear in f between table points), `None` beyond the
    /// branch's range.
    pub fn at(&self, f: f64) -> Option<f64> {
        let k = self.table.partition_point(|p| p.0 < f);
        if k == 0 {
            return Some(self.c0);
        }
        let ((f0, c0), (f1, c1)) = (self.table[k - 1], *self.table.get(k)?);
        Some(c0 + (c1 - c0) * (f - f0) / (f1 - f0))
    }
}

/// `signal` (sampled every `dt` [s]) moved by `distance` [m] along the bar with the
/// dispersive part of the travel time (module docs); the mean is kept, the record is
/// padded with its end values to twice a power of two against wrap-around.
pub fn correct(signal: &[f64], dt: f64, distance: f64, bar: &PhaseVelocity) -> Vec<f64> {
    let n = signal.len();
    let size = (2 * n).next_power_of_two();
    let last = *signal.last().unwrap_or(&0.0);
    let mut spectrum: Vec<Complex<f64>> = (0..size)
        .map(|k| Complex::new(if k < n { signal[k] } else { last }, 0.0))
        .collect();
    let mut planner = FftPlanner::new();
    planner.plan_fft_forward(size).process(&mut spectrum);
    let mut held = 0.0;
    // the Nyquist bin of a real record has no phase to turn: it is left as it is
    for m in 1..size / 2 {
        let f = m as f64 / (size as f64 * dt);
        let extra = match bar.at(f) {
            Some(c) => {
                held = distance * (1.0 / c - 1.0 / bar.c0);
                held
            }
            None => held,
        };
        let phase = Complex::from_polar(1.0, -2.0 * PI * f * extra);
        spectrum[m] *= phase;
        spectrum[size - m] *= phase.conj();
    }
    planner.plan_fft_inverse(size).process(&mut spectrum);
    spectrum[..n].iter().map(|z| z.re / size as f64).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rayleigh-Love: c/c0 = 1 − ν² π² (a/Λ)² + O((a/Λ)⁴), checked at a/Λ = 0.01 and
    /// 0.02 to 1e-6, where the next term is ≈ 1e-7.
    #[test]
    fn long_waves_follow_rayleigh_love() {
        for nu in [0.29, 0.33] {
            for r in [0.01, 0.02] {
                let c = phase_velocity_ratio(r, nu).unwrap();
                let love = 1.0 - nu * nu * PI * PI * r * r;
                assert!((c - love).abs() < 1e-6, "ν {nu} a/Λ {r}: {c} vs {love}");
            }
        }
    }

    /// Shorter waves travel slower, down towards the shear speed.
    #[test]
    fn phase_velocity_falls_with_frequency() {
        let mut last = 1.0;
        for k in 1..26 {
            let c = phase_velocity_ratio(0.02 * k as f64, 0.29).unwrap();
            println!("a/Λ {:.2}: c/c0 {c:.5}", 0.02 * k as f64);
            assert!(c < last, "a/Λ {}: {c}", 0.02 * k as f64);
            last = c;
        }
        let shear = 1.0 / (2.0f64 * 1.29).sqrt();
        assert!(last > shear);
    }

    /// A trapezoidal pulse (5 µs rise, 1e-3) moved 0.75 m along a 20 mm bar with
    /// dispersion and corrected back: `round_trip` (the verify row) measures both errors.
    #[test]
    fn a_dispersed_pulse_is_corrected_back() {
        let (dispersed, recovered) = round_trip();
        assert!(
            dispersed > 0.01,
            "dispersion changes the pulse: {dispersed}"
        );
        assert!(recovered < 1e-3, "{recovered}");
    }
}

/// The pulse of the round trip: 1e-3 with 5 µs ramps at 20 and 80 µs, sampled at 32 ns
/// over 512 µs.
fn trapezoid() -> (Vec<f64>, f64) {
    let dt = 32e-9;
    let ramp = |t: f64| (t / 5e-6).clamp(0.0, 1.0);
    let pulse = (0..16000)
        .map(|k| k as f64 * dt)
        .map(|t| 1e-3 * (ramp(t - 20e-6) - ramp(t - 80e-6)))
        .collect();
    (pulse, dt)
}

/// A trapezoidal pulse moved 0.75 m along a 20 mm bar (c0 5189 m/s, ν 0.29) with the
/// dispersive travel time, and that moved back: the largest difference from the pulse,
/// relative to its amplitude, (after the first move, after both).
pub fn round_trip() -> (f64, f64) {
    let bar = PhaseVelocity::new(5189.0, 0.01, 0.29);
    let (pulse, dt) = trapezoid();
    let there = correct(&pulse, dt, 0.75, &bar);
    let back = correct(&there, dt, -0.75, &bar);
    let worst = |x: &[f64]| {
        pulse
            .iter()
            .zip(x)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / 1e-3
    };
    (worst(&there), worst(&back))
}
