//! The generated API, described once: every const and method a model gets,
//! with its signature, its docs, what its body computes, and how it appears
//! in the `Lagrangian` impl and in the error stub. [`emit`](super::emit)
//! writes the items of a derived model from these tables;
//! [`fallback`](crate::fallback) writes the stub of a model with an error
//! from the same tables, so the two cannot drift apart.
//!
//! To add an output: compute its expressions in [`derive`](mod@crate::derive)
//! (a field of `Equations`), then add one [`Method`] to [`METHODS`] whose
//! `roots` returns them in the layout of its [`Returns`]; the impl, the
//! `Lagrangian` impl and the stub follow. (A method new to the `Lagrangian`
//! trait is also declared there, in `lagrange-runtime`.)

use super::outline::{Outline, Types};
use crate::derive::{Equations, ExprMatrix};
use crate::expr::ExprId;
use crate::model::Model;
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

/// An argument of a generated method, after `&self`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arg {
    /// `t: S`.
    T,
    /// `q: &SVector<S, N>`.
    Q,
    /// `qdot: &SVector<S, N>`.
    Qdot,
    /// `qddot: &SVector<S, N>` (only the residual's Jacobians read it).
    Qddot,
}

impl Arg {
    pub fn ident(self) -> Ident {
        let name = match self {
            Arg::T => "t",
            Arg::Q => "q",
            Arg::Qdot => "qdot",
            Arg::Qddot => "qddot",
        };
        Ident::new(name, Span::call_site())
    }

    fn declaration(self, ty: &Types) -> TokenStream {
        let name = self.ident();
        let vector = &ty.vector;
        match self {
            Arg::T => quote!(#name: S),
            _ => quote!(#name: &#vector),
        }
    }
}

/// What a method returns, `N` being the number of coordinates, and how its
/// roots are laid out (matrices column-major, as nalgebra stores them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Returns {
    /// `S`: one root.
    Scalar,
    /// `SVector<S, N>`: `N` roots.
    Vector,
    /// `SMatrix<S, N, N>`: `N²` roots.
    Matrix,
    /// `(SMatrix<S, N, N>, SVector<S, N>)`: `N²` roots, then `N`.
    MatrixAndVector,
    /// `(SMatrix<S, N, N>, SMatrix<S, N, N>)`: `N²` roots, then `N²`.
    TwoMatrices,
}

impl Returns {
    pub fn ty(self, ty: &Types) -> TokenStream {
        let (vector, matrix) = (&ty.vector, &ty.matrix);
        match self {
            Returns::Scalar => quote!(S),
            Returns::Vector => quote!(#vector),
            Returns::Matrix => quote!(#matrix),
            Returns::MatrixAndVector => quote!((#matrix, #vector)),
            Returns::TwoMatrices => quote!((#matrix, #matrix)),
        }
    }

    /// The value built from the roots' expressions.
    pub fn assemble(self, ty: &Types, outs: &[TokenStream]) -> TokenStream {
        let (new_vector, new_matrix) = (&ty.new_vector, &ty.new_matrix);
        let square = ty.dof * ty.dof;
        match self {
            Returns::Scalar => quote!(#(#outs)*),
            Returns::Vector => quote!(#new_vector(&[#(#outs),*])),
            Returns::Matrix => quote!(#new_matrix(&[#(#outs),*])),
            Returns::MatrixAndVector => {
                let (m, f) = outs.split_at(square);
                quote! {
                    (
                        #new_matrix(&[#(#m),*]),
                        #new_vector(&[#(#f),*]),
                    )
                }
            }
            Returns::TwoMatrices => {
                let (a, b) = outs.split_at(square);
                quote!((#new_matrix(&[#(#a),*]), #new_matrix(&[#(#b),*])))
            }
        }
    }
}

/// How a method appears in the `impl Lagrangian`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InTrait {
    /// A required method: the impl calls the inherent one, and the stub
    /// implements it too.
    Required,
    /// A provided method, overridden by a call of the inherent one.
    Provided,
    /// A provided method returning `Option` (`None` by default): the impl
    /// returns `Some` of the inherent one. Where a model has no such method,
    /// the impl sets `flag_if_absent` (if any) to `true` instead.
    Optional {
        flag_if_absent: Option<&'static str>,
    },
}

/// A generated method `fn name(&self, args) -> returns`.
pub struct Method {
    pub name: &'static str,
    /// Its doc comment, line by line.
    pub doc: &'static [&'static str],
    pub args: &'static [Arg],
    pub returns: Returns,
    /// The expressions its body computes, laid out as `returns` says;
    /// `None` where the model has no such method (it is then not generated,
    /// but the stub always has it).
    pub roots: fn(&Model, &Equations) -> Option<Vec<ExprId>>,
    pub in_trait: InTrait,
}

/// Every generated method, in the order of the generated impls.
pub const METHODS: &[Method] = &[
    Method {
        name: "mass_matrix",
        doc: &["The mass matrix `M(t, q) = ∂²T/∂q̇²`."],
        args: &[Arg::T, Arg::Q],
        returns: Returns::Matrix,
        roots: |_, eq| Some(column_major(&eq.mass)),
        in_trait: InTrait::Required,
    },
    Method {
        name: "forcing",
        doc: &["The forcing `f(t, q, q̇)` of `M q̈ = f`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Vector,
        roots: |_, eq| Some(eq.forcing.clone()),
        in_trait: InTrait::Required,
    },
    Method {
        name: "mass_matrix_and_forcing",
        doc: &["`M` and `f` together, sharing their common subexpressions."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::MatrixAndVector,
        roots: |_, eq| Some([column_major(&eq.mass), eq.forcing.clone()].concat()),
        in_trait: InTrait::Provided,
    },
    Method {
        name: "kinetic_energy",
        doc: &["Kinetic energy `T(t, q, q̇)`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Scalar,
        roots: |model, _| Some(vec![model.kinetic.value]),
        in_trait: InTrait::Required,
    },
    Method {
        name: "potential_energy",
        doc: &["Potential energy `V(t, q)`."],
        args: &[Arg::T, Arg::Q],
        returns: Returns::Scalar,
        roots: |model, _| Some(vec![model.potential.value]),
        in_trait: InTrait::Required,
    },
    Method {
        name: "energy",
        doc: &["Total energy `T + V`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Scalar,
        roots: |_, eq| Some(vec![eq.energy]),
        in_trait: InTrait::Provided,
    },
    Method {
        name: "momentum",
        doc: &["The generalized momenta `p = ∂L/∂q̇`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Vector,
        roots: |_, eq| Some(eq.momenta.clone()),
        in_trait: InTrait::Optional {
            flag_if_absent: None,
        },
    },
    Method {
        name: "lagrangian_gradient",
        doc: &["`∂L/∂q`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Vector,
        roots: |_, eq| Some(eq.lagrangian_gradient.clone()),
        in_trait: InTrait::Optional {
            flag_if_absent: None,
        },
    },
    Method {
        name: "nonconservative_forces",
        doc: &["The non-conservative generalized forces `Q − ∂R/∂q̇`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Vector,
        // Only a model with forces or dissipation has them; a conservative
        // one says so and emits no code for them.
        roots: |model, eq| {
            let conservative = model.forces.is_empty() && model.dissipation.is_none();
            (!conservative).then(|| eq.nonconservative.clone())
        },
        in_trait: InTrait::Optional {
            flag_if_absent: Some("CONSERVATIVE"),
        },
    },
    Method {
        name: "residual_jacobians",
        doc: &[
            "The exact Jacobians `(∂r/∂q, ∂r/∂q̇)` of the residual",
            "`r = M(t, q) q̈ − f(t, q, q̇)`, for implicit integrators.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot, Arg::Qddot],
        returns: Returns::TwoMatrices,
        // Opt-in, `#[lagrange(jacobians)]`: ∂r/∂q, then ∂r/∂q̇.
        roots: |_, eq| {
            let (jq, jv) = eq.jacobians.as_ref()?;
            Some([column_major(jq), column_major(jv)].concat())
        },
        in_trait: InTrait::Optional {
            flag_if_absent: None,
        },
    },
];

/// The entries of a square matrix, column by column.
fn column_major(m: &ExprMatrix) -> Vec<ExprId> {
    let n = m.len();
    (0..n).flat_map(|j| (0..n).map(move |i| m[i][j])).collect()
}

impl Method {
    pub fn ident(&self) -> Ident {
        Ident::new(self.name, Span::call_site())
    }

    /// `fn name(&self, args) -> returns`.
    pub fn signature(&self, ty: &Types) -> TokenStream {
        self.signature_returning(ty, self.returns.ty(ty))
    }

    /// The signature in the `impl Lagrangian`: an optional method returns
    /// an `Option`.
    pub fn trait_signature(&self, ty: &Types) -> TokenStream {
        let returns = self.returns.ty(ty);
        match self.in_trait {
            InTrait::Optional { .. } => {
                self.signature_returning(ty, quote!(::core::option::Option<#returns>))
            }
            InTrait::Required | InTrait::Provided => self.signature_returning(ty, returns),
        }
    }

    fn signature_returning(&self, ty: &Types, returns: TokenStream) -> TokenStream {
        let name = self.ident();
        let args = self.args.iter().map(|a| a.declaration(ty));
        quote!(fn #name(&self, #(#args),*) -> #returns)
    }

    /// The argument names, for a call.
    pub fn arg_idents(&self) -> Vec<Ident> {
        self.args.iter().map(|a| a.ident()).collect()
    }
}

/// A generated associated `const`.
pub struct Const {
    pub name: &'static str,
    pub doc: Doc,
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
    /// `&'static str`: the derived equations as text (empty in the stub).
    EquationsText,
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
        name: "PARAMETERS",
        doc: Doc::Lines(&[
            "Names of the runtime parameters (the struct's fields; an",
            "indexed parameter `m[N]` is one field `m: [S; N]`), in",
            "declaration order.",
        ]),
        value: ConstValue::ParameterNames,
    },
    Const {
        name: "EQUATIONS",
        doc: Doc::Attribute(
            "The derived equations `M q̈ = f`, readable: shared subexpressions first, then each entry.",
        ),
        value: ConstValue::EquationsText,
    },
];

impl Const {
    /// `const NAME: type = value;`, with the values of a derived model
    /// (`derived`: its coordinates' names and equations text) or of the
    /// stub (`None`); `None` if the stub has no such const.
    pub fn item(&self, outline: &Outline, derived: Option<(&Model, &str)>) -> Option<TokenStream> {
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
            (ConstValue::EquationsText, Some((_, text))) => (quote!(&'static str), quote!(#text)),
            (ConstValue::EquationsText, None) => (quote!(&'static str), quote!("")),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_doc_line_makes_a_doc_attribute() {
        for m in METHODS {
            assert!(!Doc::Lines(m.doc).attributes().is_empty(), "{}", m.name);
        }
        for c in CONSTS {
            assert!(!c.doc.attributes().is_empty(), "{}", c.name);
        }
        assert_eq!(
            line_doc(r#"say "hi""#).to_string(),
            r####"# [doc = r#" say "hi""#]"####
        );
    }

    #[test]
    fn methods_are_named_once() {
        for (k, m) in METHODS.iter().enumerate() {
            assert!(METHODS[..k].iter().all(|o| o.name != m.name), "{}", m.name);
        }
    }
}
