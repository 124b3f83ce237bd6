//! The cutting forces as the thesis reads them (§12.3): through a Savitzky-Golay filter of
//! 31 history samples, first order (the filter of the `fitting` library applied to the
//! runs of the `cutting` library; the commands and the verification catalogue share it).

use cutting::orthogonal::OrthogonalCut;
use cutting::orthogonal_result::OrthogonalResult;
use fitting::experiment::processing::SavitzkyGolay;
use std::path::Path;

/// Filter of the cutting forces: 31 history samples, first order.
pub const FORCE_FILTER: SavitzkyGolay = SavitzkyGolay {
    window: 31,
    order: 1,
};

/// The orthogonal run in `folder` read back, its forces through `FORCE_FILTER`.
pub fn orthogonal_result(folder: &Path, cut: &OrthogonalCut) -> anyhow::Result<OrthogonalResult> {
    OrthogonalResult::read(folder, cut, |f| FORCE_FILTER.apply(f))
}
