//! The front end: the DSL parsed into a tree that keeps every span ([`ast`], with numbers in
//! [`value`] and the platform's `home` in [`home`]), then checked name by name against one table
//! of what each pair takes ([`check`]).

pub mod ast;
pub mod check;
pub mod home;
pub mod value;
