//! Misuse of the `mechanism!` DSL: each case must fail to compile with a message at the
//! offending tokens (the expected output is in `cases/*.stderr`).
//!
//! This package depends on `linkage` alone, so that trybuild's own build of the cases checks
//! nothing else: the test harnesses of the integration tests stay out of it.
//!
//! Compiling every case takes about half a minute (trybuild builds `linkage` again in a target
//! of its own), so a plain `cargo test --workspace` lists the test as ignored;
//! `cargo test -p linkage-ui -- --ignored` runs it, and `.ci/run` does.

#[test]
#[ignore = "compiles every DSL misuse case (about 35 s): cargo test -p linkage-ui -- --ignored"]
fn dsl_misuse_is_a_spanned_compile_error() {
    trybuild::TestCases::new().compile_fail("cases/*.rs");
}
