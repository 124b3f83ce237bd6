//! A watch for points that reach the melting temperature θm of their material (Johnson-Cook
//! `theta_m`). The thermal factor 1 − θ*^M, θ* = (θ − θ0)/(θm − θ0), falls to zero there,
//! and since the plastic heating is proportional to the flow stress a point approaches θm
//! without quite reaching it; a point counts as molten from θ* ≥ `MOLTEN` (its flow stress
//! below about 1 % of the cold value for M ≈ 1). Such a point carries almost no stress, so
//! the run goes on but its numbers near that point no longer describe a solid. This is
//! almost never the physics of the test; it is too much plastic work in too few points (a
//! contact or wall layer, a free-surface point that has gone unstable) or a material file
//! whose θm or Taylor-Quinney fraction is wrong. The watch checks every observed state
//! (one pass over the points' temperatures) and keeps, per body, when a point first became
//! molten, how many are molten now and at most, and the hottest point.

use crate::solver::observer::{Observer, Verdict, CONTINUE};
use crate::solver::Solver;
use std::fmt;

/// Homologous temperature θ* from which a point counts as molten.
pub const MOLTEN: f64 = 0.99;

/// Points of one body at or above its melting temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct Melting {
    pub body: String,
    /// Melting temperature θm [K] and the temperature θ0 + `MOLTEN` (θm − θ0) from which a
    /// point counts as molten [K].
    pub theta_m: f64,
    pub molten_from: f64,
    /// Step and time [s] of the first state with a molten point.
    pub first_step: usize,
    pub first_time: f64,
    /// Molten points in the last observed state, and at most over the run.
    pub points: usize,
    pub most_points: usize,
    /// The hottest point when most points were molten: its index, temperature [K], position
    /// [m] and equivalent plastic strain α [-].
    pub hottest: usize,
    pub hottest_theta: f64,
    pub hottest_position: Vec<f64>,
    pub hottest_alpha: f64,
}

impl fmt::Display for Melting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let at: Vec<String> = self
            .hottest_position
            .iter()
            .map(|x| format!("{:.4}", x * 1e3))
            .collect();
        write!(
            f,
            "{}: points reached the melting temperature θm = {:.0} K (θ ≥ {:.1} K, where almost no flow stress is left), first at step {} (t = {:.4e} s); {} such point(s) at the end, {} at most; hottest point {} at ({}) mm, θ = {:.1} K, α = {:.3}. They carry no flow stress, so the run near them is not a solid's: usually too much plastic work in too few points (a wall or contact layer; refine, or another shape function), or θm or the Taylor-Quinney fraction of the material file is wrong",
            self.body,
            self.theta_m,
            self.molten_from,
            self.first_step,
            self.first_time,
            self.points,
            self.most_points,
            self.hottest,
            at.join(", "),
            self.hottest_theta,
            self.hottest_alpha,
        )
    }
}

/// An observer that keeps a `Melting` per body with molten points.
#[derive(Debug, Clone, Default)]
pub struct MeltingWatch {
    /// Per body (as `Solver::blocks`), once it has a molten point.
    bodies: Vec<Option<Melting>>,
}

impl MeltingWatch {
    /// The bodies with molten points, in the solver's order.
    pub fn melted(&self) -> Vec<Melting> {
        self.bodies.iter().flatten().cloned().collect()
    }

    /// Look at the current state of every body.
    pub fn check<const D: usize>(&mut self, s: &Solver<D>) {
        self.bodies.resize(s.blocks.len(), None);
        for (b, block) in s.blocks.iter().enumerate() {
            let Some([theta0, theta_m]) = block.material.melting_range() else {
                continue;
            };
            let molten_from = theta0 + MOLTEN * (theta_m - theta0);
            let (count, hottest) =
                block
                    .state
                    .iter()
                    .enumerate()
                    .fold((0, 0), |(count, hottest), (k, st)| {
                        let hotter = st.theta > block.state[hottest].theta;
                        (
                            count + usize::from(st.theta >= molten_from),
                            if hotter { k } else { hottest },
                        )
                    });
            let entry = &mut self.bodies[b];
            if count == 0 {
                if let Some(m) = entry {
                    m.points = 0;
                }
                continue;
            }
            let m = entry.get_or_insert_with(|| Melting {
                body: block.name.clone(),
                theta_m,
                molten_from,
                first_step: s.step,
                first_time: s.time,
                points: 0,
                most_points: 0,
                hottest: 0,
                hottest_theta: f64::NAN,
                hottest_position: Vec::new(),
                hottest_alpha: f64::NAN,
            });
            m.points = count;
            if count >= m.most_points {
                let st = &block.state[hottest];
                let p = block.range.start + hottest;
                m.most_points = count;
                m.hottest = p;
                m.hottest_theta = st.theta;
                m.hottest_position = s.particles.position[p].iter().copied().collect();
                m.hottest_alpha = st.alpha;
            }
        }
    }
}

impl<const D: usize> Observer<D> for MeltingWatch {
    fn observe(&mut self, s: &Solver<D>) -> Verdict {
        self.check(s);
        CONTINUE
    }
}
