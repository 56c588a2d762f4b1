//! `lagrangian!`: see the `lagrange` crate.

#![deny(missing_docs)]

use proc_macro::TokenStream;

/// Derive the Euler–Lagrange equations of a model at compile time.
#[proc_macro]
pub fn lagrangian(input: TokenStream) -> TokenStream {
    lagrange_engine::expand(input.into()).into()
}
