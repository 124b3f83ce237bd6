//! Experiments, SHPB signal processing, Johnson-Cook fitting, charts, and the `mpw`
//! subcommands (one module per subcommand in `cli`).

pub mod cli;
