//! The one error accumulator every phase writes to: each mistake a spanned message, all of them
//! reported together as one `compile_error!` per message.

use proc_macro2::Span;

#[derive(Default)]
pub struct Errors(Option<syn::Error>);

impl Errors {
    pub fn push(&mut self, span: Span, msg: impl std::fmt::Display) {
        self.add(syn::Error::new(span, msg));
    }

    /// Adds an error (and any it combines).
    pub fn add(&mut self, e: syn::Error) {
        match &mut self.0 {
            Some(all) => all.combine(e),
            None => self.0 = Some(e),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_none()
    }

    /// Every mistake reported, as one error (a phase that gave up without a reason is a bug
    /// in the generator, and says so rather than let the build pass).
    pub fn into_error(self) -> syn::Error {
        self.0.unwrap_or_else(|| {
            syn::Error::new(
                proc_macro2::Span::call_site(),
                "linkage: the generator stopped without a reason (a bug; please report it)",
            )
        })
    }

    pub fn finish(self) -> syn::Result<()> {
        match self.0 {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}
