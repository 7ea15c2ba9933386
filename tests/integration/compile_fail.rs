//! Misuse of the `mechanism!` DSL: each case must fail to compile with a message at the
//! offending tokens (the expected output is in `ui/*.stderr`).

#[test]
fn dsl_misuse_is_a_spanned_compile_error() {
    trybuild::TestCases::new().compile_fail("ui/*.rs");
}
