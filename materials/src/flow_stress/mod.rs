//! Flow stress laws τ_y(α, α̇, θ) in Kirchhoff stress [Pa].
//!
//! - `Voce`: rate-independent saturation plus linear hardening, eq. 4.51:
//!   τ_y = τ∞ + (τ0 − τ∞) exp(−η α) + h α.
//! - `JohnsonCook`: eq. 4.52, τ_y = [A + B α^N] [1 + C ln(α̇/α̇0)] [1 − θ*^M] with the rate
//!   term clamped to ≥ 1 (α̇ < α̇0 counts as α̇0) and θ* = (θ − θ0)/(θm − θ0) clamped to
//!   [0, 1], as common explicit codes do.
//! - `Composed`: any hardening × rate sensitivity × thermal softening of `hardening`,
//!   `rate` and `softening` (`composed`); JC among them, which keeps its own variant and
//!   fast path.

pub mod composed;
pub mod hardening;
pub mod rate;
pub mod softening;

use crate::lanes::{pack, select, Lane, Mask};
use crate::parameter_set;
use crate::scalar::{c, Scalar};
pub use composed::Composed;
pub use hardening::{Hardening, Voce};
pub use rate::RateSensitivity;
use simba::simd::SimdBool;
pub use softening::ThermalSoftening;

parameter_set! {
    /// Eq. 4.52 parameters (θ0 lives with the thermal parameters).
    JohnsonCookLaw {
        /// initial yield strength A [Pa]
        a => "A",
        /// hardening modulus B [Pa]
        b => "B",
        /// hardening exponent N [-]
        n => "N",
        /// rate sensitivity C [-]
        c => "C",
        /// thermal softening exponent M [-]
        m => "M",
        /// reference plastic rate α̇0 [1/s]
        alpha_dot0 => "alpha_dot0",
        /// melting temperature θm [K]
        theta_m => "theta_m",
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FlowStress<D = f64> {
    Voce(Voce<D>),
    JohnsonCook(JohnsonCookLaw<D>),
    Composed(Composed<D>),
}

impl<D: Scalar> FlowStress<D> {
    /// τ_y at accumulated plastic strain `alpha`, plastic rate `alpha_dot` [1/s] and
    /// temperature `theta` [K] (reference temperature `theta0`).
    pub fn tau_y(&self, alpha: D, alpha_dot: D, theta: D, theta0: D) -> D {
        self.tau_y_athermal(alpha, alpha_dot) * self.thermal_factor(theta, theta0)
    }

    /// τ_y without its thermal factor: τ_y = `tau_y_athermal` · `thermal_factor`.
    pub fn tau_y_athermal(&self, alpha: D, alpha_dot: D) -> D {
        match self {
            FlowStress::Voce(p) => Hardening::Voce(*p).at(alpha),
            FlowStress::JohnsonCook(p) => {
                let hardening = hardening::power_law(p.a, p.b, p.n, alpha);
                let rate = RateSensitivity::JohnsonCook(rate::LogRate {
                    c: p.c,
                    alpha_dot0: p.alpha_dot0,
                });
                hardening * rate.factor(alpha_dot)
            }
            FlowStress::Composed(law) => law.tau_y_athermal(alpha, alpha_dot),
        }
    }

    /// The thermal factor: JC's 1 − θ*^M with θ* clamped to [0, 1]; 1 for Voce; the
    /// softening factor of a composed law.
    pub fn thermal_factor(&self, theta: D, theta0: D) -> D {
        match self {
            FlowStress::Voce(_) => c::<D>(1.0),
            FlowStress::JohnsonCook(p) => softening::johnson_cook(p.m, p.theta_m, theta, theta0),
            FlowStress::Composed(law) => law.thermal_factor(theta, theta0),
        }
    }

    /// Initial yield strength (for scaling and elastic-limit estimates).
    pub fn initial_yield(&self) -> D {
        match self {
            FlowStress::Voce(p) => p.tau0,
            FlowStress::JohnsonCook(p) => p.a,
            FlowStress::Composed(law) => law.hardening.at(c::<D>(0.0)),
        }
    }

    pub fn map<E>(&self, f: impl FnMut(&'static str, D) -> E) -> FlowStress<E> {
        match self {
            FlowStress::Voce(p) => FlowStress::Voce(p.map(f)),
            FlowStress::JohnsonCook(p) => FlowStress::JohnsonCook(p.map(f)),
            FlowStress::Composed(law) => FlowStress::Composed(law.map(f)),
        }
    }

    /// The law in words: `Johnson-Cook`, `voce (rate independent)`, or a composed law's
    /// factors (`power × huh-kang × johnson-cook`).
    pub fn describe(&self) -> String {
        match self {
            FlowStress::Voce(_) => "voce (rate independent)".into(),
            FlowStress::JohnsonCook(_) => "Johnson-Cook".into(),
            FlowStress::Composed(law) => law.describe(),
        }
    }

    /// The law as eq. 4.52 where it is one: the JC variant, or a composed law of power
    /// hardening, JC rate and JC softening; `None` for any other law.
    pub fn as_johnson_cook(&self) -> Option<JohnsonCookLaw<D>> {
        match self {
            FlowStress::JohnsonCook(p) => Some(*p),
            FlowStress::Composed(Composed {
                hardening: Hardening::Power(h),
                rate: RateSensitivity::JohnsonCook(r),
                softening: ThermalSoftening::JohnsonCook(t),
            }) => Some(JohnsonCookLaw {
                a: h.a,
                b: h.b,
                n: h.n,
                c: r.c,
                m: t.m,
                alpha_dot0: r.alpha_dot0,
                theta_m: t.theta_m,
            }),
            _ => None,
        }
    }

    pub fn names(&self) -> Vec<&'static str> {
        match self {
            FlowStress::Voce(_) => Voce::<D>::NAMES.to_vec(),
            FlowStress::JohnsonCook(_) => JohnsonCookLaw::<D>::NAMES.to_vec(),
            FlowStress::Composed(law) => law.names(),
        }
    }
}

/// The flow stress at one plastic increment of a local solve (see `LogIncrementPath`).
#[derive(Debug, Clone, Copy)]
pub struct AtIncrement<L = f64> {
    /// Δα = e^u [-]
    pub dalpha: L,
    /// τ_y [Pa]
    pub tau_y: L,
    /// dτ_y/du [Pa]
    pub dtau_y_du: L,
}

/// The flow stress at the start of a step, τ_y0 = τ_y(α_n, 0, θ_n) [Pa], which decides
/// whether a trial state yields, and the parts of it that a return reuses (one point, or
/// one per lane: `Onset::pack`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Onset<L = f64> {
    pub tau_y0: L,
    alpha_n: L,
    /// α_n^N (JC with α_n > 0, else 0).
    alpha_n_pow: L,
    /// The thermal factor at θ_n (1 for Voce).
    thermal: L,
}

/// Thermal factor (JC: 1 − θ*^M) below which a point is returned as molten
/// (`return_principal::molten`): the shear stress it could still carry, under 1e-6 of its
/// cold flow stress, is dropped. The 4×4 Newton return loses digits below it (Al 7075-T6
/// sheared 5 %: Δα off by 3e-5 at a factor of 1e-8, no convergence at 1e-9 to 1e-11).
pub const MOLTEN_THERMAL_FACTOR: f64 = 1e-6;

impl Onset {
    /// Whether the flow stress is negligible for every increment: θ_n at or within
    /// `MOLTEN_THERMAL_FACTOR` of the melting temperature.
    pub fn is_molten(&self) -> bool {
        self.thermal < MOLTEN_THERMAL_FACTOR
    }
}

impl FlowStress<f64> {
    /// τ_y(α_n, 0, θ_n) at `alpha_n` and `theta` [K] (reference temperature `theta0`), of
    /// one point or a point per lane. Every point takes it at every step: in lanes JC's two
    /// powers are the vectorized x^y (`elementary`), four points for about the cost of one
    /// library `powf`.
    pub fn onset<L: Lane>(&self, alpha_n: L, theta: L, theta0: f64) -> Onset<L> {
        let p = match self {
            FlowStress::JohnsonCook(p) => p,
            FlowStress::Voce(_) | FlowStress::Composed(_) => {
                return Onset::pack(|i| {
                    self.onset_athermal_law(alpha_n.extract(i), theta.extract(i), theta0)
                });
            }
        };
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let theta_star = (theta - L::splat(theta0)) / L::splat(p.theta_m - theta0);
        // 1 − θ*^M with θ* clamped to [0, 1], as `softening::johnson_cook`; the powers only
        // where a lane needs them (a virgin point at θ0 needs neither).
        let warming = theta_star.simd_gt(zero);
        let thermal = match warming.any() {
            true => {
                let warm = one - theta_star.simd_clamp(zero, one).powf_v(L::splat(p.m));
                select(warming, select(theta_star.simd_ge(one), zero, warm), one)
            }
            false => one,
        };
        let hardened = alpha_n.simd_gt(zero);
        let power = match hardened.any() {
            true => select(hardened, alpha_n.powf_v(L::splat(p.n)), zero),
            false => zero,
        };
        Onset {
            tau_y0: (L::splat(p.a) + L::splat(p.b) * power) * thermal,
            alpha_n,
            alpha_n_pow: power,
            thermal,
        }
    }

    /// The onset of a Voce or composed law, whose hardening is not a power of α.
    fn onset_athermal_law(&self, alpha_n: f64, theta: f64, theta0: f64) -> Onset {
        let thermal = self.thermal_factor(theta, theta0);
        Onset {
            tau_y0: self.tau_y_athermal(alpha_n, 0.0) * thermal,
            alpha_n,
            alpha_n_pow: 0.0,
            thermal,
        }
    }
}

impl<L: Lane> Onset<L> {
    /// The onsets of the points of a batch, lane `i` from `point(i)`.
    pub fn pack(point: impl Fn(usize) -> Onset) -> Self {
        Onset {
            tau_y0: pack(|i| point(i).tau_y0),
            alpha_n: pack(|i| point(i).alpha_n),
            alpha_n_pow: pack(|i| point(i).alpha_n_pow),
            thermal: pack(|i| point(i).thermal),
        }
    }

    /// The onset of the point in lane `i`.
    pub fn lane(&self, i: usize) -> Onset {
        Onset {
            tau_y0: self.tau_y0.extract(i),
            alpha_n: self.alpha_n.extract(i),
            alpha_n_pow: self.alpha_n_pow.extract(i),
            thermal: self.thermal.extract(i),
        }
    }
}

/// The flow stress along the local solve of one return, in u = ln Δα
/// (`plasticity::return_principal`'s hot path): α = α_n + e^u, α̇ = e^u/Δt and θ = θ_n frozen, so the
/// thermal factor is given once and the JC rate term 1 + C (u − ln(Δt α̇0)) needs no
/// logarithm. `at` equals `FlowStress::tau_y` to round-off (tested). Lane by lane for a
/// batch of points with one law and one Δt.
#[derive(Debug, Clone, Copy)]
pub struct LogIncrementPath<'a, L = f64> {
    flow: &'a FlowStress<f64>,
    alpha_n: L,
    /// ln(Δt α̇0), the JC rate kink (0 for Voce).
    ln_dalpha0: f64,
    /// The step Δt [s].
    dt: f64,
    /// The thermal factor at θ_n.
    thermal: L,
    /// α^N = α_n^N (1 + x)^N with x = Δα/α_n, by its binomial series where that is exact.
    power: SeriesPower<L>,
}

/// Terms of the binomial series after the constant one.
const SERIES_TERMS: usize = 10;

/// 1/k for k = 1..=11: the binomial coefficients without divisions (one per local solve).
const INV_COUNT: [f64; SERIES_TERMS + 1] = [
    1.0,
    1.0 / 2.0,
    1.0 / 3.0,
    1.0 / 4.0,
    1.0 / 5.0,
    1.0 / 6.0,
    1.0 / 7.0,
    1.0 / 8.0,
    1.0 / 9.0,
    1.0 / 10.0,
    1.0 / 11.0,
];

/// α^N near α_n > 0 by its binomial series, exact to round-off: the series is used where
/// its first omitted term, which bounds the remainder for N < 11 (Lagrange form), is below
/// half an ulp: Δα/α_n up to 0.05 at N = 0.31. A plastic step of a point in flow has
/// Δα/α_n ~ 1e-4..1e-2, so `powf` is left for first yield and the first steps of flow.
#[derive(Debug, Clone, Copy)]
struct SeriesPower<L> {
    alpha_n: L,
    alpha_n_inv: L,
    /// α_n^N (0 where the series is not used).
    alpha_n_pow: L,
    /// Binomial coefficients (N choose k), k = 1..=10.
    coefficients: [f64; SERIES_TERMS],
    /// |N choose 11|, the first omitted coefficient (infinite where the series is not
    /// used).
    omitted: L,
}

impl<L: Lane> SeriesPower<L> {
    /// The series about `alpha_n` with `alpha_n_pow` = α_n^N.
    fn new(alpha_n: L, alpha_n_pow: L, n: f64) -> Self {
        let mut coefficients = [0.0; SERIES_TERMS];
        let mut c = 1.0;
        for (k, slot) in coefficients.iter_mut().enumerate() {
            c *= (n - k as f64) * INV_COUNT[k];
            *slot = c;
        }
        let omitted = if n < (SERIES_TERMS + 1) as f64 {
            (c * (n - SERIES_TERMS as f64) * INV_COUNT[SERIES_TERMS]).abs()
        } else {
            f64::INFINITY
        };
        let usable = alpha_n.simd_gt(L::splat(0.0));
        SeriesPower {
            alpha_n,
            alpha_n_inv: L::splat(1.0) / alpha_n,
            alpha_n_pow,
            coefficients,
            omitted: select(usable, L::splat(omitted), L::splat(f64::INFINITY)),
        }
    }

    /// Where the series is exact to round-off at x = Δα/α_n ≥ 0.
    fn converged(&self, x: L) -> Mask<L> {
        let x2 = x * x;
        let x4 = x2 * x2;
        let x11 = x4 * x4 * x2 * x;
        (self.omitted * x11).simd_le(L::splat(0.5 * f64::EPSILON))
    }

    /// α^N at α = α_n + `dalpha`.
    fn at(&self, dalpha: L, n: f64) -> L {
        let x = dalpha * self.alpha_n_inv;
        let converged = self.converged(x);
        let series = || {
            let tail = self
                .coefficients
                .iter()
                .rev()
                .fold(L::splat(0.0), |acc, &c| (acc + L::splat(c)) * x);
            self.alpha_n_pow * (L::splat(1.0) + tail)
        };
        let power = || (self.alpha_n + dalpha).powf_v(L::splat(n));
        if converged.all() {
            series()
        } else if converged.none() {
            power()
        } else {
            select(converged, series(), power())
        }
    }
}

impl<'a, L: Lane> LogIncrementPath<'a, L> {
    /// The path from the `onset` state over a step `dt` [s].
    pub fn new(flow: &'a FlowStress<f64>, onset: &Onset<L>, dt: f64) -> Self {
        let (ln_dalpha0, n) = match flow {
            FlowStress::JohnsonCook(p) => ((dt * p.alpha_dot0).ln(), p.n),
            FlowStress::Voce(_) | FlowStress::Composed(_) => (0.0, f64::INFINITY),
        };
        LogIncrementPath {
            flow,
            alpha_n: onset.alpha_n,
            ln_dalpha0,
            dt,
            thermal: onset.thermal,
            power: SeriesPower::new(onset.alpha_n, onset.alpha_n_pow, n),
        }
    }

    /// Δα, τ_y and dτ_y/du at u = ln Δα.
    pub fn at(&self, u: L) -> AtIncrement<L> {
        let dalpha = u.exp_v();
        let alpha = self.alpha_n + dalpha;
        let (tau_y, dtau_y_du) = match self.flow {
            FlowStress::Voce(p) => {
                let decay = L::splat(p.tau0 - p.tau_inf) * (L::splat(-p.eta) * alpha).exp_v();
                (
                    L::splat(p.tau_inf) + decay + L::splat(p.h) * alpha,
                    dalpha * (L::splat(p.h) - L::splat(p.eta) * decay),
                )
            }
            FlowStress::JohnsonCook(p) => {
                let alpha_pow_n = self.power.at(dalpha, p.n);
                let hardening = L::splat(p.a) + L::splat(p.b) * alpha_pow_n;
                let d_hardening = L::splat(p.b * p.n) * alpha_pow_n / alpha * dalpha;
                let excess = u - L::splat(self.ln_dalpha0);
                let flowing = excess.simd_gt(L::splat(0.0));
                let one = L::splat(1.0);
                let rate = select(flowing, one + L::splat(p.c) * excess, one);
                let d_rate = select(flowing, L::splat(p.c), L::splat(0.0));
                (
                    hardening * rate * self.thermal,
                    (d_hardening * rate + hardening * d_rate) * self.thermal,
                )
            }
            FlowStress::Composed(law) => {
                let (mut tau_y, mut dtau_y_du) = (u, u);
                for i in 0..L::LANES {
                    let (value, slope) = law.along_increment(
                        self.alpha_n.extract(i),
                        u.extract(i),
                        self.dt,
                        self.thermal.extract(i),
                    );
                    tau_y.replace(i, value);
                    dtau_y_du.replace(i, slope);
                }
                (tau_y, dtau_y_du)
            }
        };
        AtIncrement {
            dalpha,
            tau_y,
            dtau_y_du,
        }
    }

    /// The u = ln Δα at which the JC rate term alone takes up the overstress ratio
    /// q/τ_y0 > 1 of a trial state (τ_y0 = τ_y(α_n, 0, θ_n)): 1 + C (u − ln(Δt α̇0)) = q/τ_y0.
    /// Hardening and the elastic relaxation q − 3G̃ Δα only lower the root of the return,
    /// so this bounds its ln Δα from above. `None` for a law without a rate term.
    pub fn rate_only_bound(&self, overstress: L) -> Option<L> {
        match self.flow {
            FlowStress::JohnsonCook(p) if p.c > 0.0 => {
                Some(L::splat(self.ln_dalpha0) + (overstress - L::splat(1.0)) / L::splat(p.c))
            }
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elementary::Elementary;
    use num_dual::Dual64;

    #[test]
    fn log_increment_path_matches_tau_y_and_its_derivative() {
        let laws = [
            FlowStress::JohnsonCook(JohnsonCookLaw {
                a: 800e6,
                b: 1500e6,
                n: 0.3,
                c: 0.03,
                m: 1.2,
                alpha_dot0: 1e-3,
                theta_m: 1800.0,
            }),
            FlowStress::Voce(Voce {
                tau0: 300e6,
                tau_inf: 450e6,
                eta: 12.0,
                h: 1e8,
            }),
            FlowStress::Composed(composed::tests::huh_kang_power_voce()),
            FlowStress::Composed(composed::tests::cowper_symonds_exponential()),
        ];
        let (alpha_n, dt, theta, theta0) = (0.05, 1e-5, 400.0, 293.15);
        for law in &laws {
            let along = LogIncrementPath::new(law, &law.onset(alpha_n, theta, theta0), dt);
            let dual = law.map(|_, v| Dual64::from(v));
            // Below and above the rate kink Δα = Δt α̇0 = 1e-8.
            for dalpha in [1e-10, 3e-9, 2e-8, 1e-4, 0.05] {
                let u = f64::ln(dalpha);
                let at = along.at(u);
                assert_eq!(at.dalpha, u.exp_v());
                let (tau, dtau_du) = (at.tau_y, at.dtau_y_du);
                let d = Dual64::new(dalpha, dalpha); // d/du of e^u
                let expected = dual.tau_y(
                    Dual64::from(alpha_n) + d,
                    d / dt,
                    Dual64::from(theta),
                    Dual64::from(theta0),
                );
                assert!(
                    (tau / expected.re - 1.0).abs() < 1e-13,
                    "τ_y {tau} vs {}",
                    expected.re
                );
                assert!(
                    (dtau_du - expected.eps).abs() <= 1e-9 * expected.eps.abs() + 1e-6,
                    "dτ_y/du {dtau_du} vs {}",
                    expected.eps
                );
            }
        }
    }

    /// The binomial series of α^N agrees with `powf` to 2 ulp wherever it is used, and is
    /// used up to Δα/α_n = 0.02 for exponents of real JC cards and beyond.
    #[test]
    fn series_power_is_exact_to_round_off() {
        for n in [0.09, 0.31, 0.5, 0.83, 1.0, 1.7] {
            let power = SeriesPower::<f64>::new(1.0, 1.0, n);
            assert!(power.converged(0.02), "N {n}: series not used at 0.02");
            for alpha_n in [1e-3, 0.05, 1.2] {
                let power = SeriesPower::<f64>::new(alpha_n, alpha_n.powf(n), n);
                for x in [1e-9, 1e-6, 1e-4, 1e-3, 0.01, 0.02, 0.04, 0.08, 0.3] {
                    let dalpha = x * alpha_n;
                    let exact = (alpha_n + dalpha).powf(n);
                    let err = (power.at(dalpha, n) / exact - 1.0).abs();
                    assert!(
                        err <= 2.0 * f64::EPSILON,
                        "N {n}, α_n {alpha_n}, x {x:e}: {err:e}"
                    );
                }
            }
        }
        let virgin = SeriesPower::<f64>::new(0.0, 0.0, 0.31);
        assert_eq!(virgin.at(1e-4, 0.31), 1e-4f64.powf(0.31));
    }

    /// The rate-only increment bounds the root of the scalar return q − 3G e^u = τ_y(u)
    /// (found by bisection) from above, for small and large overstress.
    #[test]
    fn log_increment_bound_lies_above_the_scalar_return() {
        let law = FlowStress::JohnsonCook(JohnsonCookLaw {
            a: 90e6,
            b: 292e6,
            n: 0.31,
            c: 0.025,
            m: 1.09,
            alpha_dot0: 1.0,
            theta_m: 1356.0,
        });
        let (alpha_n, dt, theta, theta0, three_g) = (0.05, 3e-8, 400.0, 293.15, 3.0 * 46e9);
        let onset = law.onset(alpha_n, theta, theta0);
        let along = LogIncrementPath::new(&law, &onset, dt);
        let tau_y0 = law.tau_y(alpha_n, 0.0, theta, theta0);
        assert!((onset.tau_y0 / tau_y0 - 1.0).abs() < 1e-15);
        for overstress in [1.001, 1.05, 1.3, 3.0] {
            let q = overstress * tau_y0;
            let f = |u: f64| q - three_g * u.exp() - along.at(u).tau_y;
            let (mut below, mut above) = (-60.0, (q / three_g).ln());
            assert!(f(below) > 0.0 && f(above) < 0.0);
            for _ in 0..200 {
                let mid = 0.5 * (below + above);
                if f(mid) > 0.0 {
                    below = mid;
                } else {
                    above = mid;
                }
            }
            let bound = along
                .rate_only_bound(overstress)
                .expect("JC has a rate term");
            assert!(
                below <= bound,
                "q/τ_y0 = {overstress}: root {below} above bound {bound}"
            );
        }
        let voce = FlowStress::Voce(Voce {
            tau0: 300e6,
            tau_inf: 450e6,
            eta: 12.0,
            h: 1e8,
        });
        let voce_path = LogIncrementPath::new(&voce, &voce.onset(alpha_n, theta, theta0), dt);
        assert_eq!(voce_path.rate_only_bound(1.1), None);
    }
}
