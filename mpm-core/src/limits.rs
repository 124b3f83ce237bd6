//! The largest models a scene may ask for (`materials::limits::SizeLimit`): particles
//! from a body and a spacing, grid nodes from the particles' extent, time steps from the
//! end time and Δt, each checked before anything of that size is allocated.

use materials::limits::SizeLimit;

/// Material points of a scene (the shipped 3D Taylor bar has 4·10⁵).
pub const PARTICLES: SizeLimit = SizeLimit {
    what: "material points",
    max: 50_000_000,
    bytes_each: 300,
};

/// Nodes of a background grid.
pub const GRID_NODES: SizeLimit = SizeLimit {
    what: "grid nodes",
    max: 100_000_000,
    bytes_each: 120,
};

/// Time steps of one run (`time.end / Δt`); the run keeps a few numbers per history row.
pub const TIME_STEPS: SizeLimit = SizeLimit {
    what: "time steps",
    max: 100_000_000,
    bytes_each: 32,
};
