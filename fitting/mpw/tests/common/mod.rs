//! Shared by the tests that read `../shared/data`.

/// Say that a test is skipped because `what` is not there; when the environment sets
/// `MPW_REQUIRE_SHARED_DATA` (CI does, when the shared folder is beside the repository)
/// a skip is a failure instead.
pub fn skip(what: &str) {
    if std::env::var_os("MPW_REQUIRE_SHARED_DATA").is_some() {
        panic!("{what} not found, but MPW_REQUIRE_SHARED_DATA is set: the real-data test must run");
    }
    eprintln!("skipped: {what} not found");
}
