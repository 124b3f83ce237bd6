//! The largest inputs the readers accept (`materials::limits::SizeLimit`): a data file is
//! read into memory whole, and a signal is resampled from a record; both are checked
//! before anything of that size is allocated.

use materials::limits::SizeLimit;

/// Samples of a signal resampled from a record.
pub const SIGNAL_SAMPLES: SizeLimit = SizeLimit {
    what: "signal samples",
    max: 50_000_000,
    bytes_each: 8,
};

/// Bytes of one experiment CSV, which is read into memory whole.
pub const TEXT_FILE_BYTES: SizeLimit = SizeLimit {
    what: "bytes of a text data file",
    max: 512 << 20,
    bytes_each: 1,
};
