//! Synthetic experiments from a stated parameter set (`mpw synth`): a quasi-static
//! tensile test and SHPB tests, written in the experiment-file format
//! (`fitting::experiment`) with the truth, noise level and seed in every file header,
//! plus the experiment-set file that fits them.
//!
//! - Tensile: engineering strain 0 → `TENSILE_STRAIN` at the reference rate α̇0,
//!   isothermal at θ0, `TENSILE_SAMPLES` samples; engineering stress from the single-point
//!   tensile model.
//! - SHPB: relative face velocity ramped linearly over `RAMP` to v0 = ε̇ L0 and held
//!   until `PULSE`; specimen force F from the single-point SHPB model (adiabatic, from the
//!   test temperature). Bar strains by 1-D wave relations with equilibrium F1 = F2 = F
//!   (compression positive): ε_t = F/(E_b A_b), ε_r = −v/(2 c0), ε_i = ε_t + v/(2 c0); then
//!   all three pulses are tapered linearly to zero over `TAPER` (outside any fit window)
//!   and placed on the gauge records with the transit times d_i/c0, d_t/c0; recorded
//!   signs (compression negative).
//! - Noise: Gaussian, standard deviation `noise` × the channel's peak magnitude (stress
//!   for tensile, each gauge channel for SHPB), from a PCG64 generator seeded by `seed`.

use crate::fit::levels::model::ExperimentModel;
use crate::fit::levels::model::Material;
use crate::fit::levels::shpb_specimen::ShpbSpecimen;
use crate::fit::levels::single_point::SinglePoint;
use crate::fit::levels::tensile::{Tensile, Thermal};
use anyhow::{Context, Result};
use materials::material::Model;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

pub const TENSILE_STRAIN: f64 = 0.3;
pub const TENSILE_SAMPLES: usize = 240;
pub const RAMP: f64 = 10e-6;
pub const PULSE: f64 = 120e-6;
pub const TAPER: f64 = 5e-6;
/// Gauge sampling interval of the synthetic SHPB records [s].
pub const SHPB_SAMPLING: f64 = 0.5e-6;
/// Fit window of the synthetic SHPB tests (specimen-face time) [s].
pub const SHPB_WINDOW: [f64; 2] = [15e-6, 115e-6];

/// Bars and specimen of the synthetic SHPB tests (thesis chapter 11: 14 mm steel bars,
/// E 210 GPa, gauges at mid-length of 1.5 m bars; specimen 8 mm × 4 mm). The density is
/// steel's 7850 kg/m³: the thesis's "9850" (section 11.2) is a typo (DESIGN 10).
pub struct ShpbSetup {
    pub bar_modulus: f64,
    pub bar_density: f64,
    pub bar_diameter: f64,
    pub gauge_distance: f64,
    pub specimen_diameter: f64,
    pub specimen_length: f64,
}

pub const THESIS_BARS: ShpbSetup = ShpbSetup {
    bar_modulus: 210e9,
    bar_density: 7850.0,
    bar_diameter: 14e-3,
    gauge_distance: 0.75,
    specimen_diameter: 8e-3,
    specimen_length: 4e-3,
};

/// What to generate.
pub struct SynthSpec<'a> {
    pub material: &'a Material,
    pub material_name: &'a str,
    /// Path of the material file as the set file should reference it.
    pub material_ref: &'a str,
    pub noise: f64,
    pub seed: u64,
    pub shpb_rate: f64,
    pub shpb_temperatures: &'a [f64],
}

/// A standard normal deviate (Box-Muller) from `rng`.
pub fn gaussian(rng: &mut Pcg64) -> f64 {
    let u1: f64 = rng.gen_range(f64::EPSILON..1.0);
    let u2: f64 = rng.gen();
    (-2.0 * u1.ln()).sqrt() * (2.0 * PI * u2).cos()
}

fn add_noise(v: &mut [f64], level: f64, rng: &mut Pcg64) {
    let peak = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for x in v.iter_mut() {
        *x += level * peak * gaussian(rng);
    }
}

fn truth_header(spec: &SynthSpec, what: &str) -> String {
    let mut h = String::new();
    let _ = writeln!(
        h,
        "# synthetic {what}, written by `mpw synth` (fitting::fit::synthetic::synth)"
    );
    let _ = writeln!(h, "# truth: {} parameters, SI units:", spec.material_name);
    for name in spec.material.param_names() {
        let _ = writeln!(h, "#   {name} = {:e}", spec.material.param(name).unwrap());
    }
    let _ = writeln!(
        h,
        "# noise: Gaussian, standard deviation {} x the channel's peak magnitude; seed {}",
        spec.noise, spec.seed
    );
    h
}

fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
        .collect()
}

/// Write the tensile test `qs_tension.{csv,toml}` into `dir`.
fn write_tensile(dir: &Path, spec: &SynthSpec, rng: &mut Pcg64) -> Result<()> {
    let m = spec.material;
    let rate = m.param("alpha_dot0").unwrap();
    let theta = m.thermal.theta0;
    let strain = linspace(
        TENSILE_STRAIN / TENSILE_SAMPLES as f64,
        TENSILE_STRAIN,
        TENSILE_SAMPLES,
    );
    let time: Vec<f64> = strain.iter().map(|e| e / rate).collect();
    let model = SinglePoint::new(Tensile::new(
        m,
        &time,
        &strain,
        &(0..time.len()).collect::<Vec<_>>(),
        Thermal::Isothermal,
        theta,
    )?);
    let mut stress = model.predict(m)?;
    add_noise(&mut stress, spec.noise, rng);
    let mut csv = truth_header(spec, "quasi-static tensile test");
    let _ = writeln!(
        csv,
        "# engineering strain rate {rate:e} 1/s, isothermal at {theta} K"
    );
    csv.push_str("time_s,engineering_strain,engineering_stress_pa\n");
    for k in 0..strain.len() {
        let _ = writeln!(csv, "{:.6e},{:.8e},{:.8e}", time[k], strain[k], stress[k]);
    }
    std::fs::write(dir.join("qs_tension.csv"), csv)?;
    let toml = format!(
        "# Synthetic quasi-static tensile test (truth in qs_tension.csv's header).\n\
         kind = \"tensile\"\nname = \"qs_tension\"\ndata = \"qs_tension.csv\"\n\
         temperature = \"{theta} K\"\nnominal_strain_rate = \"{rate:e} 1/s\"\n\
         [columns]\ntime = {{ name = \"time_s\", unit = \"s\" }}\n\
         strain = {{ name = \"engineering_strain\", unit = \"1\" }}\n\
         stress = {{ name = \"engineering_stress_pa\", unit = \"Pa\" }}\n"
    );
    std::fs::write(dir.join("qs_tension.toml"), toml)?;
    Ok(())
}

/// Write the SHPB test `<name>.{csv,toml}` at temperature `theta` into `dir`.
fn write_shpb(dir: &Path, name: &str, theta: f64, spec: &SynthSpec, rng: &mut Pcg64) -> Result<()> {
    let s = &THESIS_BARS;
    let m = spec.material;
    let c0 = (s.bar_modulus / s.bar_density).sqrt();
    let ea = s.bar_modulus * PI * s.bar_diameter.powi(2) / 4.0;
    let area0 = PI * s.specimen_diameter.powi(2) / 4.0;
    let v0 = spec.shpb_rate * s.specimen_length;
    // Face history on a fine grid.
    let dt = SHPB_SAMPLING / 2.0;
    let n = (PULSE / dt).round() as usize + 1;
    let tf: Vec<f64> = (0..n).map(|k| k as f64 * dt).collect();
    let v: Vec<f64> = tf.iter().map(|&t| v0 * (t / RAMP).min(1.0)).collect();
    let samples: Vec<usize> = (1..n).collect();
    let model = SinglePoint::new(ShpbSpecimen::new(
        m,
        &tf,
        &v,
        &samples,
        s.specimen_length,
        area0,
        theta,
        1,
    )?);
    let mut force = vec![0.0];
    force.extend(model.predict(m)?);
    let pulse = |t: f64, which: usize| -> f64 {
        if !(0.0..=PULSE + TAPER).contains(&t) {
            return 0.0;
        }
        let taper = if t > PULSE {
            (PULSE + TAPER - t) / TAPER
        } else {
            1.0
        };
        let tc = t.min(PULSE);
        let k = ((tc / dt).floor() as usize).min(n - 2);
        let w = (tc - tf[k]) / dt;
        let (f, vel) = (
            force[k] + w * (force[k + 1] - force[k]),
            v[k] + w * (v[k + 1] - v[k]),
        );
        let e_t = f / ea;
        let e_r = -vel / (2.0 * c0);
        taper
            * match which {
                0 => e_t + vel / (2.0 * c0),
                1 => e_r,
                _ => e_t,
            }
    };
    let lead = 40e-6;
    let transit = s.gauge_distance / c0;
    let t_end = lead + 2.0 * transit + PULSE + TAPER + 40e-6;
    let ng = (t_end / SHPB_SAMPLING).round() as usize;
    let tg: Vec<f64> = (0..ng).map(|k| k as f64 * SHPB_SAMPLING).collect();
    // Gauge records, compression negative; the incident pulse reaches the gauge at `lead`.
    let mut inc: Vec<f64> = tg
        .iter()
        .map(|&t| -(pulse(t - lead, 0) + pulse(t - lead - 2.0 * transit, 1)))
        .collect();
    let mut tra: Vec<f64> = tg
        .iter()
        .map(|&t| -pulse(t - lead - 2.0 * transit, 2))
        .collect();
    add_noise(&mut inc, spec.noise, rng);
    add_noise(&mut tra, spec.noise, rng);
    let mut csv = truth_header(spec, "SHPB compression test");
    let _ = writeln!(
        csv,
        "# nominal strain rate {:e} 1/s (face velocity {v0:e} m/s after a {RAMP:e} s ramp, held to {PULSE:e} s, tapered over {TAPER:e} s), start temperature {theta} K, adiabatic",
        spec.shpb_rate
    );
    csv.push_str("time_s,incident_microstrain,transmitted_microstrain\n");
    for k in 0..ng {
        let _ = writeln!(csv, "{:.6e},{:.6},{:.6}", tg[k], inc[k] * 1e6, tra[k] * 1e6);
    }
    std::fs::write(dir.join(format!("{name}.csv")), csv)?;
    let toml = format!(
        "# Synthetic SHPB test (truth in {name}.csv's header).\n\
         kind = \"shpb\"\nname = \"{name}\"\ndata = \"{name}.csv\"\ntemperature = \"{theta} K\"\n\
         [columns]\ntime = {{ name = \"time_s\", unit = \"s\" }}\n\
         incident = {{ name = \"incident_microstrain\", unit = \"microstrain\" }}\n\
         transmitted = {{ name = \"transmitted_microstrain\", unit = \"microstrain\" }}\n\
         [bar]\nelastic_modulus = \"{} GPa\"\ndensity = \"{} kg/m^3\"\ndiameter = \"{} mm\"\n\
         incident_gauge_to_specimen = \"{} mm\"\ntransmitted_gauge_to_specimen = \"{} mm\"\n\
         [specimen]\ndiameter = \"{} mm\"\nlength = \"{} mm\"\n",
        s.bar_modulus * 1e-9,
        s.bar_density,
        s.bar_diameter * 1e3,
        s.gauge_distance * 1e3,
        s.gauge_distance * 1e3,
        s.specimen_diameter * 1e3,
        s.specimen_length * 1e3,
    );
    std::fs::write(dir.join(format!("{name}.toml")), toml)?;
    Ok(())
}

/// Write the synthetic set into `dir`: the experiments and `default.toml`, the
/// experiment set that fits A, B, N, C, M simultaneously from neutral starts.
pub fn write_set(dir: &Path, spec: &SynthSpec) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
    let mut rng = Pcg64::seed_from_u64(spec.seed);
    write_tensile(dir, spec, &mut rng)?;
    let mut names = Vec::new();
    for &theta in spec.shpb_temperatures {
        let name = format!("shpb_{:.0}K", theta);
        write_shpb(dir, &name, theta, spec, &mut rng)?;
        names.push(name);
    }
    let m = spec.material;
    let mut set = String::new();
    let _ = writeln!(
        set,
        "# Synthetic experiment set written by `mpw synth` (noise {}, seed {}).",
        spec.noise, spec.seed
    );
    let _ = writeln!(set, "# `mpw fit` without arguments fits this set.");
    let _ = writeln!(
        set,
        "name = \"{} synthetic: quasi-static tension + SHPB\"",
        spec.material_name
    );
    let _ = writeln!(
        set,
        "material = \"{}\"\noptimizer = \"lm\"\nstarts = 1\nseed = 1\n",
        spec.material_ref
    );
    let _ = writeln!(set, "[truth]");
    for name in ["A", "B", "N", "C", "M"] {
        let _ = writeln!(set, "{name} = {:e}", m.param(name).unwrap());
    }
    let bounds = [
        ("A", 200e6, 2000e6, 600e6),
        ("B", 100e6, 4000e6, 1000e6),
        ("N", 0.05, 1.5, 0.5),
        ("C", 0.0, 0.2, 0.02),
        ("M", 0.3, 4.0, 1.0),
    ];
    for (name, lo, hi, start) in bounds {
        let _ = writeln!(
            set,
            "\n[[parameter]]\nname = \"{name}\"\nlower = {lo:e}\nupper = {hi:e}\nstart = {start:e}"
        );
    }
    let _ = writeln!(
        set,
        "\n[[experiment]]\nfile = \"qs_tension.toml\"\nthermal = \"isothermal\""
    );
    for name in &names {
        let _ = writeln!(
            set,
            "\n[[experiment]]\nfile = \"{name}.toml\"\nwindow = [{:e}, {:e}]\nforces = \"both\"",
            SHPB_WINDOW[0], SHPB_WINDOW[1]
        );
    }
    std::fs::write(dir.join("default.toml"), set)?;
    Ok(())
}
