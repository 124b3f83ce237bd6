//! Checks of the bar coupling: an elastic specimen between two elastic bars,
//! driven by a step pulse on the incident bar alone. While only the first wave front is
//! in the specimen, 1D wave theory gives the reflected and transmitted pulses in terms of
//! the impedances Z = ρ c A of bar (b) and specimen (s):
//!
//!   ε_r / ε_i = (Z_s − Z_b) / (Z_s + Z_b),   ε_t / ε_i = 4 Z_s Z_b / (Z_s + Z_b)²,
//!
//! so a specimen of the bar's own impedance reflects nothing and transmits the pulse.
//! The ratios are measured as window means: ε_r after the pulse has risen and before the
//! far end's echo (the specimen's P-wave front, the fastest) returns; ε_t after the
//! transmitted front has risen and before the first internal echo arrives.
//!
//! And quasi-static elastic compression between the faces, against the specimen in
//! series with the contact springs (`elastic_compression`). Both at the axisymmetric
//! level, and at the 3D quarter, whose symmetry planes are checked against the full 3D
//! cylinder.

use crate::verify::row::Row;
use crate::verify::Inputs;
use fitting::shpb_model::{
    Bars, Cylinder, Drive, FaceSignals, ModelLevel, ModelSettings, ShpbModel,
};
use materials::{Material, NeoHooke};
use mpm_core::shape::ShapeFunction;
use std::sync::Arc;

use fitting::shpb_model::STUDY_BAR_DIAMETER as BAR_DIAMETER;
use fitting::shpb_model::{STUDY_BAR_DENSITY as BAR_DENSITY, STUDY_BAR_MODULUS as BAR_MODULUS};

/// Specimen: the bar's diameter, 40 mm long, so the first front is clear of its echoes
/// for ≈ 2 L / c_P − rise ≈ 9 µs.
pub const SPECIMEN: Cylinder = Cylinder {
    diameter: BAR_DIAMETER,
    length: 40e-3,
};
/// Incident step: 1e-3 reached over `RISE` from `ONSET` [s].
const AMPLITUDE: f64 = 1e-3;
const ONSET: f64 = 1e-6;
const RISE: f64 = 4e-6;

/// The bars of the study (`Bars::study`, see `lateral_inertia_error`).
pub fn bars() -> Bars {
    Bars::study()
}

/// Relative error of the 1D (elementary) rod theory for a pulse rising over `rise` [s] in
/// a rod of radius `radius` [m], Poisson ratio `nu` and bar speed `c` [m/s]: the
/// Rayleigh-Love lateral-inertia term, (ν k a)² / 2, at the rise's wavenumber
/// k = π / (c τ). The 1D ratios are known to this accuracy, not better.
pub fn lateral_inertia_error(radius: f64, nu: f64, c: f64, rise: f64) -> f64 {
    let k = std::f64::consts::PI / (c * rise);
    0.5 * (nu * k * radius).powi(2)
}

/// Layers of the checks: the rows assert at the finest and show the errors falling.
pub const LAYERS: [usize; 3] = [20, 40, 80];

/// Ratios measured and from 1D theory.
#[derive(Debug, Clone, Copy)]
pub struct Impedance {
    /// Z_s / Z_b [-].
    pub impedance_ratio: f64,
    pub reflection: f64,
    pub reflection_theory: f64,
    pub transmission: f64,
    pub transmission_theory: f64,
    /// The 1D theory's own error for this pulse and rod (`lateral_inertia_error`).
    pub theory_error: f64,
}

impl Impedance {
    /// (what, measured, theory) of the reflected and the transmitted pulse.
    fn rows(&self) -> [(&'static str, f64, f64); 2] {
        [
            (
                "reflection eps_r/eps_i",
                self.reflection,
                self.reflection_theory,
            ),
            (
                "transmission eps_t/eps_i",
                self.transmission,
                self.transmission_theory,
            ),
        ]
    }
}

fn step_pulse(end: f64) -> FaceSignals {
    let n = 2001;
    let time_s: Vec<f64> = (0..n).map(|k| end * k as f64 / (n - 1) as f64).collect();
    let incident = time_s
        .iter()
        .map(|t| AMPLITUDE * ((t - ONSET) / RISE).clamp(0.0, 1.0))
        .collect();
    FaceSignals {
        relative_velocity_m_per_s: vec![0.0; n],
        time_s,
        incident,
    }
}

fn mean_over(t: &[f64], v: &[f64], (from, to): (f64, f64)) -> f64 {
    let w: Vec<f64> = t
        .iter()
        .zip(v)
        .filter(|(t, _)| (from..to).contains(*t))
        .map(|(_, v)| *v)
        .collect();
    w.iter().sum::<f64>() / w.len() as f64
}

/// Run an elastic specimen of modulus `e` [Pa], Poisson ratio `nu` and density `rho`
/// [kg/m³] at `level` with `layers` points along its length, frictionless, with shape
/// functions `kernel`.
pub fn impedance_check(
    (e, nu, rho): (f64, f64, f64),
    (level, layers): (ModelLevel, usize),
    kernel: ShapeFunction,
) -> anyhow::Result<Impedance> {
    let bars = bars();
    let z_b = bars.axial_stiffness / bars.wave_speed;
    let area = SPECIMEN.area();
    let c_rod = (e / rho).sqrt();
    let z_s = rho * c_rod * area;
    let material = NeoHooke::new(e, nu, rho);
    let c_p = (material.p_wave_modulus() / rho).sqrt();
    let length = SPECIMEN.length;
    // windows from the moment the front enters the specimen
    let enter = ONSET + RISE;
    let reflection_window = (enter + 1e-6, ONSET + 2.0 * length / c_p);
    let arrive = ONSET + length / c_rod + RISE;
    let transmission_window = (arrive + 1e-6, ONSET + 3.0 * length / c_p);
    let end = transmission_window.1 + 1e-6;
    let mut settings = ModelSettings::new(layers, Drive::IncidentPulse);
    settings.friction = 0.0;
    settings.shape_function = kernel;
    settings.level = level;
    let model = ShpbModel::new(
        SPECIMEN,
        bars,
        step_pulse(end),
        settings,
        Arc::new(material),
    )?;
    let run = model.run(Arc::new(material))?;
    let h = &run.history;
    Ok(Impedance {
        impedance_ratio: z_s / z_b,
        reflection: mean_over(&h.time_s, &h.reflected, reflection_window) / AMPLITUDE,
        reflection_theory: (z_s - z_b) / (z_s + z_b),
        transmission: mean_over(&h.time_s, &h.transmitted, transmission_window) / AMPLITUDE,
        transmission_theory: 4.0 * z_s * z_b / (z_s + z_b).powi(2),
        theory_error: lateral_inertia_error(
            0.5 * SPECIMEN.diameter,
            nu.max(0.3),
            c_rod.min(bars.wave_speed),
            RISE,
        ),
    })
}

/// Quasi-static elastic compression between frictionless faces (measured drive, the
/// face speed ramped to 0.04 m/s over 10 µs, 60 µs, ε ≈ 5e-4, where the Neo-Hooke law is
/// linear to 4e-4): the face force F2 over E A ε with ε from the faces' travel, and the
/// same ratio for the specimen in series with the two contact layers.
///
/// Each face's springs sum to κ_layer = ω_c² m_layer = f² E_p A / s (ω_c = f c / s,
/// c² = E_p/ρ with the P-wave modulus E_p), so F2 / (E A ε) = 1 / (1 + 2 E / (f² E_p n))
/// for n points along: the contact compliance is the model's only first-order error in
/// quasi-static compression (before the contact forces acted at the domain surfaces, the
/// end cells carried ≈ 3/4 of the interior stress and the ratio came out 0.957, 0.980,
/// 0.991 at n = 10, 20, 40 from errors that partly cancelled).
pub fn elastic_compression(level: ModelLevel, layers: usize) -> anyhow::Result<(f64, f64)> {
    let cylinder = Cylinder {
        diameter: 8e-3,
        length: 4e-3,
    };
    let n = 2001;
    let end = 60e-6;
    let time_s: Vec<f64> = (0..n).map(|k| end * k as f64 / (n - 1) as f64).collect();
    let relative_velocity_m_per_s = time_s.iter().map(|t| 0.04 * (t / 10e-6).min(1.0)).collect();
    let signals = FaceSignals {
        time_s,
        incident: vec![0.0; n],
        relative_velocity_m_per_s,
    };
    let mut settings = ModelSettings::new(layers, Drive::MeasuredVelocity);
    settings.shape_function = ShapeFunction::Linear;
    settings.friction = 0.0;
    settings.level = level;
    let (e, nu) = (200e9, 0.3);
    let material = NeoHooke::new(e, nu, 7850.0);
    let model = ShpbModel::new(cylinder, bars(), signals, settings, Arc::new(material))?;
    let h = model.run(Arc::new(material))?.history;
    let k = h.time_s.len() - 1;
    let strain = 1.0 - h.length_m[k] / cylinder.length;
    let ratio = h.force_transmitted_n[k] / (e * cylinder.area() * strain);
    let p_wave = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let f = settings.contact_factor;
    let series = 1.0 / (1.0 + 2.0 * e / (f * f * p_wave * layers as f64));
    Ok((ratio, series))
}

/// Rows of `mpw verify`: the matched and the aluminium specimen at `LAYERS`; the elastic
/// compression against the series springs.
/// Every SHPB-model row of `mpw verify`.
pub fn rows(_inputs: &Inputs) -> anyhow::Result<Vec<Row>> {
    Ok(cases())
}

fn cases() -> Vec<Row> {
    let mut out = Vec::new();
    for layers in [10, 20, 40] {
        let name = format!(
            "shpb-model/elastic compression n{layers}: F2 / (E A eps) vs specimen and contact springs in series"
        );
        out.push(
            match elastic_compression(ModelLevel::Axisymmetric, layers) {
                // tolerance: a fifth of the end-cell error this row guards against (2.7 % at
                // n = 40 with stiff contact), well above the Neo-Hooke nonlinearity (4e-4)
                Ok((ratio, series)) => Row::relative(name, ratio, series, 5e-3),
                Err(e) => Row::holds(format!("{name}: {e:#}"), false),
            },
        );
    }
    for (name, (e, nu, rho)) in [
        ("matched", (BAR_MODULUS, 0.3, BAR_DENSITY)),
        ("aluminium", (70e9, 0.33, 2700.0)),
    ] {
        let runs: anyhow::Result<Vec<Impedance>> = LAYERS
            .iter()
            .map(|&layers| {
                let at = (ModelLevel::Axisymmetric, layers);
                impedance_check((e, nu, rho), at, ShapeFunction::Linear)
            })
            .collect();
        let runs = match runs {
            Ok(r) => r,
            Err(e) => {
                out.push(Row::holds(
                    format!("shpb-model/impedance/{name}: {e:#}"),
                    false,
                ));
                continue;
            }
        };
        for (r, layers) in runs.iter().zip(LAYERS) {
            let prefix = format!(
                "shpb-model/impedance/{name} (Zs/Zb {:.3}) n{layers}",
                r.impedance_ratio
            );
            for (what, measured, theory) in r.rows() {
                let name = format!("{prefix} {what}");
                out.push(match layers == LAYERS[LAYERS.len() - 1] {
                    true => Row::absolute(name, measured, theory, r.theory_error),
                    false => Row::info(name, measured, theory),
                });
            }
        }
        // the transmitted front carries the discretization error (the reflection is at
        // the noise level, 1e-4, from the coarsest level on)
        let error = |r: &Impedance| (r.transmission - r.transmission_theory).abs();
        let errors: Vec<f64> = runs.iter().map(error).collect();
        let note = format!(
            "errors {:.1e}, {:.1e}, {:.1e}",
            errors[0], errors[1], errors[2]
        );
        out.push(
            Row::holds(
                format!("shpb-model/impedance/{name}: transmission error falls with refinement"),
                errors.windows(2).all(|w| w[1] < w[0]),
            )
            .with_note(note),
        );
    }
    out.extend(solid_level_cases());
    // the domain kernels on the matched specimen at the finest level; uGIMP's
    // fixed domains miss the 1D theory there (0.9858), a domain that follows F does not
    let finest = LAYERS[LAYERS.len() - 1];
    for kernel in [
        ShapeFunction::UGimp,
        ShapeFunction::CpGimp,
        ShapeFunction::Cpdi,
    ] {
        let name = format!(
            "shpb-model/impedance/matched n{finest} {} transmission eps_t/eps_i",
            kernel.name()
        );
        out.push(
            match impedance_check(
                (BAR_MODULUS, 0.3, BAR_DENSITY),
                (ModelLevel::Axisymmetric, finest),
                kernel,
            ) {
                Ok(r) if kernel == ShapeFunction::UGimp => Row::info(
                    format!("{name} (gap)"),
                    r.transmission,
                    r.transmission_theory,
                ),
                Ok(r) => Row::absolute(name, r.transmission, r.transmission_theory, r.theory_error),
                Err(e) => Row::holds(format!("{name}: {e:#}"), false),
            },
        );
    }
    out
}

/// The 3D levels: the quarter with its two symmetry planes is the full cylinder to
/// round-off, takes the series springs of the quasi-static compression, and couples to
/// the bars as the axisymmetric level does (matched specimen, finest level).
fn solid_level_cases() -> Vec<Row> {
    let mut out = Vec::new();
    let name = "shpb-model/elastic compression n10 mpm-3d-quarter";
    let (quarter, full) = (
        elastic_compression(ModelLevel::Quarter3d, 10),
        elastic_compression(ModelLevel::Full3d, 10),
    );
    match (quarter, full) {
        (Ok((quarter, series)), Ok((full, _))) => {
            out.push(Row::relative(
                format!("{name}: F2 / (E A eps) vs specimen and contact springs in series"),
                quarter,
                series,
                5e-3,
            ));
            // round-off of two runs that sum the same forces in another order
            out.push(Row::relative(
                format!("{name}: F2 of the quarter x 4 vs the full 3D cylinder"),
                quarter,
                full,
                1e-9,
            ));
        }
        (Err(e), _) | (_, Err(e)) => out.push(Row::holds(format!("{name}: {e:#}"), false)),
    }
    let finest = LAYERS[LAYERS.len() - 1];
    let name = format!("shpb-model/impedance/matched n{finest} mpm-3d-quarter");
    let at = (ModelLevel::Quarter3d, finest);
    match impedance_check((BAR_MODULUS, 0.3, BAR_DENSITY), at, ShapeFunction::Linear) {
        Ok(r) => {
            for (what, measured, theory) in r.rows() {
                let row = format!("{name} {what}");
                out.push(Row::absolute(row, measured, theory, r.theory_error));
            }
        }
        Err(e) => out.push(Row::holds(format!("{name}: {e:#}"), false)),
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The matched check at 40 points along the specimen (0.1 s): nothing reflected, the
    /// pulse transmitted, within the 1D theory's own error (at 20 points the transmitted
    /// front is still 1.9 % high, beyond it).
    #[test]
    fn a_matched_specimen_reflects_nothing_and_transmits_the_pulse() {
        let r = impedance_check(
            (BAR_MODULUS, 0.3, BAR_DENSITY),
            (ModelLevel::Axisymmetric, LAYERS[1]),
            ShapeFunction::Linear,
        )
        .unwrap();
        assert!(r.reflection.abs() < r.theory_error, "{r:?}");
        assert!((r.transmission - 1.0).abs() < r.theory_error, "{r:?}");
    }
}
