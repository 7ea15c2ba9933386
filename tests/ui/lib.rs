//! Nothing: this package holds the compile-fail cases of `mechanism!` (see `compile_fail.rs`).
#![no_std]
