//! On error: the `compile_error!` plus a stub of the model's items, so that
//! code using the model (constructing it, calling `mass_matrix`, integrating
//! it) raises no second wave of errors. One mistake, one error.

use crate::ast::ModelDef;
use crate::model::{declared_shape, Field};
use proc_macro2::{Literal, TokenStream};
use quote::quote;
use syn::{Attribute, Ident, Visibility};

/// What the stub needs from the model, taken before lowering consumes it.
pub struct Stub {
    attrs: Vec<Attribute>,
    vis: Visibility,
    name: Ident,
    dof: usize,
    fields: Vec<Field>,
}

impl Stub {
    pub fn of(def: &ModelDef) -> Self {
        let (dof, fields) = declared_shape(def);
        Stub {
            attrs: def.attrs.clone(),
            vis: def.vis.clone(),
            name: def.name.clone(),
            dof,
            fields,
        }
    }

    pub fn emit(&self, error: syn::Error) -> TokenStream {
        let error = error.to_compile_error();
        let Stub {
            attrs,
            vis,
            name,
            dof,
            fields,
        } = self;
        let params: Vec<&Ident> = fields.iter().map(|f| &f.name).collect();
        let types: Vec<TokenStream> = fields.iter().map(Field::rust_type).collect();
        let fields = if params.is_empty() {
            quote!({ _scalar: ::core::marker::PhantomData<S> })
        } else {
            quote!({ #(pub #params: #types,)* })
        };
        let constructor = if params.is_empty() {
            quote!(Self {
                _scalar: ::core::marker::PhantomData
            })
        } else {
            quote!(Self { #(#params,)* })
        };
        let item = quote! {
            #error
            #(#attrs)*
            #[derive(Clone, Copy, Debug, PartialEq)]
            #vis struct #name<S = f64> #fields
        };
        if *dof == 0 {
            return item;
        }
        let na = quote!(::lagrange::nalgebra);
        let n = Literal::usize_unsuffixed(*dof);
        let vector = quote!(#na::SVector<S, #n>);
        let matrix = quote!(#na::SMatrix<S, #n, #n>);
        let stop = quote!(::core::unreachable!(
            "`lagrangian!` reported a compile error for this model"
        ));
        let names = vec![String::new(); *dof];
        quote! {
            #item
            #[allow(unused_variables, clippy::all)]
            impl<S: #na::RealField + ::core::marker::Copy> #name<S> {
                pub const DOF: usize = #n;
                pub const COORDINATES: [&'static str; #n] = [#(#names),*];
                pub const EQUATIONS: &'static str = "";
                pub const fn new(#(#params: #types),*) -> Self { #constructor }
                pub fn mass_matrix(&self, t: S, q: &#vector) -> #matrix { #stop }
                pub fn forcing(&self, t: S, q: &#vector, qdot: &#vector) -> #vector { #stop }
                pub fn mass_matrix_and_forcing(&self, t: S, q: &#vector, qdot: &#vector) -> (#matrix, #vector) { #stop }
                pub fn kinetic_energy(&self, t: S, q: &#vector, qdot: &#vector) -> S { #stop }
                pub fn potential_energy(&self, t: S, q: &#vector) -> S { #stop }
                pub fn energy(&self, t: S, q: &#vector, qdot: &#vector) -> S { #stop }
                pub fn momentum(&self, t: S, q: &#vector, qdot: &#vector) -> #vector { #stop }
                pub fn lagrangian_gradient(&self, t: S, q: &#vector, qdot: &#vector) -> #vector { #stop }
                pub fn nonconservative_forces(&self, t: S, q: &#vector, qdot: &#vector) -> #vector { #stop }
                pub fn residual_jacobians(&self, t: S, q: &#vector, qdot: &#vector, qddot: &#vector) -> (#matrix, #matrix) { #stop }
            }
            #[allow(unused_variables, clippy::all)]
            impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::Lagrangian<#n> for #name<S> {
                type Scalar = S;
                const COORDINATES: [&'static str; #n] = [#(#names),*];
                fn mass_matrix(&self, t: S, q: &#vector) -> #matrix { #stop }
                fn forcing(&self, t: S, q: &#vector, qdot: &#vector) -> #vector { #stop }
                fn kinetic_energy(&self, t: S, q: &#vector, qdot: &#vector) -> S { #stop }
                fn potential_energy(&self, t: S, q: &#vector) -> S { #stop }
            }
        }
    }
}
