//! The shear angle φ_s of an orthogonal cut, measured two ways.
//!
//! From the chip's flow (`from_chip_flow`, Merchant's geometry): continuity through the
//! shear plane gives the chip thickness ratio r = h/h_c = v_c/v, v_c the chip's speed up
//! the rake face relative to the tool and v the cutting speed, and
//! tan φ_s = r cos α / (1 − r sin α), α the rake angle. v_c is the mean, over the chip's
//! points just above the uncut surface (heights between h/4 and h above it) within 3 h in
//! front of the rake face, of their velocity relative to the tool along the rake face.
//! This needs only the chip's motion, not a resolved shear zone.
//!
//! From the chip's thickness (`from_chip_thickness`): the same r = h/h_c with h_c the chip
//! thickness normal to the rake face, the largest distance from the face of the chip's
//! points at heights between h/2 and 3h/2 above the uncut surface (within 4 h of the face;
//! the chip ends at the first gap of more than two point spacings, so that a point thrown
//! off or the chip curling back does not count) plus half a point spacing (each point
//! stands for a square of that side). Continuity
//! makes the two measures one for an incompressible chip that sticks together; where the
//! MPM chip opens gaps between its points, the thickness measure is the larger.
//!
//! From the plastic strain rate field (`shear_angle`, `from_snapshot`):
//! the primary shear zone is the band in which the workpiece ahead of the tool deforms
//! fastest, and it runs from the tool tip up to the free surface at the chip root
//! (Merchant's shear plane). For each trial angle φ the band of half-width `w` around the
//! segment from the tip, direction (−cos φ, sin φ) for a tool moving to −x, up to the
//! uncut surface y = y_s, holds some points; their mean equivalent plastic strain rate is
//! the band's score, and φ_s is the angle of the highest score (searched on a 0.25° grid
//! from 5° to 85°, refined by a parabola through the best three). The contrast — the best
//! score over the median score of all trial angles — says how clear the band is (near 1:
//! no band).

/// A point of the field: position [m] and equivalent plastic strain rate [1/s].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RatePoint {
    pub x: f64,
    pub y: f64,
    pub rate: f64,
}

/// The measured shear angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearAngle {
    /// φ_s from the cutting direction [degrees].
    pub degrees: f64,
    /// Best band score over the median band score [-].
    pub contrast: f64,
}

/// The mean rate of the points within `half_width` of the segment from `tip` along angle
/// `phi` [rad] (tool moving to −x) up to the surface `y_surface`; `None` without points.
fn band_score(
    points: &[RatePoint],
    tip: (f64, f64),
    y_surface: f64,
    phi: f64,
    half_width: f64,
) -> Option<f64> {
    let (dx, dy) = (-phi.cos(), phi.sin());
    let length = (y_surface - tip.1) / dy;
    let (mut sum, mut count) = (0.0, 0usize);
    for p in points {
        let (rx, ry) = (p.x - tip.0, p.y - tip.1);
        let along = rx * dx + ry * dy;
        let across = (rx * dy - ry * dx).abs();
        if (0.0..=length).contains(&along) && across <= half_width {
            sum += p.rate;
            count += 1;
        }
    }
    (count > 0).then(|| sum / count as f64)
}

/// φ_s of the field `points` for a tool tip at `tip` moving to −x under a free surface at
/// `y_surface` (above the tip), bands of half-width `half_width` [m]. `None` when no trial
/// band holds a point.
pub fn shear_angle(
    points: &[RatePoint],
    tip: (f64, f64),
    y_surface: f64,
    half_width: f64,
) -> Option<ShearAngle> {
    let step = 0.25f64;
    let trials: Vec<(f64, f64)> = (0..=320)
        .map(|k| 5.0 + step * k as f64)
        .filter_map(|deg| {
            band_score(points, tip, y_surface, deg.to_radians(), half_width).map(|s| (deg, s))
        })
        .collect();
    let best = (0..trials.len()).max_by(|&a, &b| trials[a].1.total_cmp(&trials[b].1))?;
    let mut degrees = trials[best].0;
    if best > 0 && best + 1 < trials.len() {
        let (a, b, c) = (trials[best - 1].1, trials[best].1, trials[best + 1].1);
        let curvature = a - 2.0 * b + c;
        if curvature < 0.0 {
            degrees += 0.5 * step * (a - c) / curvature;
        }
    }
    let mut scores: Vec<f64> = trials.iter().map(|t| t.1).collect();
    scores.sort_by(f64::total_cmp);
    let median = scores[scores.len() / 2];
    Some(ShearAngle {
        degrees,
        contrast: trials[best].1 / median,
    })
}

/// φ_s from a snapshot of the run (`mpm_core::output::read_snapshot`, its `alpha_rate`):
/// every point of it, for a tool tip at `tip` under the surface `y_surface`.
pub fn from_snapshot(
    snapshot: &mpm_core::output::Snapshot,
    tip: (f64, f64),
    y_surface: f64,
    half_width: f64,
) -> Option<ShearAngle> {
    let rate = snapshot.scalar("alpha_rate")?;
    let points: Vec<RatePoint> = snapshot
        .position
        .iter()
        .zip(rate)
        .map(|(p, &rate)| RatePoint {
            x: p[0],
            y: p[1],
            rate,
        })
        .collect();
    shear_angle(&points, tip, y_surface, half_width)
}

/// The cut's geometry for `from_chip_flow`: tool tip [m], uncut surface y [m], depth of
/// cut h [m], rake angle [degrees], cutting speed v [m/s] (the tool moves to −x).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChipGeometry {
    pub tip: (f64, f64),
    pub y_surface: f64,
    pub depth: f64,
    pub rake_deg: f64,
    pub speed: f64,
}

/// φ_s [degrees] and the chip thickness ratio r from the chip points' velocities
/// (`positions`, `velocities` [m/s]); `None` without chip points moving up the face.
pub fn from_chip_flow(
    positions: &[[f64; 3]],
    velocities: &[[f64; 3]],
    g: &ChipGeometry,
) -> Option<(f64, f64)> {
    let a = g.rake_deg.to_radians();
    // up the rake face, which leans back (to +x) by α from the tip
    let (tx, ty) = (a.sin(), a.cos());
    let face_x = |y: f64| g.tip.0 + (y - g.tip.1) * a.tan();
    let (mut sum, mut count) = (0.0, 0usize);
    for (p, v) in positions.iter().zip(velocities) {
        let above = p[1] - g.y_surface;
        let ahead = face_x(p[1]) - p[0];
        if (0.25 * g.depth..=g.depth).contains(&above) && (0.0..=3.0 * g.depth).contains(&ahead) {
            // velocity relative to the tool, which moves at (−v, 0)
            sum += (v[0] + g.speed) * tx + v[1] * ty;
            count += 1;
        }
    }
    if count == 0 || sum <= 0.0 {
        return None;
    }
    let r = sum / count as f64 / g.speed;
    Some((merchant_angle(r, a), r))
}

/// Merchant's shear angle [degrees] from the chip thickness ratio `r` and the rake angle
/// `rake` [rad]: tan φ_s = r cos α / (1 − r sin α).
fn merchant_angle(r: f64, rake: f64) -> f64 {
    (r * rake.cos()).atan2(1.0 - r * rake.sin()).to_degrees()
}

/// φ_s [degrees], the chip thickness ratio r and the chip thickness h_c [m] from the
/// chip's points (`positions`, a point standing for a square of side `spacing`); `None`
/// without chip points beside the rake face.
pub fn from_chip_thickness(
    positions: &[[f64; 3]],
    g: &ChipGeometry,
    spacing: f64,
) -> Option<(f64, f64, f64)> {
    let a = g.rake_deg.to_radians();
    let face_x = |y: f64| g.tip.0 + (y - g.tip.1) * a.tan();
    let mut from_face: Vec<f64> = positions
        .iter()
        .filter(|p| (0.5 * g.depth..=1.5 * g.depth).contains(&(p[1] - g.y_surface)))
        .map(|p| (face_x(p[1]) - p[0]) * a.cos())
        .filter(|d| (0.0..=4.0 * g.depth).contains(d))
        .collect();
    from_face.sort_by(f64::total_cmp);
    // the chip on the face ends at the first gap of more than two spacings
    let farthest =
        from_face
            .iter()
            .copied()
            .reduce(|last, d| if d - last > 2.0 * spacing { last } else { d })?;
    let thickness = farthest + 0.5 * spacing;
    let r = g.depth / thickness;
    Some((merchant_angle(r, a), r, thickness))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A workpiece 2 mm × 1 mm ahead of a tip at (1 mm, 0.7 mm) under a surface at 1 mm,
    /// points every 20 µm, with a Gaussian band of strain rate (width 60 µm) along a known
    /// angle over a background of rate 1 and noise: the angle comes back within 0.5°.
    fn field(angle_deg: f64, noise: f64) -> Vec<RatePoint> {
        let (tip, phi) = ((1e-3, 0.7e-3), angle_deg.to_radians());
        let (dx, dy) = (-phi.cos(), phi.sin());
        let mut state = 12345u64;
        let mut uniform = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut out = Vec::new();
        for i in 0..100 {
            for j in 0..50 {
                let (x, y) = (i as f64 * 20e-6, j as f64 * 20e-6 + 10e-6);
                let (rx, ry) = (x - tip.0, y - tip.1);
                let across = rx * dy - ry * dx;
                let ahead = rx * dx + ry * dy > 0.0 && y > tip.1;
                let band = if ahead {
                    1e4 * (-(across / 60e-6).powi(2)).exp()
                } else {
                    0.0
                };
                out.push(RatePoint {
                    x,
                    y,
                    rate: 1.0 + band + noise * 1e4 * uniform(),
                });
            }
        }
        out
    }

    #[test]
    fn a_band_at_a_known_angle_is_found() {
        for angle in [15.0, 25.0, 40.0] {
            let found = shear_angle(&field(angle, 0.2), (1e-3, 0.7e-3), 1e-3, 50e-6).unwrap();
            assert!((found.degrees - angle).abs() < 0.5, "{angle}: {found:?}");
            assert!(found.contrast > 2.0, "a clear band: {found:?}");
        }
    }

    /// A tip at (1 mm, 0.7 mm) under a surface at 1 mm, depth of cut 0.3 mm, rake 5°, tool
    /// at 40 m/s.
    const CHIP: ChipGeometry = ChipGeometry {
        tip: (1e-3, 0.7e-3),
        y_surface: 1e-3,
        depth: 0.3e-3,
        rake_deg: 5.0,
        speed: 40.0,
    };

    /// A chip that slides up a 5° rake face at r v relative to the tool (tool at 40 m/s):
    /// r and Merchant's angle come back exactly; points below the surface or behind the
    /// face do not count.
    #[test]
    fn the_chip_flow_gives_merchant_s_angle() {
        let g = CHIP;
        let a = 5f64.to_radians();
        let r = 0.5;
        let chip = [-g.speed + r * g.speed * a.sin(), r * g.speed * a.cos(), 0.0];
        let mut positions = Vec::new();
        let mut velocities = Vec::new();
        for i in 0..40 {
            for j in 0..40 {
                let (x, y) = (0.2e-3 + i as f64 * 25e-6, 0.5e-3 + j as f64 * 25e-6);
                positions.push([x, y, 0.0]);
                let in_chip = y > g.y_surface && x < g.tip.0 + (y - g.tip.1) * a.tan();
                velocities.push(if in_chip { chip } else { [0.0, 0.0, 0.0] });
            }
        }
        let (phi, ratio) = from_chip_flow(&positions, &velocities, &g).unwrap();
        assert!((ratio - r).abs() < 1e-12, "{ratio}");
        let expected = (r * a.cos() / (1.0 - r * a.sin())).atan().to_degrees();
        assert!(
            (phi - expected).abs() < 1e-9 && (phi - 27.5).abs() < 0.1,
            "{phi} vs {expected}"
        );
    }

    #[test]
    fn no_band_means_low_contrast() {
        let flat: Vec<RatePoint> = field(25.0, 0.0)
            .into_iter()
            .map(|p| RatePoint { rate: 1.0, ..p })
            .collect();
        let found = shear_angle(&flat, (1e-3, 0.7e-3), 1e-3, 50e-6).unwrap();
        assert!((found.contrast - 1.0).abs() < 1e-12, "{found:?}");
        assert!(shear_angle(&[], (0.0, 0.0), 1.0, 1e-3).is_none());
    }

    /// A straight chip 0.6 mm thick on a 5° rake face above a workpiece, points every
    /// 20 µm: the thickness comes back within a point spacing, and the angle with it;
    /// points below the surface or behind the face, and a point thrown off beyond a gap,
    /// do not count.
    #[test]
    fn the_chip_thickness_gives_merchant_s_angle() {
        let g = CHIP;
        let (a, t, s) = (5f64.to_radians(), 0.6e-3, 20e-6);
        let mut positions = Vec::new();
        for i in 0..150 {
            for j in 0..100 {
                let (x, y) = (i as f64 * s + 0.5 * s, j as f64 * s + 0.5 * s);
                let from_face = (g.tip.0 + (y - g.tip.1) * a.tan() - x) * a.cos();
                let in_chip = y > g.y_surface && (0.0..t).contains(&from_face);
                let in_workpiece = y < g.y_surface && x < g.tip.0;
                if in_chip || in_workpiece {
                    positions.push([x, y, 0.0]);
                }
            }
        }
        positions.push([0.2e-3, 1.3e-3, 0.0]);
        let (phi, r, thickness) = from_chip_thickness(&positions, &g, s).unwrap();
        assert!((thickness - t).abs() <= s, "{thickness}");
        let exact = (0.5 * a.cos() / (1.0 - 0.5 * a.sin())).atan().to_degrees();
        let (lo, hi) = (g.depth / (t + s), g.depth / (t - s));
        assert!(r >= lo && r <= hi, "{r}");
        assert!((phi - exact).abs() < 1.0, "{phi} vs {exact}");
        assert!(from_chip_thickness(&positions[..10], &g, s).is_none());
    }
}
