//! How an SHPB record asks to be processed (its TOML's processing keys, read by
//! `experiment::shpb`): the alignment of the pulses, the dispersion correction and the
//! Savitzky-Golay filter. The record declares the choice; `shpb` carries it out (the
//! alignments in `shpb::alignment`, the filter's arithmetic in `shpb::filter`).

use std::str::FromStr;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Alignment {
    Geometric,
    Arrival,
    ForceBalance,
}

impl Alignment {
    pub const ALL: [Alignment; 3] = [
        Alignment::Geometric,
        Alignment::Arrival,
        Alignment::ForceBalance,
    ];
}

impl FromStr for Alignment {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "geometric" => Ok(Alignment::Geometric),
            "arrival" => Ok(Alignment::Arrival),
            "force-balance" => Ok(Alignment::ForceBalance),
            other => Err(format!(
                "\"{other}\": expected \"geometric\" (the default), \"arrival\" or \"force-balance\""
            )),
        }
    }
}

impl std::fmt::Display for Alignment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Alignment::Geometric => "geometric",
            Alignment::Arrival => "arrival",
            Alignment::ForceBalance => "force-balance",
        })
    }
}

/// A Savitzky-Golay filter: `window` samples (odd), polynomial `order` (< window).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SavitzkyGolay {
    pub window: usize,
    pub order: usize,
}

impl SavitzkyGolay {
    /// The filter, if `window` is odd and larger than `order`.
    pub fn new(window: usize, order: usize) -> Result<SavitzkyGolay, String> {
        if window.is_multiple_of(2) || window <= order {
            return Err(format!(
                "window {window}, order {order}: expected an odd window of more samples than the order"
            ));
        }
        Ok(SavitzkyGolay { window, order })
    }
}

/// How the pulses are moved from the gauges to the specimen faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Processing {
    pub alignment: Alignment,
    /// Pochhammer-Chree dispersion correction over the gauge distances.
    pub dispersion: bool,
    /// Savitzky-Golay filter of both gauge records, before any other step.
    pub filter: Option<SavitzkyGolay>,
}

impl Default for Processing {
    /// Geometric alignment, no dispersion correction.
    fn default() -> Processing {
        Processing {
            alignment: Alignment::Geometric,
            dispersion: false,
            filter: None,
        }
    }
}

impl std::fmt::Display for Processing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.alignment)?;
        if self.dispersion {
            f.write_str(" + dispersion")?;
        }
        match self.filter {
            Some(sg) => write!(f, " + SG {}/{}", sg.window, sg.order),
            None => Ok(()),
        }
    }
}
