//! On error: the `compile_error!` plus a stub of the model's items, so that
//! code using the model (constructing it, calling `mass_matrix`, integrating
//! it) raises no second wave of errors. One mistake, one error.
//!
//! The stub has the struct, the consts and every method of
//! [`api`](crate::emit::api), each method's body `unreachable!()`, and the
//! `Lagrangian` impl's required methods; a model that declares constraints
//! also gets their methods and the `Holonomic` impl's required ones, and a
//! model that declares inputs their fields, `INPUTS`, the methods that read
//! and set them and the `Actuated` impl; a model that asks for its
//! parameter derivatives, those methods, `PARAMETER_SCALARS` and the
//! `ParameterDerivatives` impl.

use crate::ast::ModelDef;
use crate::emit::api::{CONSTS, InTrait, METHODS, Returns};
use crate::emit::inputs;
use crate::emit::outline::{Outline, Types, nalgebra};
use crate::model::{Field, declared_shape};
use proc_macro2::TokenStream;
use quote::quote;
use syn::{Attribute, Ident, Visibility};

/// What the stub needs from the model, taken before lowering consumes it.
pub struct Stub {
    attrs: Vec<Attribute>,
    vis: Visibility,
    name: Ident,
    dof: usize,
    fields: Vec<Field>,
    inputs: Vec<Field>,
    constraints: usize,
    contacts: usize,
    lets: usize,
    serde: bool,
    parameter_derivatives: bool,
    /// One empty name per scalar of the parameters `regressor(..)` lists
    /// (the lumped ones are known only once derived).
    regressor: Option<Vec<String>>,
}

impl Stub {
    /// Takes what the stub needs from the parsed model.
    pub fn of(def: &ModelDef) -> Self {
        let shape = declared_shape(def);
        let regressor = def.options.regressor.as_ref().map(|listed| {
            let scalars: usize = shape
                .fields
                .iter()
                .filter(|f| listed.contains(&f.name))
                .map(|f| f.len.unwrap_or(1))
                .sum();
            vec![String::new(); scalars.max(1)]
        });
        Stub {
            attrs: def.attrs.clone(),
            vis: def.vis.clone(),
            name: def.name.clone(),
            dof: shape.dof,
            fields: shape.fields,
            inputs: shape.inputs,
            constraints: shape.constraints,
            contacts: shape.contacts,
            lets: shape.lets,
            serde: def.options.serde,
            parameter_derivatives: def.options.parameter_derivatives,
            regressor,
        }
    }

    /// The stub's items, with `error` reported as a compile error.
    pub fn emit(&self, error: syn::Error) -> TokenStream {
        let error = error.to_compile_error();
        let outline = Outline {
            attrs: &self.attrs,
            vis: &self.vis,
            name: &self.name,
            dof: self.dof,
            fields: &self.fields,
            inputs: &self.inputs,
            constraints: self.constraints,
            contacts: self.contacts,
            serde: self.serde,
            parameter_derivatives: self.parameter_derivatives,
            regressor: self.regressor.as_deref(),
            lets: self.lets,
        };
        let item = outline.struct_item();
        if self.dof == 0 {
            return quote!(#error #item);
        }
        let na = nalgebra();
        let name = &self.name;
        let k: usize = self.inputs.iter().map(|f| f.len.unwrap_or(1)).sum();
        let p: usize = self.fields.iter().map(|f| f.len.unwrap_or(1)).sum();
        let types = Types::new(self.dof, self.constraints, k, self.lets)
            .with_contacts(&vec![false; self.contacts])
            .with_parameters(p)
            .with_regressor(self.regressor.as_ref().map_or(0, Vec::len));
        let n = &types.n;
        let stop = quote!(::core::unreachable!(
            "`lagrangian!` reported a compile error for this model"
        ));
        let constrained = self.constraints > 0;
        let actuated = k > 0;
        let consts = CONSTS.iter().filter_map(|c| c.item(&outline, None));
        let new = outline.constructor();
        let methods = METHODS
            .iter()
            .filter(|m| constrained || !matches!(m.in_trait, InTrait::Holonomic { .. }))
            .filter(|m| self.contacts > 0 || m.in_trait != InTrait::Contacts)
            .filter(|m| actuated || m.in_trait != InTrait::Actuated)
            .filter(|m| self.parameter_derivatives || m.in_trait != InTrait::ParameterDerivatives)
            .filter(|m| self.regressor.is_some() || m.in_trait != InTrait::Regressor)
            .filter(|m| constrained || m.returns != Returns::ConstraintParameterMatrix)
            .filter(|m| m.in_trait != InTrait::Articulated)
            .map(|m| {
                let signature = m.signature(&types);
                quote!(pub #signature { #stop })
            });
        let required = METHODS
            .iter()
            .filter(|m| m.in_trait == InTrait::Required)
            .map(|m| {
                let signature = m.trait_signature(&types);
                quote!(#signature { #stop })
            });
        let holonomic = constrained.then(|| {
            let c = &types.c;
            let required = METHODS
                .iter()
                .filter(|m| m.in_trait == InTrait::Holonomic { required: true })
                .map(|m| {
                    let signature = m.trait_signature(&types);
                    quote!(#signature { #stop })
                });
            quote! {
                #[allow(unused_variables, clippy::all)]
                impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::Holonomic<#n, #c> for #name<S> {
                    const CONSTRAINTS: [&'static str; #c] = [""; #c];
                    #(#required)*
                }
            }
        });
        let contacts = (self.contacts > 0).then(|| {
            let kc = &types.kc;
            let required = METHODS
                .iter()
                .filter(|m| m.in_trait == InTrait::Contacts)
                .map(|m| {
                    let signature = m.trait_signature(&types);
                    quote!(#signature { #stop })
                });
            quote! {
                #[allow(unused_variables, clippy::all)]
                impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::contact::Contacts<#n, #kc> for #name<S> {
                    const CONTACTS: [&'static str; #kc] = [""; #kc];
                    #(#required)*
                }
            }
        });
        let input_methods = inputs::inherent_methods(&outline, &types);
        let let_value = crate::emit::api::let_value(&types);
        let jacobian = METHODS
            .iter()
            .filter(|m| m.in_trait == InTrait::Actuated)
            .map(|m| {
                let signature = m.trait_signature(&types);
                quote!(#signature { #stop })
            })
            .collect();
        let actuated = inputs::actuated_impl(&outline, &types, jacobian);
        let actuated = (!actuated.is_empty())
            .then(|| quote!(#[allow(unused_variables, clippy::all)] #actuated));
        let lets = crate::emit::lets_impl(&self.name, &types);
        let lanes = crate::emit::lanes_impl(&outline, &types, None);
        let derivatives = METHODS
            .iter()
            .filter(|m| {
                m.in_trait == InTrait::ParameterDerivatives
                    && m.returns != Returns::ConstraintParameterMatrix
            })
            .map(|m| {
                let signature = m.trait_signature(&types);
                quote!(#signature { #stop })
            })
            .collect();
        let parameters = crate::emit::parameters::parameters_impl(&outline, &types, derivatives);
        let parameters = (!parameters.is_empty())
            .then(|| quote!(#[allow(unused_variables, clippy::all)] #parameters));
        let by_name = outline.by_name();
        quote! {
            #error
            #item
            #by_name
            #[allow(unused_variables, clippy::all)]
            impl<S: #na::SimdRealField + ::core::marker::Copy> #name<S> where
            S::Element: #na::RealField + ::core::marker::Copy,
        {
                #(#consts)*
                pub #new
                #(#methods)*
                #let_value
                #input_methods
            }
            #[allow(unused_variables, clippy::all)]
            impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::Lagrangian<#n> for #name<S> {
                type Scalar = S;
                const COORDINATES: [&'static str; #n] = [""; #n];
                #(#required)*
            }
            #holonomic
            #contacts
            #actuated
            #lets
            #lanes
            #parameters
        }
    }
}
