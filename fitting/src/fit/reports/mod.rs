//! Reports: the fit report (terminal table and `report.toml`, `report`), what a report says
//! its parameters rest on (`origin`), and the reports of the studies around a fit
//! (`study_report`).

pub mod origin;
pub mod report;
pub mod study_report;
