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
    #[error("{name}: no strain-rate plateau: the strain rate never exceeds half its maximum for more than one sample")]
    NoPlateau { name: String },
    #[error("{name}: {source}")]
    TooLarge {
        name: String,
        source: materials::limits::TooLarge,
    },
}
