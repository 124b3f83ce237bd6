//! Experiments, SHPB signal processing, fitting.
