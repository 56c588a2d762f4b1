//! The items of a model with control inputs (`inputs:`) that are not
//! expressions: reading and setting the input fields, and the
//! `Actuated<N, K>` impl. They depend on the fields alone, so the error
//! stub writes the same ones.

use super::outline::{Outline, Types, nalgebra};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// Each input scalar as a place of `self`: `self.force`, `self.tau[0]`, …
fn places(outline: &Outline) -> Vec<TokenStream> {
    outline
        .inputs
        .iter()
        .flat_map(|f| {
            let name = &f.name;
            match f.len {
                None => vec![quote!(self.#name)],
                Some(len) => (0..len)
                    .map(|k| {
                        let k = Literal::usize_unsuffixed(k);
                        quote!(self.#name[#k])
                    })
                    .collect(),
            }
        })
        .collect()
}

/// `inputs`, `set_inputs` and `with_inputs`, for the inherent impl; nothing
/// for a model without inputs.
pub(crate) fn inherent_methods(outline: &Outline, types: &Types) -> TokenStream {
    if outline.inputs.is_empty() {
        return TokenStream::new();
    }
    let (vector, na, k) = (&types.input_vector, nalgebra(), &types.k);
    let places = places(outline);
    let index = (0..places.len()).map(Literal::usize_unsuffixed);
    quote! {
        /// The control inputs the model holds, in the order of `INPUTS` (NaN where never set).
        #[inline]
        pub fn inputs(&self) -> #vector {
            #na::SVector::<S, #k>::from_column_slice(&[#(#places),*])
        }

        /// Sets the control inputs, in the order of `INPUTS`, for the following evaluations.
        #[inline]
        pub fn set_inputs(&mut self, u: &#vector) {
            #(#places = u[#index];)*
        }

        /// This model with constant control inputs `u`, in the order of `INPUTS`: what a run
        /// with inputs that never change integrates (a controller is `with_controller`).
        #[inline]
        #[must_use]
        pub fn with_inputs(mut self, u: &#vector) -> Self {
            self.set_inputs(u);
            self
        }
    }
}

/// `Lagrangian::visit_inputs`: the model hands itself, with its number of
/// inputs, to the runtime's visitor (which reads its `INPUTS` and the
/// values it holds through `Actuated`); `None` for a model without inputs
/// (the trait's default: none).
pub(crate) fn visit_inputs(outline: &Outline, types: &Types) -> Option<TokenStream> {
    if outline.inputs.is_empty() {
        return None;
    }
    let (n, k) = (&types.n, &types.k);
    Some(quote! {
        #[inline]
        fn visit_inputs<V: ::lagrange::inputs::Visitor<S, #n>>(&self, visitor: V) -> ::core::option::Option<V::Output> {
            ::core::option::Option::Some(visitor.visit::<Self, #k>(self))
        }
    })
}

/// `impl Actuated<N, K>`, its `input_jacobian` being `jacobian` (a call
/// of the inherent method, or the stub's `unreachable!`); nothing for a
/// model without inputs.
pub(crate) fn actuated_impl(
    outline: &Outline,
    types: &Types,
    jacobian: TokenStream,
) -> TokenStream {
    if outline.inputs.is_empty() {
        return TokenStream::new();
    }
    let (na, name) = (nalgebra(), outline.name);
    let (n, k, vector) = (&types.n, &types.k, &types.input_vector);
    quote! {
        impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::Actuated<#n, #k> for #name<S> {
            const INPUTS: [&'static str; #k] = Self::INPUTS;
            #[inline]
            fn inputs(&self) -> #vector {
                #name::inputs(self)
            }
            #[inline]
            fn set_inputs(&mut self, u: &#vector) {
                #name::set_inputs(self, u)
            }
            #jacobian
        }
    }
}
