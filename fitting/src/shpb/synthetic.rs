//! Synthetic SHPB records from a known specimen response, to test the processing.
//!
//! The specimen is rate independent: elastic with modulus E_s up to σ0, then
//! σ = σ0 + K ε_p^n on loading, elastic unloading. It is in equilibrium (F1 = F2), so
//! ε_t = ε_i + ε_r with ε_t = A_s σ/(E_b A_b), and the engineering strain follows
//! dε/dt = c0 (ε_i − ε_r − ε_t)/L_s = 2 c0 (ε_i − ε_t)/L_s (integrated by RK4 at a
//! quarter of the sampling interval). A trapezoidal incident pulse ε_i(t) drives it.
//! The face strains are delayed to the gauges (d_i/c0, d_t/c0, or the bar's calibrated
//! delays), turned to the recorded sign (compression negative), offset by a baseline and
//! given uniform noise from a seeded generator. With `dispersed` the waves also disperse
//! on their way (`shpb::dispersion`): the trapezoid is recorded at the incident gauge
//! and reaches the specimen dispersed over d_i, and the reflected and transmitted face
//! pulses disperse over d_i and d_t on their way to the gauges.

use super::dispersion::{correct, PhaseVelocity};
use super::signal::interpolate;
use crate::experiment::{Bar, ShpbExperiment, Specimen};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::path::PathBuf;

/// Rate-independent elastic-plastic specimen in uniaxial stress (compression positive).
#[derive(Debug, Clone, Copy)]
pub struct HardeningCurve {
    /// E_s [Pa].
    pub elastic_modulus_pa: f64,
    /// σ0 [Pa].
    pub yield_stress_pa: f64,
    /// K [Pa].
    pub hardening_pa: f64,
    /// n [-].
    pub exponent: f64,
}

impl HardeningCurve {
    /// σ_y(ε_p) = σ0 + K ε_p^n [Pa].
    pub fn flow_stress(&self, plastic_strain: f64) -> f64 {
        self.yield_stress_pa + self.hardening_pa * plastic_strain.max(0.0).powf(self.exponent)
    }

    /// Stress [Pa] and plastic strain at total strain `strain`, from plastic strain
    /// `plastic_strain` of the previous state (return mapping by bisection).
    pub fn update(&self, strain: f64, plastic_strain: f64) -> (f64, f64) {
        let trial = self.elastic_modulus_pa * (strain - plastic_strain);
        if trial <= self.flow_stress(plastic_strain) {
            return (trial, plastic_strain);
        }
        // E_s (ε − ε_p) − σ_y(ε_p) decreases in ε_p; it is > 0 at the old ε_p, < 0 at ε.
        let (mut lo, mut hi) = (plastic_strain, strain);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if self.elastic_modulus_pa * (strain - mid) > self.flow_stress(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let ep = 0.5 * (lo + hi);
        (self.elastic_modulus_pa * (strain - ep), ep)
    }

    /// Stress on monotonic loading to `strain` [Pa].
    pub fn loading_stress(&self, strain: f64) -> f64 {
        self.update(strain, 0.0).0
    }
}

/// Trapezoidal incident pulse at the specimen face, compression positive.
#[derive(Debug, Clone, Copy)]
pub struct TrapezoidPulse {
    pub amplitude: f64,
    pub rise_s: f64,
    pub flat_s: f64,
    pub fall_s: f64,
}

impl TrapezoidPulse {
    pub fn duration_s(&self) -> f64 {
        self.rise_s + self.flat_s + self.fall_s
    }

    /// ε_i at time `t` after the pulse front reaches the face.
    pub fn at(&self, t: f64) -> f64 {
        let up = t / self.rise_s;
        let down = (self.duration_s() - t) / self.fall_s;
        self.amplitude * up.min(1.0).min(down).max(0.0)
    }
}

/// Everything that defines a synthetic record.
#[derive(Debug, Clone)]
pub struct SyntheticSetup {
    pub bar: Bar,
    pub specimen: Specimen,
    pub curve: HardeningCurve,
    pub pulse: TrapezoidPulse,
    /// Sampling interval [s].
    pub sampling_s: f64,
    /// Record time before the incident pulse reaches the incident gauge [s].
    pub pre_trigger_s: f64,
    /// Baselines added to the incident and transmitted records [strain].
    pub baseline_incident: f64,
    pub baseline_transmitted: f64,
    /// Whether the pulses disperse between faces and gauges (needs the bar's Poisson
    /// ratio).
    pub dispersed: bool,
    /// Noise: uniform in ± this [strain].
    pub noise: f64,
    pub seed: u64,
}

impl SyntheticSetup {
    /// The 945-steel bars and specimen of the shared data (E_b 210 GPa, ρ_b 7800 kg/m³,
    /// Ø 20 mm, gauges 1020/770 mm; specimen Ø 8 × 4 mm), a steel-like specimen
    /// (E_s 200 GPa, σ0 800 MPa, K 600 MPa, n 0.4), a 1500 µε pulse (15/70/15 µs),
    /// sampled at 32 ns, baselines +30/−20 µε and ±2 µε noise.
    pub fn steel_945_like(seed: u64) -> SyntheticSetup {
        SyntheticSetup {
            bar: Bar {
                elastic_modulus_pa: 210e9,
                density_kg_m3: 7800.0,
                diameter_m: 0.020,
                incident_gauge_to_specimen_m: 1.020,
                transmitted_gauge_to_specimen_m: 0.770,
                incident_delay_calibrated_s: None,
                transmitted_delay_calibrated_s: None,
                poisson_ratio: Some(0.29),
            },
            specimen: Specimen {
                diameter_m: 0.008,
                length_m: 0.004,
            },
            curve: HardeningCurve {
                elastic_modulus_pa: 200e9,
                yield_stress_pa: 800e6,
                hardening_pa: 600e6,
                exponent: 0.4,
            },
            pulse: TrapezoidPulse {
                amplitude: 1500e-6,
                rise_s: 15e-6,
                flat_s: 70e-6,
                fall_s: 15e-6,
            },
            sampling_s: 32e-9,
            pre_trigger_s: 60e-6,
            baseline_incident: 30e-6,
            baseline_transmitted: -20e-6,
            dispersed: false,
            noise: 2e-6,
            seed,
        }
    }
}

/// A synthetic record and the exact specimen history behind it.
#[derive(Debug, Clone)]
pub struct SyntheticShpb {
    pub experiment: ShpbExperiment,
    /// Record time at which the incident pulse front reaches the specimen face [s].
    pub load_start_s: f64,
    /// Exact history after `load_start_s`: time [s], engineering strain, stress [Pa].
    pub time_s: Vec<f64>,
    pub strain: Vec<f64>,
    pub stress_pa: Vec<f64>,
}

impl SyntheticShpb {
    pub fn generate(setup: &SyntheticSetup) -> SyntheticShpb {
        let bar = &setup.bar;
        let c0 = bar.wave_speed_m_per_s();
        let rate_factor = 2.0 * c0 / setup.specimen.length_m;
        let to_bar_strain = setup.specimen.area_m2() / (bar.elastic_modulus_pa * bar.area_m2());
        let pulse = setup.pulse;
        let curve = setup.curve;
        let dispersion = setup.dispersed.then(|| {
            let nu = bar
                .poisson_ratio
                .expect("a dispersed synthetic record needs the bar's Poisson ratio");
            PhaseVelocity::new(c0, 0.5 * bar.diameter_m, nu)
        });

        // Specimen history, for the pulse and 30 µs of unloading after it.
        let h = setup.sampling_s / 4.0;
        let steps = ((pulse.duration_s() + 30e-6) / h).ceil() as usize;
        let grid: Vec<f64> = (0..=steps + 1).map(|k| k as f64 * h).collect();
        let trapezoid: Vec<f64> = grid.iter().map(|&t| pulse.at(t)).collect();
        let incident_at_face = match &dispersion {
            Some(phase) => correct(&trapezoid, h, bar.incident_gauge_to_specimen_m, phase),
            None => trapezoid,
        };
        let incident_face = |t: f64| interpolate(&grid, &incident_at_face, t);
        let (mut time_s, mut strain, mut stress_pa) = (vec![0.0], vec![0.0], vec![0.0]);
        let mut plastic = 0.0;
        for k in 0..steps {
            let (t, e) = (k as f64 * h, strain[k]);
            let rate = |t: f64, e: f64| {
                rate_factor * (incident_face(t) - to_bar_strain * curve.update(e, plastic).0)
            };
            let k1 = rate(t, e);
            let k2 = rate(t + 0.5 * h, e + 0.5 * h * k1);
            let k3 = rate(t + 0.5 * h, e + 0.5 * h * k2);
            let k4 = rate(t + h, e + h * k3);
            let e_new = e + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
            let (s_new, p_new) = curve.update(e_new, plastic);
            plastic = p_new;
            time_s.push(t + h);
            strain.push(e_new);
            stress_pa.push(s_new);
        }
        let transmitted: Vec<f64> = stress_pa.iter().map(|s| to_bar_strain * s).collect();
        let reflected: Vec<f64> = time_s
            .iter()
            .zip(&transmitted)
            .map(|(&t, et)| et - incident_face(t))
            .collect();
        let last = *time_s.last().unwrap();
        let face = |values: &[f64], t: f64| {
            if (0.0..=last).contains(&t) {
                interpolate(&time_s, values, t)
            } else {
                0.0
            }
        };

        // Gauge records, compression negative.
        let di = bar.incident_delay_s();
        let dtr = bar.transmitted_delay_s();
        let load_start_s = setup.pre_trigger_s + di;
        // the record runs 20 µs past the last pulse, and with dispersion as long again as
        // the slowest waves lag behind
        let tail = if setup.dispersed { 220e-6 } else { 20e-6 };
        let end = load_start_s + last + di.max(dtr) + tail;
        let samples = (end / setup.sampling_s).ceil() as usize;
        let record_time: Vec<f64> = (0..samples).map(|j| j as f64 * setup.sampling_s).collect();
        // a face pulse read at the gauge `distance` [m] away, dispersed on its way if asked
        let at_gauge = |f: &dyn Fn(f64) -> f64, distance: f64| -> Vec<f64> {
            let clean: Vec<f64> = record_time.iter().map(|&t| f(t - load_start_s)).collect();
            match &dispersion {
                Some(phase) => correct(&clean, setup.sampling_s, distance, phase),
                None => clean,
            }
        };
        let incident_part: Vec<f64> = record_time
            .iter()
            .map(|&t| pulse.at(t - load_start_s + di))
            .collect();
        let reflected_part = at_gauge(
            &|tf| face(&reflected, tf - di),
            bar.incident_gauge_to_specimen_m,
        );
        let transmitted_part = at_gauge(
            &|tf| face(&transmitted, tf - dtr),
            bar.transmitted_gauge_to_specimen_m,
        );
        let mut rng = Pcg64::seed_from_u64(setup.seed);
        let mut noise = || rng.gen_range(-setup.noise..=setup.noise);
        let mut incident = Vec::with_capacity(samples);
        let mut transmitted_gauge = Vec::with_capacity(samples);
        for j in 0..samples {
            incident
                .push(-(incident_part[j] + reflected_part[j]) + setup.baseline_incident + noise());
            transmitted_gauge.push(-transmitted_part[j] + setup.baseline_transmitted + noise());
        }
        SyntheticShpb {
            experiment: ShpbExperiment {
                name: format!("synthetic (seed {})", setup.seed),
                data_file: PathBuf::from("<synthetic>"),
                bar: bar.clone(),
                specimen: setup.specimen.clone(),
                temperature_k: 293.15,
                time_s: record_time,
                incident,
                transmitted: transmitted_gauge,
                processing: crate::shpb::Processing::default(),
                notes: Vec::new(),
            },
            load_start_s,
            time_s,
            strain,
            stress_pa,
        }
    }
}
