//! What a run of the orthogonal cut gives (thesis §12.3), read back from its folder: the
//! tool forces raw and filtered (by the caller's filter: the thesis's is Savitzky-Golay,
//! 31 history samples, first order), their steady values from 20 µs on, how steady they
//! are, the noise the filter removes, and the shear angle φ_s of every snapshot from 20 µs
//! on (from the chip's flow and from its thickness, with the strain-rate band and its
//! contrast beside them).
//!
//! Steadiness: the filtered f_x's mean over the second half of the steady window minus its
//! mean over the first half, over the mean of the whole window (0 for a flat force; the
//! thesis reads f_x as "almost steady" after 15-20 µs).

use crate::merchant::{Merchant, MerchantForce};
use crate::orthogonal::OrthogonalCut;
use crate::record::{snapshot_files, ToolForce};
use crate::shear_angle::{
    from_chip_flow, from_chip_thickness, from_snapshot, ChipGeometry, ShearAngle,
};
use anyhow::{Context, Result};
use materials::plasticity::ElastoPlastic;
use std::path::Path;

/// Forces count as steady from this time on (the thesis: after 15-20 µs) [s].
pub const STEADY_FROM: f64 = 20e-6;

/// The name of the tool in the orthogonal scene.
pub const TOOL: &str = "tool";

/// The shear angle measured in one snapshot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleSample {
    /// Snapshot time [s].
    pub time: f64,
    /// φ_s [degrees] and chip thickness ratio from the chip's flow, once there is a chip.
    pub chip_flow: Option<(f64, f64)>,
    /// φ_s [degrees], chip thickness ratio and chip thickness [m] from the chip's
    /// thickness.
    pub chip_thickness: Option<(f64, f64, f64)>,
    /// The band of highest plastic strain rate through the tool tip.
    pub band: Option<ShearAngle>,
}

/// Forces and shear angles of one orthogonal run.
#[derive(Debug, Clone)]
pub struct OrthogonalResult {
    pub force: ToolForce,
    /// f_x and f_y through the filter given to `read` [N/m].
    pub filtered_x: Vec<f64>,
    pub filtered_y: Vec<f64>,
    /// One per snapshot from `STEADY_FROM` on.
    pub angles: Vec<AngleSample>,
}

impl OrthogonalResult {
    /// Read the run of `cut` in folder `run` (its `history.csv` and snapshots), its forces
    /// filtered by `filter`.
    pub fn read(
        run: &Path,
        cut: &OrthogonalCut,
        filter: impl Fn(&[f64]) -> Vec<f64>,
    ) -> Result<OrthogonalResult> {
        let force = ToolForce::read(&run.join("history.csv"), TOOL)?;
        let mut angles = Vec::new();
        for file in snapshot_files(run)? {
            let snapshot = mpm_core::output::read_snapshot(&file)?;
            if snapshot.time >= STEADY_FROM {
                angles.push(
                    angle_sample(&snapshot, cut).with_context(|| file.display().to_string())?,
                );
            }
        }
        Ok(OrthogonalResult {
            filtered_x: filter(&force.force_x),
            filtered_y: filter(&force.force_y),
            force,
            angles,
        })
    }

    /// The samples of `series` from `STEADY_FROM` on.
    fn steady<'a>(&'a self, series: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
        (self.force.time_s.iter().zip(series))
            .filter(|(t, _)| **t >= STEADY_FROM)
            .map(|(_, f)| *f)
    }

    /// Mean filtered f_x and f_y from `STEADY_FROM` on [N/m]; `None` for a run that ended
    /// before.
    pub fn steady_force(&self) -> Option<[f64; 2]> {
        Some([
            self.steady_mean(&self.filtered_x)?,
            self.steady_mean(&self.filtered_y)?,
        ])
    }

    /// Mean of `series`, one value per history row, from `STEADY_FROM` on; `None` for a
    /// run that ended before.
    pub fn steady_mean(&self, series: &[f64]) -> Option<f64> {
        mean(self.steady(series))
    }

    /// Root mean square of raw minus filtered f_x from `STEADY_FROM` on [N/m]: the noise
    /// the filter removes.
    pub fn noise_rms(&self) -> Option<f64> {
        let noise = self
            .steady(&self.force.force_x)
            .zip(self.steady(&self.filtered_x))
            .map(|(raw, filtered)| (raw - filtered).powi(2));
        mean(noise).map(f64::sqrt)
    }

    /// (mean of the second half − mean of the first half) / mean of the filtered f_x from
    /// `STEADY_FROM` on (module docs); `None` with fewer than two samples.
    pub fn drift(&self) -> Option<f64> {
        let steady: Vec<f64> = self.steady(&self.filtered_x).collect();
        if steady.len() < 2 {
            return None;
        }
        let (first, second) = steady.split_at(steady.len() / 2);
        let whole = mean(steady.iter().copied())?;
        Some((mean(second.iter().copied())? - mean(first.iter().copied())?) / whole)
    }

    /// Mean and sample standard deviation of φ_s from the chip's flow over the snapshots
    /// from `STEADY_FROM` on [degrees]; `None` without a chip.
    pub fn shear_angle(&self) -> Option<(f64, f64)> {
        mean_and_spread(
            self.angles
                .iter()
                .filter_map(|a| a.chip_flow.map(|(phi, _)| phi)),
        )
    }

    /// The same from the chip's thickness.
    pub fn shear_angle_from_thickness(&self) -> Option<(f64, f64)> {
        mean_and_spread(
            self.angles
                .iter()
                .filter_map(|a| a.chip_thickness.map(|(phi, _, _)| phi)),
        )
    }

    /// Merchant's cutting force at the measured mean shear angle, `material` being the
    /// workpiece's.
    pub fn merchant(
        &self,
        cut: &OrthogonalCut,
        material: &ElastoPlastic<f64>,
    ) -> Option<MerchantForce> {
        let (phi, _) = self.shear_angle()?;
        Some(
            Merchant {
                depth: cut.feed,
                speed: cut.speed,
                rake_deg: cut.rake_deg,
                shear_deg: phi,
                friction: cut.friction,
            }
            .estimate(material),
        )
    }
}

fn angle_sample(snapshot: &mpm_core::output::Snapshot, cut: &OrthogonalCut) -> Result<AngleSample> {
    let [x, y] = cut.tip_at(snapshot.time);
    let geometry = ChipGeometry {
        tip: (x, y),
        y_surface: cut.height,
        depth: cut.feed,
        rake_deg: cut.rake_deg,
        speed: cut.speed,
    };
    let velocity = snapshot
        .vector("velocity")
        .context("snapshot without velocity")?;
    // the points' initial lattice: n_x × n_y squares over the workpiece
    let spacing = (cut.length * cut.height / snapshot.position.len() as f64).sqrt();
    Ok(AngleSample {
        time: snapshot.time,
        chip_flow: from_chip_flow(&snapshot.position, velocity, &geometry),
        chip_thickness: from_chip_thickness(&snapshot.position, &geometry, spacing),
        band: from_snapshot(snapshot, (x, y), cut.height, 0.25 * cut.feed),
    })
}

/// Mean and sample standard deviation (0 for one value).
fn mean_and_spread(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let v: Vec<f64> = values.collect();
    let m = mean(v.iter().copied())?;
    let spread = match v.len() {
        1 => 0.0,
        n => (v.iter().map(|p| (p - m).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt(),
    };
    Some((m, spread))
}

fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn result(time_s: Vec<f64>, fx: Vec<f64>) -> OrthogonalResult {
        OrthogonalResult {
            force: ToolForce {
                force_y: vec![0.0; fx.len()],
                force_x: fx.clone(),
                time_s,
            },
            filtered_x: fx,
            filtered_y: Vec::new(),
            angles: Vec::new(),
        }
    }

    /// A flat force does not drift, whatever it was before `STEADY_FROM`; one rising
    /// linearly from 1 to 1.1 over the steady window has halves' means 1.025 and 1.075, a
    /// drift of 0.05/1.05.
    #[test]
    fn drift_is_the_halves_difference_over_the_mean() {
        let t: Vec<f64> = (0..=800).map(|k| k as f64 * 1e-7).collect();
        let flat = result(
            t.clone(),
            t.iter()
                .map(|&s| if s < STEADY_FROM { 9.0 } else { 1.0 })
                .collect(),
        );
        assert_eq!(flat.drift(), Some(0.0));
        // from 1.0 at 20 µs to 1.1 at 80 µs: halves' means 1.025 and 1.075 (to one sample)
        let rising = result(
            t.clone(),
            t.iter()
                .map(|&s| 1.0 + 0.1 * ((s - STEADY_FROM) / 60e-6).max(0.0))
                .collect(),
        );
        let expected = 0.05 / 1.05;
        assert!(
            (rising.drift().unwrap() - expected).abs() < 1e-3,
            "{:?}",
            rising.drift()
        );
    }

    /// The noise removed is the RMS of raw minus filtered from `STEADY_FROM` on.
    #[test]
    fn noise_is_the_rms_of_raw_minus_filtered() {
        let t: Vec<f64> = (0..400).map(|k| k as f64 * 1e-7).collect();
        let raw: Vec<f64> = (0..400)
            .map(|k| if k % 2 == 0 { 3.0 } else { 1.0 })
            .collect();
        let mut r = result(t, raw);
        r.filtered_x = vec![2.0; 400];
        assert_eq!(r.noise_rms(), Some(1.0));
    }
}
