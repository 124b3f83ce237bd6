//! Single-point driver (in progress).
