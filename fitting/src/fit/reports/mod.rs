//! Reports: the fit report (terminal table and `report.toml`, `report`) and the reports of
//! the studies around a fit (`study_report`).

pub mod report;
pub mod study_report;
