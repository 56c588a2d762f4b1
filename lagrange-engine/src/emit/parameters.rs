//! `impl ParameterDerivatives<N, P>` for a model written with
//! `#[lagrange(parameter_derivatives)]`, shared with the stub: the
//! parameter scalars' names, their values read and set in the order of
//! `PARAMETER_SCALARS` (an indexed parameter `m[N]` is `m[0]` … `m[N-1]`),
//! and the generated derivatives, each a call of the inherent method.

use super::outline::{Outline, Types, domain_tokens, nalgebra};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// The impl, with `methods` (the trait's derivatives, calls of the inherent
/// ones or the stub's); nothing for a model that did not ask for it.
pub fn parameters_impl(outline: &Outline, ty: &Types, methods: Vec<TokenStream>) -> TokenStream {
    if !outline.parameter_derivatives {
        return TokenStream::new();
    }
    let na = nalgebra();
    let name = outline.name;
    let (n, p) = (&ty.n, Literal::usize_unsuffixed(ty.parameters));
    // Each parameter scalar as a place: `self.m1`, `self.l[0]`, ...
    let places: Vec<TokenStream> = outline
        .fields
        .iter()
        .flat_map(|f| {
            let field = &f.name;
            match f.len {
                None => vec![quote!(self.#field)],
                Some(len) => (0..len)
                    .map(|i| {
                        let i = Literal::usize_unsuffixed(i);
                        quote!(self.#field[#i])
                    })
                    .collect(),
            }
        })
        .collect();
    let indices = (0..places.len()).map(Literal::usize_unsuffixed);
    // Each parameter scalar's domain, where any is declared.
    let domains = outline.fields.iter().any(|f| f.domain.is_some()).then(|| {
        let each = outline.fields.iter().flat_map(|f| {
            let domain = domain_tokens(f.domain);
            std::iter::repeat_n(domain, f.len.unwrap_or(1))
        });
        quote!(const DOMAINS: [::lagrange::Domain; #p] = [#(#each),*];)
    });
    // The sensitivities' size along every number of directions the model
    // has (each parameter scalar, initial position and velocity), so that
    // `Sensitivity::new` and `identify::fit` infer it.
    let augmented = (1..=ty.parameters + 2 * ty.dof).map(|d| {
        let na = Literal::usize_unsuffixed(ty.dof * (1 + d));
        let d = Literal::usize_unsuffixed(d);
        quote!(impl<S> ::lagrange::sensitivity::Augmented<#d, #na> for #name<S> {})
    });
    quote! {
        #(#augmented)*
        impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::ParameterDerivatives<#n, #p> for #name<S> {
            const PARAMETERS: [&'static str; #p] = Self::PARAMETER_SCALARS;
            #domains
            #[inline]
            fn parameter_values(&self) -> #na::SVector<S, #p> {
                #na::SVector::<S, #p>::from_column_slice(&[#(#places),*])
            }
            #[inline]
            fn set_parameter_values(&mut self, values: &#na::SVector<S, #p>) {
                let _ = values;
                #(#places = values[#indices];)*
            }
            #(#methods)*
        }
    }
}
