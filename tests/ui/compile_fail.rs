//! Misuse of the `mechanism!` DSL: each case must fail to compile with a message at the
//! offending tokens (the expected output is in `cases/*.stderr`).
//!
//! This package depends on `linkage` alone, so that trybuild's own build of the cases checks
//! nothing else: the test harnesses of the integration tests stay out of it.

#[test]
fn dsl_misuse_is_a_spanned_compile_error() {
    trybuild::TestCases::new().compile_fail("cases/*.rs");
}
