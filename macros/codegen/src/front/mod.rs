//! The front end: the DSL parsed into a tree that keeps every span ([`ast`], with numbers in
//! [`value`] and the platform's `home` in [`home`]), then resolved in one pass ([`resolve`]):
//! every pair checked against one table of what each pair kind takes, every mistake into one
//! accumulator ([`errors`]) that the later phases share, and the names turned into typed ids
//! ([`ids`]) in the resolved declaration the model consumes ([`resolved`]).

pub mod accepts;
pub mod ast;
pub mod errors;
pub mod home;
pub mod ids;
pub mod inputs;
pub mod resolve;
pub mod resolved;
pub mod value;
