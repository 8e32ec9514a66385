//! Errors collected across rules: each at the span of the offending tokens.

use crate::syntax::SpanRange;

/// The errors found so far.
#[derive(Default, Debug)]
pub struct Diagnostics {
    errors: Vec<syn::Error>,
}

impl Diagnostics {
    /// Records an error at a span: a single token's `Span`, or a [`SpanRange`] from the
    /// first to the last token of a node (the error then covers all of it).
    pub fn error(&mut self, span: impl Into<SpanRange>, message: impl std::fmt::Display) {
        self.errors.push(span.into().error(message));
    }

    /// Whether any error was recorded.
    pub fn has_errors(&self) -> bool {
        !self.errors.is_empty()
    }

    /// `Ok` when no error was recorded, else all of them combined into one `syn::Error`
    /// (which expands to one `compile_error!` per message).
    pub fn take_result(&mut self) -> Result<(), syn::Error> {
        let mut errors = std::mem::take(&mut self.errors).into_iter();
        match errors.next() {
            None => Ok(()),
            Some(mut first) => {
                for e in errors {
                    first.combine(e);
                }
                Err(first)
            }
        }
    }
}
