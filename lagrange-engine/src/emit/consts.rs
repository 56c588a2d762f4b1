//! The generated consts, described once like the methods of
//! [`api`](super::api): name, docs, and the value of a derived model or of
//! the error stub.

use super::outline::Outline;
use crate::model::Model;
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

/// A generated associated `const`.
pub struct Const {
    /// The const's name.
    pub name: &'static str,
    /// Its doc comment.
    pub doc: Doc,
    /// What it holds.
    pub value: ConstValue,
}

/// A doc comment.
pub enum Doc {
    /// Written as `///` lines.
    Lines(&'static [&'static str]),
    /// Written as one `#[doc = "..."]`.
    Attribute(&'static str),
}

/// What a generated `const` holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConstValue {
    /// `usize`: the number of coordinates.
    Dof,
    /// `[&'static str; N]`: the coordinates' names (empty in the stub).
    CoordinateNames,
    /// `[&'static str; P]`: the parameter fields' names (not in the stub).
    ParameterNames,
    /// `[&'static str; P]`: the parameter scalars' names, an indexed
    /// parameter flattened (`m[0]`, ...), the columns of the parameter
    /// derivatives; only with `#[lagrange(parameter_derivatives)]` (empty
    /// in the stub).
    ParameterScalarNames,
    /// `[&'static str; K]`: the regressor's lumped parameters' names; only
    /// with `#[lagrange(regressor(..))]` (empty strings in the stub).
    RegressorNames,
    /// `[&'static str; K]`: the inputs' names, flattened (`tau[0]`, ...);
    /// empty in the stub, absent from a model without inputs.
    InputNames,
    /// `[&'static str; C]`: the constraints' names (empty in the stub;
    /// absent from a model without constraints).
    ConstraintNames,
    /// `[&'static str; K]`: the contacts' names (empty in the stub;
    /// absent from a model without contacts).
    ContactNames,
    /// `[&'static str; L]`: the `let` values' names, an indexed `let`
    /// flattened (`x[0]`, ...); empty strings in the stub.
    LetNames,
    /// `&'static str`: the derived equations as text (empty in the stub).
    EquationsText,
    /// `&'static str`: the derived equations as LaTeX (empty in the stub).
    EquationsLatex,
}

/// Every generated `const`, in the order of the generated impl.
pub const CONSTS: &[Const] = &[
    Const {
        name: "DOF",
        doc: Doc::Lines(&["Number of degrees of freedom (generalized coordinates)."]),
        value: ConstValue::Dof,
    },
    Const {
        name: "COORDINATES",
        doc: Doc::Lines(&["Names of the generalized coordinates, in the order of `q`."]),
        value: ConstValue::CoordinateNames,
    },
    Const {
        name: "CONSTRAINTS",
        doc: Doc::Lines(&["Names of the holonomic constraints, in the order of `φ`."]),
        value: ConstValue::ConstraintNames,
    },
    Const {
        name: "CONTACTS",
        doc: Doc::Lines(&["Names of the contacts, in the order of the gaps `g`."]),
        value: ConstValue::ContactNames,
    },
    Const {
        name: "PARAMETERS",
        doc: Doc::Lines(&[
            "Names of the runtime parameters (the struct's fields; an",
            "indexed parameter `m[N]` is one field `m: [S; N]`), in",
            "declaration order.",
        ]),
        value: ConstValue::ParameterNames,
    },
    Const {
        name: "PARAMETER_SCALARS",
        doc: Doc::Lines(&[
            "Names of the parameter scalars (an indexed parameter `m[N]` is",
            "`m[0]` … `m[N-1]`), in the order of the columns of the parameter",
            "derivatives (`#[lagrange(parameter_derivatives)]`).",
        ]),
        value: ConstValue::ParameterScalarNames,
    },
    Const {
        name: "REGRESSOR_PARAMETERS",
        doc: Doc::Lines(&[
            "Names of the regressor's lumped parameters `π`, each the products",
            "of the listed parameters it sums (`m2*l1*l2`, `m[1]*l[0]^2 + m[2]*l[0]^2`),",
            "in the order of the regressor's columns (`#[lagrange(regressor(..))]`).",
        ]),
        value: ConstValue::RegressorNames,
    },
    Const {
        name: "INPUTS",
        doc: Doc::Lines(&[
            "Names of the control inputs, in the order of `u` (an indexed",
            "input `tau[N]` is `tau[0]` … `tau[N-1]`).",
        ]),
        value: ConstValue::InputNames,
    },
    Const {
        name: "LETS",
        doc: Doc::Lines(&[
            "Names of the `let` values, in the order of `lets` (an indexed",
            "`let x[i in 0..N]` is `x[0]` … `x[N-1]`).",
        ]),
        value: ConstValue::LetNames,
    },
    Const {
        name: "EQUATIONS",
        doc: Doc::Attribute(
            "The derived equations `M q̈ = f`, readable: shared subexpressions first, then each entry.",
        ),
        value: ConstValue::EquationsText,
    },
    Const {
        name: "LATEX",
        doc: Doc::Attribute(
            "The derived equations as LaTeX: one `aligned` block, the same entries as `EQUATIONS`.",
        ),
        value: ConstValue::EquationsLatex,
    },
];

impl Const {
    /// `const NAME: type = value;`, with the values of a derived model
    /// (`derived`: its coordinates' names and equations text) or of the
    /// stub (`None`); `None` if the stub has no such const.
    pub fn item(
        &self,
        outline: &Outline,
        derived: Option<(&Model, (&str, &str))>,
    ) -> Option<TokenStream> {
        let name = Ident::new(self.name, Span::call_site());
        let n = Literal::usize_unsuffixed(outline.dof);
        let (ty, value) = match (self.value, derived) {
            (ConstValue::Dof, _) => (quote!(usize), quote!(#n)),
            (ConstValue::CoordinateNames, Some((model, _))) => {
                let names = model.coordinates.iter().map(|c| c.to_string());
                (quote!([&'static str; #n]), quote!([#(#names),*]))
            }
            // `[""; N]`, not N empty strings: a model with an error may
            // declare a great many coordinates.
            (ConstValue::CoordinateNames, None) => (quote!([&'static str; #n]), quote!([""; #n])),
            (ConstValue::ParameterNames, Some(_)) => {
                let p = Literal::usize_unsuffixed(outline.fields.len());
                let names = outline.fields.iter().map(|f| f.name.to_string());
                (quote!([&'static str; #p]), quote!([#(#names),*]))
            }
            (ConstValue::ParameterNames, None) => return None,
            (ConstValue::ParameterScalarNames, _) if !outline.parameter_derivatives => {
                return None;
            }
            (ConstValue::ParameterScalarNames, Some((model, _))) => {
                let p = Literal::usize_unsuffixed(model.parameters.len());
                let names = model.parameters.iter().map(|p| p.to_string());
                (quote!([&'static str; #p]), quote!([#(#names),*]))
            }
            (ConstValue::ParameterScalarNames, None) => {
                let len: usize = outline.fields.iter().map(|f| f.len.unwrap_or(1)).sum();
                let p = Literal::usize_unsuffixed(len);
                (quote!([&'static str; #p]), quote!([""; #p]))
            }
            (ConstValue::RegressorNames, _) => {
                let names = outline.regressor?;
                let k = Literal::usize_unsuffixed(names.len());
                (quote!([&'static str; #k]), quote!([#(#names),*]))
            }
            (ConstValue::InputNames, _) if outline.inputs.is_empty() => return None,
            (ConstValue::InputNames, Some((model, _))) => {
                let k = Literal::usize_unsuffixed(model.inputs.len());
                let names = model.inputs.iter().map(|u| u.to_string());
                (quote!([&'static str; #k]), quote!([#(#names),*]))
            }
            (ConstValue::InputNames, None) => {
                let len: usize = outline.inputs.iter().map(|f| f.len.unwrap_or(1)).sum();
                let k = Literal::usize_unsuffixed(len);
                (quote!([&'static str; #k]), quote!([""; #k]))
            }
            (ConstValue::ConstraintNames, _) if outline.constraints == 0 => return None,
            (ConstValue::ConstraintNames, Some((model, _))) => {
                let c = Literal::usize_unsuffixed(outline.constraints);
                let names = model.constraints.iter().map(|c| &c.label);
                (quote!([&'static str; #c]), quote!([#(#names),*]))
            }
            (ConstValue::ConstraintNames, None) => {
                let c = Literal::usize_unsuffixed(outline.constraints);
                (quote!([&'static str; #c]), quote!([""; #c]))
            }
            (ConstValue::ContactNames, _) if outline.contacts == 0 => return None,
            (ConstValue::ContactNames, Some((model, _))) => {
                let k = Literal::usize_unsuffixed(outline.contacts);
                let names = model.contacts.iter().map(|c| &c.label);
                (quote!([&'static str; #k]), quote!([#(#names),*]))
            }
            (ConstValue::ContactNames, None) => {
                let k = Literal::usize_unsuffixed(outline.contacts);
                (quote!([&'static str; #k]), quote!([""; #k]))
            }
            (ConstValue::LetNames, Some((model, _))) => {
                let l = Literal::usize_unsuffixed(model.lets.len());
                let names = model.lets.iter().map(|(name, _)| name);
                (quote!([&'static str; #l]), quote!([#(#names),*]))
            }
            (ConstValue::LetNames, None) => {
                let l = Literal::usize_unsuffixed(outline.lets);
                (quote!([&'static str; #l]), quote!([""; #l]))
            }
            (ConstValue::EquationsText, Some((_, (text, _)))) => {
                (quote!(&'static str), quote!(#text))
            }
            (ConstValue::EquationsLatex, Some((_, (_, latex)))) => {
                (quote!(&'static str), quote!(#latex))
            }
            (ConstValue::EquationsText | ConstValue::EquationsLatex, None) => {
                (quote!(&'static str), quote!(""))
            }
        };
        Some(quote!(pub const #name: #ty = #value;))
    }
}

impl Doc {
    /// The doc attributes, token for token what `///` lines (or
    /// `#[doc = "..."]`) written in a `quote!` give.
    pub fn attributes(&self) -> TokenStream {
        match self {
            Doc::Lines(lines) => lines.iter().map(|l| line_doc(l)).collect(),
            Doc::Attribute(text) => quote!(#[doc = #text]),
        }
    }
}

/// `/// line` as the compiler desugars it: `#[doc = r" line"]`.
fn line_doc(line: &str) -> TokenStream {
    // The fewest `#` that no `"` in the line is followed by.
    let hashes = (0..)
        .find(|&k| !line.contains(&format!("\"{}", "#".repeat(k))))
        .map_or(String::new(), |k| "#".repeat(k));
    let literal: Literal = format!("r{hashes}\" {line}\"{hashes}")
        .parse()
        .expect("a raw string of static doc text lexes");
    quote!(#[doc = #literal])
}
