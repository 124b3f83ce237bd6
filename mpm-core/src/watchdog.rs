//! Checks that stop a run which has gone bad before its numbers are reported, beside the
//! NaN, det F ≤ 0 and energy blow-up checks of the solver (DESIGN 6.6):
//!
//! - speed: no point of a solid moves faster than 2 (v_ref + |b| t) + c_max by the time t,
//!   with v_ref the fastest prescribed or initial speed [m/s], b the body force [m/s²]
//!   (free fall adds |b| t) and c_max the largest dilatational wave speed [m/s] (behind a
//!   wave the particle velocity is σ/(ρ c) < c for any stress a solid carries);
//! - escape: no point is farther from the initial bounding box of the points than the
//!   box's diagonal plus ten cells plus the travel 2 v_ref t + |b| t²/2 that the
//!   prescribed speeds and the body force b allow by the time t;
//! - energy: the energy error K + W_int − (K0 + W_ext + W_bc) stays below a fraction of
//!   the energy supplied (an unstable rim gains energy long before it blows up).
//!
//! A 3D Taylor bar whose rim went unstable (rim points 100 mm away at 37 km/s,
//! energy error from 0.8 J to 217 J) trips all three.

use crate::failure::Cause;
use nalgebra::SVector;

/// What a point may have reached by a given time.
#[derive(Debug, Clone, Copy)]
pub struct Bounds {
    /// Speed [m/s].
    pub speed: f64,
    /// Distance from the initial bounding box [m].
    pub reach: f64,
}

#[derive(Debug, Clone)]
pub struct Watchdog<const D: usize> {
    /// Largest dilatational wave speed c_max [m/s].
    pub c_max: f64,
    /// Initial bounding box of the points [m].
    pub lo: SVector<f64, D>,
    pub hi: SVector<f64, D>,
    /// Distance from that box allowed at t = 0 [m].
    pub reach: f64,
    /// v_ref [m/s] and |b| [m/s²] for the travel allowed by the time t.
    pub v_ref: f64,
    pub body_force: f64,
    /// Largest allowed energy error as a fraction of the energy supplied [-].
    pub energy_error_fraction: f64,
}

impl<const D: usize> Watchdog<D> {
    /// From the initial points, the cell size `h` [m], the fastest prescribed or initial
    /// speed `v_ref` [m/s], the largest wave speed `c_max` [m/s] and the body force |b|
    /// [m/s²].
    pub fn new(
        positions: &[SVector<f64, D>],
        h: f64,
        (v_ref, c_max, body_force): (f64, f64, f64),
        energy_error_fraction: f64,
    ) -> Self {
        let start = (
            SVector::<f64, D>::repeat(f64::INFINITY),
            SVector::<f64, D>::repeat(f64::NEG_INFINITY),
        );
        let (lo, hi) = positions
            .iter()
            .fold(start, |(lo, hi), x| (lo.inf(x), hi.sup(x)));
        Watchdog {
            c_max,
            lo,
            hi,
            reach: (hi - lo).norm() + 10.0 * h,
            v_ref,
            body_force,
            energy_error_fraction,
        }
    }

    /// The speed [m/s] and the distance from the initial box [m] a point may have reached
    /// by the time `t`.
    pub fn bounds_at(&self, t: f64) -> Bounds {
        Bounds {
            speed: 2.0 * (self.v_ref + self.body_force * t) + self.c_max,
            reach: self.reach + 2.0 * self.v_ref * t + 0.5 * self.body_force * t * t,
        }
    }

    /// Whether a point at `x` moving at `v` is faster or farther from the initial box than
    /// `bounds` (from `bounds_at`) allow. Called from the solver's per-point position
    /// update, which already visits every point in parallel.
    #[inline]
    pub fn check_point(
        &self,
        x: &SVector<f64, D>,
        v: &SVector<f64, D>,
        bounds: Bounds,
    ) -> Option<Cause> {
        // squared lengths against squared limits: no square root for a point within them
        if v.norm_squared() > bounds.speed * bounds.speed {
            return Some(Cause::SpeedLimit {
                speed: v.norm(),
                limit: bounds.speed,
            });
        }
        let outside = x - x.sup(&self.lo).inf(&self.hi);
        (outside.norm_squared() > bounds.reach * bounds.reach).then(|| Cause::Escaped {
            distance: outside.norm(),
            limit: bounds.reach,
        })
    }

    /// Energy error [J] against the energy supplied [J].
    pub fn check_energy(&self, error: f64, supplied: f64) -> Option<Cause> {
        let limit = self.energy_error_fraction * supplied;
        (supplied > 0.0 && error > limit).then_some(Cause::EnergyError { error, limit })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    fn dog() -> Watchdog<2> {
        let x = [Vector2::new(0.0, 0.0), Vector2::new(3.0, 4.0)];
        Watchdog::new(&x, 0.1, (10.0, 100.0, 0.0), 0.25)
    }

    #[test]
    fn limits_follow_from_the_scene() {
        let w = dog();
        assert_eq!(w.bounds_at(0.0).speed, 120.0);
        // diagonal 5 m plus ten 0.1 m cells
        assert_eq!(w.reach, 6.0);
        // a body force of 1000 m/s² adds free fall: 100 m/s by t = 0.1 s, twice over
        let x = [Vector2::new(0.0, 0.0), Vector2::new(3.0, 4.0)];
        let falling = Watchdog::new(&x, 0.1, (10.0, 100.0, 1000.0), 0.25);
        assert_eq!(falling.bounds_at(0.1).speed, 320.0);
    }

    #[test]
    fn a_fast_or_escaped_point_is_caught() {
        let w = dog();
        let (x, still) = (Vector2::new(1.0, 1.0), Vector2::zeros());
        assert!(w.check_point(&x, &still, w.bounds_at(0.0)).is_none());
        let fast = Vector2::new(0.0, 121.0);
        assert!(matches!(
            w.check_point(&x, &fast, w.bounds_at(0.0)),
            Some(Cause::SpeedLimit { .. })
        ));
        // (10, 4) is 7 m beyond the box edge x = 3: farther than 6 m at t = 0
        let far = Vector2::new(10.0, 4.0);
        match w.check_point(&far, &still, w.bounds_at(0.0)) {
            Some(Cause::Escaped { distance, .. }) => assert!((distance - 7.0).abs() < 1e-12),
            other => panic!("{other:?}"),
        }
        // by t = 0.05 s the prescribed 10 m/s allows 1 m more travel
        assert_eq!(w.bounds_at(0.05).reach, 7.0);
        assert!(w.check_point(&far, &still, w.bounds_at(0.05)).is_none());
    }

    #[test]
    fn energy_error_beyond_the_fraction_of_the_supplied_energy_fails() {
        let w = dog();
        assert!(w.check_energy(24.0, 100.0).is_none());
        assert!(w.check_energy(-90.0, 100.0).is_none());
        assert!(matches!(
            w.check_energy(26.0, 100.0),
            Some(Cause::EnergyError { .. })
        ));
    }
}
