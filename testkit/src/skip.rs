//! What a test does when the service it needs is missing: it is skipped,
//! and says so with one line on stderr naming the test, the service, why,
//! and how to make it fail instead:
//!
//! ```text
//! skipped: the_store_survives_reopening: no PostgreSQL (PostgreSQL's initdb was not found (...)); set CHAPAEV_REQUIRE_POSTGRES=1 to fail instead
//! ```
//!
//! The line goes straight to the process's stderr, not through `eprintln!`,
//! which the test harness captures and shows only for failing tests: so
//! `cargo test` shows it for a passing (skipped) test too, without
//! `--nocapture`. Where the service's variable is set (CI sets both), a
//! missing service fails the test instead.

use std::io::Write;

/// A service some tests need.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Service {
    Postgres,
    Redis,
}

impl Service {
    /// Its name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Service::Postgres => "PostgreSQL",
            Service::Redis => "Redis",
        }
    }

    /// The environment variable that makes its absence a failure.
    pub fn required_by(self) -> &'static str {
        match self {
            Service::Postgres => "CHAPAEV_REQUIRE_POSTGRES",
            Service::Redis => "CHAPAEV_REQUIRE_REDIS",
        }
    }
}

/// What becomes of test `test` without `service` (which could not start
/// for `reason`): `Ok` with the line that says it was skipped, or, where
/// the service is `required`, `Err` with the failure's message.
pub fn verdict(
    test: &str,
    service: Service,
    reason: &str,
    required: bool,
) -> Result<String, String> {
    if required {
        return Err(format!(
            "{} is set and no local {} started: {reason}",
            service.required_by(),
            service.name()
        ));
    }
    Ok(format!(
        "skipped: {test}: no {} ({reason}); set {}=1 to fail instead",
        service.name(),
        service.required_by()
    ))
}

/// Test `test` goes on without `service` (see the module's
/// documentation): prints its skip line, or panics where the service is
/// required.
pub fn without(test: &str, service: Service, reason: &str) {
    let required = std::env::var_os(service.required_by()).is_some();
    match verdict(test, service, reason, required) {
        Ok(line) => {
            let _ = writeln!(std::io::stderr().lock(), "{line}");
        }
        Err(failure) => panic!("{failure}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_skip_names_the_test_the_service_the_reason_and_how_to_fail_instead() {
        let line = verdict("store_test", Service::Postgres, "initdb not found", false).unwrap();
        assert_eq!(
            line,
            "skipped: store_test: no PostgreSQL (initdb not found); set CHAPAEV_REQUIRE_POSTGRES=1 to fail instead"
        );
        let line = verdict("relay", Service::Redis, "not on PATH", false).unwrap();
        assert!(line.contains("no Redis") && line.contains("CHAPAEV_REQUIRE_REDIS=1"));
    }

    #[test]
    fn a_required_service_that_is_missing_is_a_failure() {
        let failure = verdict("t", Service::Redis, "not on PATH", true).unwrap_err();
        assert_eq!(
            failure,
            "CHAPAEV_REQUIRE_REDIS is set and no local Redis started: not on PATH"
        );
    }
}
