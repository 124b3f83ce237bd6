//! Why an SHPB record could not be processed.

use thiserror::Error;

#[derive(Debug, Error, PartialEq)]
pub enum ShpbError {
    #[error("{name}: no incident pulse: the largest compressive excursion {amplitude:.3e} is under 10 times the pre-trigger noise {noise:.3e}")]
    NoIncidentPulse {
        name: String,
        amplitude: f64,
        noise: f64,
    },
    #[error("{name}: the first pulse on the incident gauge is tensile (+{peak:.3e} strain, first beyond half of it at t = {time_s:.6e} s; largest compressive excursion {compressive_peak:.3e}): an incident pulse is compressive, so this record stores compression as positive (state polarity = \"compression-positive\" in its TOML) or its incident gauge is reversed")]
    TensileIncidentPulse {
        name: String,
        time_s: f64,
        peak: f64,
        compressive_peak: f64,
    },
    #[error("{name}: the transmitted pulse is tensile (+{peak:.3e} strain against {compressive_peak:.3e} compressive, in {:.6e} .. {:.6e} s at its gauge) while the incident pulse is compressive: the transmitted gauge's sign is reversed (wiring, or a negative gain)", window_s.0, window_s.1)]
    TensileTransmittedPulse {
        name: String,
        window_s: (f64, f64),
        peak: f64,
        compressive_peak: f64,
    },
    #[error("{name}: the incident pulse starts at sample {start}; at least {needed} quiet samples are needed before it to measure the baseline")]
    NoPreTrigger {
        name: String,
        start: usize,
        needed: usize,
    },
    #[error("{name}: the incident pulse ({duration_s:.3e} s with margins) is longer than the round trip 2 d_i/c0 = {round_trip_s:.3e} s to the specimen: incident and reflected pulses overlap at the gauge")]
    PulsesOverlap {
        name: String,
        duration_s: f64,
        round_trip_s: f64,
    },
    #[error("{name}: the record ends at {end_s:.6e} s, before the end of the {pulse} pulse at {needed_s:.6e} s")]
    RecordTooShort {
        name: String,
        pulse: &'static str,
        end_s: f64,
        needed_s: f64,
    },
    #[error("{name}: the plateau stress (3-wave, engineering) is {stress_pa:.4e} Pa, outside {low:e} .. {high:e} Pa, the range of metal and polymer specimens: {likely}")]
    ImplausibleStress {
        name: String,
        stress_pa: f64,
        low: f64,
        high: f64,
        likely: &'static str,
    },
    #[error("{name}: no strain-rate plateau: the strain rate never exceeds half its maximum for more than one sample")]
    NoPlateau { name: String },
    #[error("{name}: the dispersion correction needs the bar's Poisson ratio (bar.poisson_ratio in the TOML)")]
    NoPoissonRatio { name: String },
    #[error("{name}: the dispersion correction needs uniform sampling: the interval after sample {sample} is {interval_s:.4e} s against the mean {mean_s:.4e} s")]
    NonUniformSampling {
        name: String,
        sample: usize,
        interval_s: f64,
        mean_s: f64,
    },
    #[error("{name}: {source}")]
    TooLarge {
        name: String,
        source: materials::limits::TooLarge,
    },
}
