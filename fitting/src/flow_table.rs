//! A flow-stress law sampled for a solver's table: yield stress σ_y at nodes of plastic
//! strain ε_p × plastic strain rate ε̇_p × temperature θ, which a code interpolates
//! linearly between nodes (Abaqus `*PLASTIC, RATE=` blocks, LS-DYNA `*DEFINE_TABLE` of
//! curves).
//!
//! The laws of `materials::flow_stress` are products g(ε_p) · R(ε̇_p) · T(θ), so each axis
//! is sampled on its own: an interval is halved (in ε_p and θ; geometrically in ε̇_p) until
//! linear interpolation of its factor stays within a third of the tolerance at the quarter
//! points of every interval. The factor errors add to first order, so the table
//! interpolated trilinearly stays within `tolerance` of the law, measured as a fraction of
//! the law's flow stress at the same strain and rate and the reference temperature θ0
//! (near melting the flow stress itself goes to zero). Rates are sampled so that linear
//! interpolation in the rate and in its logarithm both meet the tolerance, whichever a code
//! uses. `FlowTable::worst_error` checks the finished table against the law off its nodes.
//!
//! Outside its nodes a code holds the table constant: beyond the last strain the material
//! flows without hardening, beyond the last rate or temperature at the last curve.

use anyhow::{bail, Result};
use materials::FlowStress;

/// Where and how finely to sample.
#[derive(Debug, Clone, Copy)]
pub struct TableRange {
    /// Largest plastic strain [-].
    pub strain_max: f64,
    /// Lowest and highest positive plastic strain rate [1/s]; the table starts at rate 0.
    pub rates: [f64; 2],
    /// Lowest and highest temperature [K] (equal: one temperature).
    pub temperatures: [f64; 2],
    /// Largest error of the interpolated table, as a fraction of the cold flow stress.
    pub tolerance: f64,
}

/// The sampled law: `stress[t][r][s]` at `temperatures[t]`, `rates[r]`, `strains[s]`.
#[derive(Debug, Clone)]
pub struct FlowTable {
    pub strains: Vec<f64>,
    /// Plastic strain rates [1/s], the first 0.
    pub rates: Vec<f64>,
    pub temperatures: Vec<f64>,
    /// Yield stress [Pa].
    pub stress: Vec<Vec<Vec<f64>>>,
}

/// How a code interpolates between two rate curves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RateInterpolation {
    Linear,
    Logarithmic,
}

/// Halvings of an interval at most, past which sampling gives up (2⁻⁴⁰ of the range).
const MAX_DEPTH: usize = 40;

impl FlowTable {
    /// `flow` (reference temperature `theta0`) sampled over `range`.
    pub fn sample(flow: &FlowStress, theta0: f64, range: &TableRange) -> Result<FlowTable> {
        check(range, theta0)?;
        let axis_tolerance = range.tolerance / 3.0;
        let strain_ref = 0.5 * range.strain_max;
        let hardening = |e: f64| flow.tau_y(e, 0.0, theta0, theta0);
        let cold = flow.tau_y(strain_ref, 0.0, theta0, theta0);
        let rate = |r: f64| flow.tau_y(strain_ref, r, theta0, theta0) / cold;
        let thermal = |t: f64| flow.tau_y(strain_ref, 0.0, t, theta0) / cold;
        let relative = |a: f64, b: f64| (a - b).abs() / b.abs();
        let strains = nodes(
            &hardening,
            [0.0, range.strain_max],
            Split::Arithmetic,
            false,
            relative,
            axis_tolerance,
        )?;
        let low = lowest_rate(&rate, range.rates[0], axis_tolerance)?;
        let positive = nodes(
            &rate,
            [low, range.rates[1]],
            Split::Geometric,
            true,
            relative,
            axis_tolerance,
        )?;
        let rates: Vec<f64> = [0.0].into_iter().chain(positive).collect();
        let temperatures = if range.temperatures[0] == range.temperatures[1] {
            vec![range.temperatures[0]]
        } else {
            let absolute = |a: f64, b: f64| (a - b).abs();
            let (t, split) = (range.temperatures, Split::Arithmetic);
            nodes(&thermal, t, split, false, absolute, axis_tolerance)?
        };
        let stress = (temperatures.iter())
            .map(|&t| {
                (rates.iter())
                    .map(|&r| {
                        strains
                            .iter()
                            .map(|&e| flow.tau_y(e, r, t, theta0))
                            .collect()
                    })
                    .collect()
            })
            .collect();
        Ok(FlowTable {
            strains,
            rates,
            temperatures,
            stress,
        })
    }

    /// The table interpolated at (ε_p, ε̇_p, θ), held constant outside its nodes, rates
    /// interpolated by `mode` (logarithmic from the first positive rate; rate 0 to it
    /// linearly).
    pub fn interpolate(&self, strain: f64, rate: f64, theta: f64, mode: RateInterpolation) -> f64 {
        let (s0, s1, ws) = bracket(&self.strains, strain, |x| x);
        let log = |x: f64| if x > 0.0 { x.ln() } else { f64::NEG_INFINITY };
        let (r0, r1, wr) = match mode {
            RateInterpolation::Logarithmic if rate > self.rates[1] => {
                bracket(&self.rates, rate, log)
            }
            _ => bracket(&self.rates, rate, |x| x),
        };
        let (t0, t1, wt) = bracket(&self.temperatures, theta, |x| x);
        let at = |t: usize, r: usize| {
            let row = &self.stress[t][r];
            row[s0] + ws * (row[s1] - row[s0])
        };
        let at_t = |t: usize| at(t, r0) + wr * (at(t, r1) - at(t, r0));
        at_t(t0) + wt * (at_t(t1) - at_t(t0))
    }

    /// The worst error of the interpolated table against `flow` at the quarter points of
    /// every interval of each axis (and every node of the others), as a fraction of the
    /// law's flow stress at that strain and rate and θ0, over both rate interpolations.
    pub fn worst_error(&self, flow: &FlowStress, theta0: f64) -> f64 {
        let between = |nodes: &[f64], geometric: bool| -> Vec<f64> {
            let mut points = nodes.to_vec();
            for w in nodes.windows(2) {
                for q in [0.25, 0.5, 0.75] {
                    points.push(match geometric && w[0] > 0.0 {
                        true => w[0] * (w[1] / w[0]).powf(q),
                        false => w[0] + q * (w[1] - w[0]),
                    });
                }
            }
            points
        };
        let strains = between(&self.strains, false);
        let mut rates = between(&self.rates, true);
        rates.extend(between(&self.rates, false));
        let temperatures = between(&self.temperatures, false);
        let mut worst = 0.0f64;
        for &t in &temperatures {
            for &r in &rates {
                for &e in &strains {
                    let law = flow.tau_y(e, r, t, theta0);
                    let scale = flow.tau_y(e, r, theta0, theta0);
                    for mode in [RateInterpolation::Linear, RateInterpolation::Logarithmic] {
                        let error = (self.interpolate(e, r, t, mode) - law).abs() / scale;
                        worst = worst.max(error);
                    }
                }
            }
        }
        worst
    }
}

fn check(range: &TableRange, theta0: f64) -> Result<()> {
    let [r_lo, r_hi] = range.rates;
    let [t_lo, t_hi] = range.temperatures;
    if !(range.strain_max > 0.0 && range.strain_max <= 100.0) {
        bail!(
            "table strain range: largest plastic strain {} is not in (0, 100]",
            range.strain_max
        );
    }
    if !(r_lo > 0.0 && r_hi > r_lo && r_hi.is_finite()) {
        bail!("table rate range: [{r_lo:e}, {r_hi:e}] 1/s must be positive and rising");
    }
    if !(t_lo > 0.0 && t_hi >= t_lo && t_hi.is_finite()) {
        bail!("table temperature range: [{t_lo}, {t_hi}] K must be positive and not falling");
    }
    if !(t_lo <= theta0 || t_lo == t_hi) {
        bail!("table temperature range: [{t_lo}, {t_hi}] K must contain the reference temperature {theta0} K");
    }
    if !(range.tolerance > 1e-6 && range.tolerance < 0.1) {
        bail!("table tolerance {} is not in (1e-6, 0.1)", range.tolerance);
    }
    Ok(())
}

/// How an interval is halved: at its middle, or (rates, over many decades) at its
/// geometric middle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Split {
    Arithmetic,
    Geometric,
}

/// Nodes on `range`, halved by `split`, such that linear interpolation of `f` between
/// them stays within `tolerance` of `f` at the quarter points of each interval, measured
/// by `error(interpolated, exact)`: in x, and where `also_in_log`, in ln x as well.
fn nodes(
    f: &dyn Fn(f64) -> f64,
    range: [f64; 2],
    split: Split,
    also_in_log: bool,
    error: impl Fn(f64, f64) -> f64,
    tolerance: f64,
) -> Result<Vec<f64>> {
    let middle = |a: f64, b: f64, q: f64| match split {
        Split::Arithmetic => a + q * (b - a),
        Split::Geometric => a * (b / a).powf(q),
    };
    let within = |a: f64, b: f64| {
        let (fa, fb) = (f(a), f(b));
        [0.25, 0.5, 0.75].iter().all(|&q| {
            let x = middle(a, b, q);
            let exact = f(x);
            let linear = (x - a) / (b - a);
            let in_log = also_in_log.then(|| (x / a).ln() / (b / a).ln());
            [Some(linear), in_log]
                .into_iter()
                .flatten()
                .all(|w| error(fa + w * (fb - fa), exact) <= tolerance)
        })
    };
    let mut out = vec![range[0]];
    let mut stack = vec![(range[0], range[1], 0usize)];
    // depth first, left interval first, so that nodes come out in order
    while let Some((a, b, depth)) = stack.pop() {
        if within(a, b) {
            out.push(b);
        } else if depth >= MAX_DEPTH {
            bail!("the law cannot be tabulated within {tolerance:e} between {a:e} and {b:e}: it changes too fast there");
        } else {
            let mid = middle(a, b, 0.5);
            stack.push((mid, b, depth + 1));
            stack.push((a, mid, depth + 1));
        }
    }
    Ok(out)
}

/// The first positive rate of the table: the lowest asked for, lowered by decades until
/// the rate factor there is within `tolerance` of its value at rate 0, so that the linear
/// segment from 0 to it holds the law (a power of the rate rises steeply from 0).
fn lowest_rate(rate: &dyn Fn(f64) -> f64, asked: f64, tolerance: f64) -> Result<f64> {
    let at_zero = rate(0.0);
    let mut low = asked;
    for _ in 0..40 {
        if (rate(low) - at_zero).abs() <= tolerance * at_zero {
            return Ok(low);
        }
        low /= 10.0;
    }
    bail!("the rate factor rises by more than {tolerance:e} below {low:e} 1/s: it cannot be tabulated from rate 0")
}

/// The nodes around `x` (held at the ends) and the weight of the upper one, in the
/// coordinate `map`.
fn bracket(nodes: &[f64], x: f64, map: impl Fn(f64) -> f64) -> (usize, usize, f64) {
    let last = nodes.len() - 1;
    if last == 0 || x <= nodes[0] {
        return (0, 0, 0.0);
    }
    if x >= nodes[last] {
        return (last, last, 0.0);
    }
    let upper = nodes.partition_point(|&n| n <= x).min(last);
    let lower = upper - 1;
    let (a, b) = (map(nodes[lower]), map(nodes[upper]));
    (lower, upper, (map(x) - a) / (b - a))
}

#[cfg(test)]
mod tests {
    use super::*;
    use materials::flow_stress::{FlowStress, JohnsonCookLaw};

    /// A piecewise-linear function is tabulated at its kinks and interpolated exactly.
    #[test]
    fn nodes_and_brackets_reproduce_a_linear_function() {
        let f = |x: f64| 2.0 * x + 1.0;
        let error = |a: f64, b: f64| (a - b).abs();
        let n = nodes(&f, [0.0, 4.0], Split::Arithmetic, false, error, 1e-12).unwrap();
        assert_eq!(n, [0.0, 4.0]);
        assert_eq!(bracket(&[0.0, 1.0, 3.0], 2.0, |x| x), (1, 2, 0.5));
        assert_eq!(bracket(&[0.0, 1.0, 3.0], 5.0, |x| x), (2, 2, 0.0));
    }

    /// JC and composed laws (a power of the rate from 0, exponential softening, a hardening
    /// exponent of 0.3 with its infinite slope at 0) over 1e-4..1e5 1/s and 293-1200 K:
    /// within tolerance everywhere, with node counts a card can carry.
    #[test]
    fn tables_of_every_kind_of_law_meet_their_tolerance() {
        use materials::flow_stress::hardening::{Hardening, Power, PowerVoce};
        use materials::flow_stress::rate::{CowperSymonds, HuhKang, RateSensitivity};
        use materials::flow_stress::softening::{ExponentialSoftening, ThermalSoftening};
        use materials::flow_stress::Composed;
        let laws = [
            FlowStress::JohnsonCook(JohnsonCookLaw {
                a: 801e6,
                b: 1531e6,
                n: 0.81,
                c: 0.036,
                m: 1.48,
                alpha_dot0: 5.6e-5,
                theta_m: 1793.15,
            }),
            FlowStress::Composed(Composed {
                hardening: Hardening::Power(Power {
                    a: 293e6,
                    b: 1090e6,
                    n: 0.3,
                }),
                rate: RateSensitivity::CowperSymonds(CowperSymonds { d: 3.3e6, p: 7.0 }),
                softening: ThermalSoftening::Exponential(ExponentialSoftening {
                    lambda: 1.2e-3,
                    theta_m: 1673.0,
                }),
            }),
            FlowStress::Composed(Composed {
                hardening: Hardening::PowerVoce(PowerVoce {
                    a: 250e6,
                    b: 900e6,
                    n: 0.7,
                    q: 150e6,
                    beta: 25.0,
                }),
                rate: RateSensitivity::HuhKang(HuhKang {
                    c: 0.004,
                    c2: 0.0008,
                    alpha_dot0: 1e-4,
                }),
                softening: ThermalSoftening::None,
            }),
        ];
        let range = TableRange {
            strain_max: 2.0,
            rates: [1e-4, 1e5],
            temperatures: [293.15, 1200.0],
            tolerance: 5e-3,
        };
        for flow in &laws {
            let table = FlowTable::sample(flow, 293.15, &range).unwrap();
            let worst = table.worst_error(flow, 293.15);
            let counts = (
                table.strains.len(),
                table.rates.len(),
                table.temperatures.len(),
            );
            assert!(
                worst <= range.tolerance,
                "{}: worst {worst:e}, {counts:?}",
                flow.describe()
            );
            assert!(
                counts.0 < 300 && counts.1 < 100 && counts.2 < 50,
                "{}: {counts:?}",
                flow.describe()
            );
            eprintln!("{}: {counts:?} nodes, worst {worst:.2e}", flow.describe());
            // the check can fail: every other strain node dropped breaks the tolerance
            let mut coarse = table.clone();
            let keep = |i: usize, n: usize| i.is_multiple_of(2) || i + 1 == n;
            let n = coarse.strains.len();
            coarse.strains = (0..n)
                .filter(|&i| keep(i, n))
                .map(|i| table.strains[i])
                .collect();
            for rows in &mut coarse.stress {
                for row in rows.iter_mut() {
                    *row = (0..n).filter(|&i| keep(i, n)).map(|i| row[i]).collect();
                }
            }
            let coarse_worst = coarse.worst_error(flow, 293.15);
            assert!(
                coarse_worst > range.tolerance,
                "{}: coarse {coarse_worst:e}",
                flow.describe()
            );
        }
    }
}
