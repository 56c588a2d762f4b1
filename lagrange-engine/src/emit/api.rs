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

pub use super::consts::{CONSTS, Const, ConstValue, Doc};
use super::outline::Types;
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
    /// The argument's name in generated code.
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
    /// `SVector<S, C>`, `C` the number of constraints: `C` roots.
    ConstraintVector,
    /// `SMatrix<S, C, N>`: `C·N` roots.
    ConstraintMatrix,
    /// `(SMatrix<S, N, N>, SVector<S, N>, SMatrix<S, C, N>, SVector<S, C>)`:
    /// `N²`, `N`, `C·N` and `C` roots.
    ConstrainedSystem,
    /// `SMatrix<S, N, K>`, `K` the number of inputs: `N·K` roots.
    InputMatrix,
    /// `[S; L]`, `L` the number of `let` values: `L` roots.
    Lets,
    /// `SVector<S, K>`, `K` the number of contacts: `K` roots.
    ContactVector,
    /// `SMatrix<S, K, N>`: `K·N` roots.
    ContactMatrix,
    /// `[ContactLaw<S>; K]`: `4K` roots, each contact's restitution, static
    /// and kinetic friction, and its given normal force (zero, unused,
    /// where it has none).
    ContactLaws,
    /// `SMatrix<S, N, P>`, `P` the number of parameter scalars: `N·P` roots.
    ParameterMatrix,
    /// `[SMatrix<S, N, N>; P]`: `P·N²` roots, matrix after matrix.
    ParameterMatrices,
    /// `SMatrix<S, C, P>`: `C·P` roots.
    ConstraintParameterMatrix,
    /// `SMatrix<S, N, K>`, `K` the regressor's lumped parameters: `N·K`
    /// roots.
    RegressorMatrix,
    /// `SVector<S, K>`: `K` roots.
    RegressorVector,
    /// `lagrange::linalg::articulated::Parts<S, N, D>`, `D` the axes of a
    /// tree of increments: `N·D` axes, `N·D` bends, `N·D` masses joint by
    /// joint, `N` inertias, `N` forces.
    Articulated,
}

impl Returns {
    /// The Rust type of the returned value.
    pub fn ty(self, ty: &Types) -> TokenStream {
        let (vector, matrix) = (&ty.vector, &ty.matrix);
        match self {
            Returns::Scalar => quote!(S),
            Returns::Vector => quote!(#vector),
            Returns::Matrix => quote!(#matrix),
            Returns::MatrixAndVector => quote!((#matrix, #vector)),
            Returns::TwoMatrices => quote!((#matrix, #matrix)),
            Returns::ConstraintVector => ty.constraint_vector.clone(),
            Returns::ConstraintMatrix => ty.constraint_matrix.clone(),
            Returns::ConstrainedSystem => {
                let (cv, cm) = (&ty.constraint_vector, &ty.constraint_matrix);
                quote!((#matrix, #vector, #cm, #cv))
            }
            Returns::InputMatrix => ty.input_matrix.clone(),
            Returns::Lets => ty.lets.clone(),
            Returns::ContactVector => ty.contact_vector.clone(),
            Returns::ContactMatrix => ty.contact_matrix.clone(),
            Returns::ContactLaws => {
                let k = &ty.kc;
                quote!([::lagrange::contact::ContactLaw<S>; #k])
            }
            Returns::ParameterMatrix => ty.parameter_matrix.clone(),
            Returns::ConstraintParameterMatrix => ty.constraint_parameter_matrix.clone(),
            Returns::ParameterMatrices => {
                let p = Literal::usize_unsuffixed(ty.parameters);
                quote!([#matrix; #p])
            }
            Returns::RegressorMatrix => ty.regressor_matrix.clone(),
            Returns::RegressorVector => ty.regressor_vector.clone(),
            Returns::Articulated => {
                let (n, d) = (&ty.n, Literal::usize_unsuffixed(ty.articulated_axes));
                quote!(::lagrange::linalg::articulated::Parts<S, #n, #d>)
            }
        }
    }

    /// The value built from the roots' expressions.
    pub fn assemble(self, ty: &Types, outs: &[TokenStream]) -> TokenStream {
        let (new_vector, new_matrix) = (&ty.new_vector, &ty.new_matrix);
        let square = ty.dof * ty.dof;
        let vector = |f: &[TokenStream]| stored(new_vector, ty.dof, f);
        let matrix = |m: &[TokenStream]| stored(new_matrix, ty.dof, m);
        match self {
            Returns::Scalar => quote!(#(#outs)*),
            Returns::Vector => vector(outs),
            Returns::Matrix => matrix(outs),
            Returns::MatrixAndVector => {
                let (m, f) = outs.split_at(square);
                let (m, f) = (matrix(m), vector(f));
                quote!((#m, #f))
            }
            Returns::TwoMatrices => {
                let (a, b) = outs.split_at(square);
                let (a, b) = (matrix(a), matrix(b));
                quote!((#a, #b))
            }
            Returns::ConstraintVector => {
                let new = &ty.new_constraint_vector;
                quote!(#new(&[#(#outs),*]))
            }
            Returns::ConstraintMatrix => {
                let new = &ty.new_constraint_matrix;
                quote!(#new(&[#(#outs),*]))
            }
            Returns::ConstrainedSystem => {
                let (new_cv, new_cm) = (&ty.new_constraint_vector, &ty.new_constraint_matrix);
                let (m, rest) = outs.split_at(square);
                let (f, rest) = rest.split_at(ty.dof);
                let (g, gamma) = rest.split_at(ty.constraints * ty.dof);
                let (m, f) = (matrix(m), vector(f));
                quote! {
                    (
                        #m,
                        #f,
                        #new_cm(&[#(#g),*]),
                        #new_cv(&[#(#gamma),*]),
                    )
                }
            }
            Returns::InputMatrix => {
                let new = &ty.new_input_matrix;
                quote!(#new(&[#(#outs),*]))
            }
            Returns::Lets => quote!([#(#outs),*]),
            Returns::ContactVector => {
                let new = &ty.new_contact_vector;
                quote!(#new(&[#(#outs),*]))
            }
            Returns::ContactMatrix => {
                let new = &ty.new_contact_matrix;
                quote!(#new(&[#(#outs),*]))
            }
            Returns::ContactLaws => {
                let laws = outs.chunks(4).enumerate().map(|(i, law)| {
                    let (e, s, k, n) = (&law[0], &law[1], &law[2], &law[3]);
                    let normal = if ty.given_normals.get(i).copied().unwrap_or(false) {
                        quote!(::core::option::Option::Some(#n))
                    } else {
                        quote!(::core::option::Option::None)
                    };
                    let in_plane = ty.slip_planes.get(i).copied().unwrap_or(false);
                    quote! {
                        ::lagrange::contact::ContactLaw {
                            restitution: #e,
                            static_friction: #s,
                            kinetic_friction: #k,
                            normal: #normal,
                            in_plane: #in_plane,
                        }
                    }
                });
                quote!([#(#laws),*])
            }
            Returns::ParameterMatrix => {
                let new = &ty.new_parameter_matrix;
                quote!(#new(&[#(#outs),*]))
            }
            Returns::ConstraintParameterMatrix => {
                let new = &ty.new_constraint_parameter_matrix;
                quote!(#new(&[#(#outs),*]))
            }
            Returns::ParameterMatrices => {
                let matrices = outs.chunks(square.max(1)).map(matrix);
                quote!([#(#matrices),*])
            }
            Returns::RegressorMatrix | Returns::RegressorVector => {
                let ty = match self {
                    Returns::RegressorMatrix => &ty.regressor_matrix,
                    _ => &ty.regressor_vector,
                };
                quote!(<#ty>::from_column_slice(&[#(#outs),*]))
            }
            Returns::Articulated => {
                let per_axis = ty.dof * ty.articulated_axes;
                let joints = |outs: &[TokenStream]| {
                    let joints = outs
                        .chunks(ty.articulated_axes.max(1))
                        .map(|joint| quote!([#(#joint),*]));
                    quote!([#(#joints),*])
                };
                let (axes, rest) = outs.split_at(per_axis);
                let (bends, rest) = rest.split_at(per_axis);
                let (masses, rest) = rest.split_at(per_axis);
                let (inertia, forcing) = rest.split_at(ty.dof);
                let (axes, bends, masses) = (joints(axes), joints(bends), joints(masses));
                let forcing = vector(forcing);
                quote! {
                    ::lagrange::linalg::articulated::Parts {
                        axes: #axes,
                        bends: #bends,
                        masses: #masses,
                        inertia: [#(#inertia),*],
                        forcing: #forcing,
                    }
                }
            }
        }
    }
}

/// `path::from_array_storage(ArrayStorage([[column 0], [column 1], …]))`,
/// the entries `outs` in column-major order, `rows` to a column: the
/// matrix written in place, for any scalar. (`from_column_slice` goes
/// through an iterator, which the optimizer reduces to copies for `f64`
/// but not for SIMD lanes, where it took more than the arithmetic.)
pub(crate) fn stored(path: &TokenStream, rows: usize, outs: &[TokenStream]) -> TokenStream {
    let na = super::outline::nalgebra();
    let columns = outs
        .chunks(rows.max(1))
        .map(|column| quote!([#(#column),*]));
    quote!(#path::from_array_storage(#na::ArrayStorage([#(#columns),*])))
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
    /// the impl returns `Some` of zeros if `zero_if_absent` (the model has
    /// them, and they are zero), and leaves the default otherwise.
    Optional {
        /// Whether a model without the method has it as zero.
        zero_if_absent: bool,
    },
    /// Not a method of `Lagrangian` but of `Holonomic<N, C>`, which only a
    /// constrained model implements: its impl calls the inherent one.
    /// `required` methods are implemented by the stub too.
    Holonomic {
        /// Whether the stub implements it too.
        required: bool,
    },
    /// Not a method of `Lagrangian` but of `Contacts<N, K>`, which only a
    /// model with contacts implements: its impl calls the inherent one,
    /// and the stub implements it too.
    Contacts,
    /// Not a method of `Lagrangian` but of `Actuated<N, K>`, which only a
    /// model with inputs implements: its impl calls the inherent one, and
    /// the stub implements it too.
    Actuated,
    /// An inherent method of a model that asked for its parameter
    /// derivatives (`#[lagrange(parameter_derivatives)]`), and of its stub.
    ParameterDerivatives,
    /// An inherent method of a model that asked for its regressor
    /// (`#[lagrange(regressor(..))]`), and of its stub.
    Regressor,
    /// An inherent method only, of every model and of the stub.
    Inherent,
    /// An inherent method (hidden) of a model whose masses hang on a tree
    /// of increments, not of the stub: what the `Lagrangian` impl's
    /// `accelerations` hands the runtime's recursion.
    Articulated,
}

/// A generated method `fn name(&self, args) -> returns`.
pub struct Method {
    /// The method's name.
    pub name: &'static str,
    /// Its doc comment, line by line.
    pub doc: &'static [&'static str],
    /// The arguments after `&self`, in order.
    pub args: &'static [Arg],
    /// What it returns, and how its roots are laid out.
    pub returns: Returns,
    /// The expressions its body computes, laid out as `returns` says;
    /// `None` where the model has no such method (it is then not generated,
    /// but the stub always has it).
    pub roots: fn(&Model, &Equations) -> Option<Vec<ExprId>>,
    /// How it appears in the `Lagrangian` (or `Holonomic`, `Actuated`) impl.
    pub in_trait: InTrait,
}

/// `let_value(name, t, q, q̇)`: one `let` by its name in `LETS`, from
/// `lets`; written the same for a model and for the stub.
pub fn let_value(ty: &Types) -> TokenStream {
    let vector = &ty.vector;
    quote! {
        /// The value of the `let` named `name` (as `LETS` writes it: `x1`,
        /// `x[2]`) at `(t, q, q̇)`; `None` where the model has no such `let`.
        #[inline]
        pub fn let_value(&self, name: &str, t: S, q: &#vector, qdot: &#vector) -> ::core::option::Option<S> {
            let index = Self::LETS.iter().position(|l| *l == name)?;
            ::core::option::Option::Some(self.lets(t, q, qdot)[index])
        }
    }
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
            zero_if_absent: false,
        },
    },
    Method {
        name: "lagrangian_gradient",
        doc: &["`∂L/∂q`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Vector,
        roots: |_, eq| Some(eq.lagrangian_gradient.clone()),
        in_trait: InTrait::Optional {
            zero_if_absent: false,
        },
    },
    Method {
        name: "nonconservative_forces",
        doc: &["The non-conservative generalized forces `Q − ∂R/∂q̇`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Vector,
        // Only a model with forces or dissipation has code for them; a
        // conservative one's are zero, and its impl says so.
        roots: |model, eq| {
            let conservative = model.forces.is_empty() && model.dissipation.is_none();
            (!conservative).then(|| eq.nonconservative.clone())
        },
        in_trait: InTrait::Optional {
            zero_if_absent: true,
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
            zero_if_absent: false,
        },
    },
    Method {
        name: "lets",
        doc: &[
            "Every `let` of the model at `(t, q, q̇)`, in the order of `LETS`:",
            "the positions (and any other quantity) the model names, for",
            "drawing a trajectory without writing the kinematics again.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Lets,
        roots: |model, _| Some(model.lets.iter().map(|(_, id)| *id).collect()),
        in_trait: InTrait::Inherent,
    },
    // Only a model with `constraints:` has the rest.
    Method {
        name: "constraints",
        doc: &["The holonomic constraints `φ(t, q)`, zero on the constraint manifold."],
        args: &[Arg::T, Arg::Q],
        returns: Returns::ConstraintVector,
        roots: |_, eq| Some(eq.constraints.as_ref()?.values.clone()),
        in_trait: InTrait::Holonomic { required: true },
    },
    Method {
        name: "constraint_jacobian",
        doc: &["The constraint Jacobian `G(t, q) = ∂φ/∂q`."],
        args: &[Arg::T, Arg::Q],
        returns: Returns::ConstraintMatrix,
        roots: |model, eq| {
            Some(column_major_of(
                &eq.constraints.as_ref()?.jacobian,
                model.dof(),
            ))
        },
        in_trait: InTrait::Holonomic { required: true },
    },
    Method {
        name: "constraint_velocities",
        doc: &["The constraint velocities `φ̇ = G q̇ + ∂φ/∂t`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ConstraintVector,
        roots: |_, eq| Some(eq.constraints.as_ref()?.velocities.clone()),
        in_trait: InTrait::Holonomic { required: true },
    },
    Method {
        name: "constraint_bias",
        doc: &["The bias `γ(t, q, q̇)` of the constraint accelerations, `φ̈ = G q̈ + γ`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ConstraintVector,
        roots: |_, eq| Some(eq.constraints.as_ref()?.bias.clone()),
        in_trait: InTrait::Holonomic { required: true },
    },
    Method {
        name: "constrained_system",
        doc: &[
            "`M`, `f`, `G` and `γ` together, sharing their common subexpressions:",
            "the saddle-point system `M q̈ + Gᵀλ = f`, `G q̈ = −γ`.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ConstrainedSystem,
        roots: |model, eq| {
            let c = eq.constraints.as_ref()?;
            Some(
                [
                    column_major(&eq.mass),
                    eq.forcing.clone(),
                    column_major_of(&c.jacobian, model.dof()),
                    c.bias.clone(),
                ]
                .concat(),
            )
        },
        in_trait: InTrait::Holonomic { required: false },
    },
    // Only a model with `contacts:` has these.
    Method {
        name: "gaps",
        doc: &["The contacts' gaps `g(t, q)`: positive apart, zero touching."],
        args: &[Arg::T, Arg::Q],
        returns: Returns::ContactVector,
        roots: |_, eq| Some(eq.contacts.as_ref()?.gaps.values.clone()),
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "gap_jacobian",
        doc: &["`G(t, q) = ∂g/∂q`: the normal forces act along its rows."],
        args: &[Arg::T, Arg::Q],
        returns: Returns::ContactMatrix,
        roots: |model, eq| {
            Some(column_major_of(
                &eq.contacts.as_ref()?.gaps.jacobian,
                model.dof(),
            ))
        },
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "gap_velocities",
        doc: &["The gaps' rates `ġ = G q̇ + ∂g/∂t`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ContactVector,
        roots: |_, eq| Some(eq.contacts.as_ref()?.gaps.velocities.clone()),
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "gap_bias",
        doc: &["The bias `γ(t, q, q̇)` of the gaps' accelerations, `g̈ = G q̈ + γ`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ContactVector,
        roots: |_, eq| Some(eq.contacts.as_ref()?.gaps.bias.clone()),
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "slip_jacobian",
        doc: &[
            "`T(t, q)` of the slip velocities `v_t = T q̇ + b`: friction acts along",
            "its rows (zero rows for frictionless contacts).",
        ],
        args: &[Arg::T, Arg::Q],
        returns: Returns::ContactMatrix,
        roots: |model, eq| {
            Some(column_major_of(
                &eq.contacts.as_ref()?.slips.jacobian,
                model.dof(),
            ))
        },
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "slip_velocities",
        doc: &["The slip velocities `v_t` (zero for frictionless contacts)."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ContactVector,
        roots: |_, eq| Some(eq.contacts.as_ref()?.slips.velocities.clone()),
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "slip_bias",
        doc: &["The bias `γ_t` of the slip accelerations, `v̇_t = T q̈ + γ_t`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ContactVector,
        roots: |_, eq| Some(eq.contacts.as_ref()?.slips.bias.clone()),
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "second_slip_jacobian",
        doc: &[
            "`T₂(t, q)` of the slip vectors' second components `v₂ = T₂ q̇ + b₂`",
            "(zero rows for a slip along one direction).",
        ],
        args: &[Arg::T, Arg::Q],
        returns: Returns::ContactMatrix,
        roots: |model, eq| {
            Some(column_major_of(
                &eq.contacts.as_ref()?.second_slips.as_ref()?.jacobian,
                model.dof(),
            ))
        },
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "second_slip_velocities",
        doc: &["The slip vectors' second components `v₂` (zero for a slip along one direction)."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ContactVector,
        roots: |_, eq| {
            Some(
                eq.contacts
                    .as_ref()?
                    .second_slips
                    .as_ref()?
                    .velocities
                    .clone(),
            )
        },
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "second_slip_bias",
        doc: &["The bias `γ₂` of the second components' accelerations, `v̇₂ = T₂ q̈ + γ₂`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ContactVector,
        roots: |_, eq| Some(eq.contacts.as_ref()?.second_slips.as_ref()?.bias.clone()),
        in_trait: InTrait::Contacts,
    },
    Method {
        name: "contact_laws",
        doc: &["Each contact's restitution and friction coefficients."],
        args: &[],
        returns: Returns::ContactLaws,
        roots: |_, eq| Some(eq.contacts.as_ref()?.laws.concat()),
        in_trait: InTrait::Contacts,
    },
    // Only a model with `inputs:` has this one.
    Method {
        name: "input_jacobian",
        doc: &[
            "`∂f/∂u`, `N × K`: how the forcing responds to each control input, at",
            "`(t, q, q̇)` and the inputs the model holds.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::InputMatrix,
        roots: |model, eq| {
            Some(column_major_of(
                eq.input_jacobian.as_ref()?,
                model.inputs.len(),
            ))
        },
        in_trait: InTrait::Actuated,
    },
    // Only a model with `#[lagrange(parameter_derivatives)]` has these.
    Method {
        name: "mass_matrix_parameter_derivatives",
        doc: &[
            "`∂M/∂p_k` at `(t, q)`, one `N × N` matrix per parameter scalar, in",
            "the order of `PARAMETER_SCALARS`.",
        ],
        args: &[Arg::T, Arg::Q],
        returns: Returns::ParameterMatrices,
        roots: |_, eq| {
            Some(
                eq.parameter_derivatives
                    .as_ref()?
                    .mass
                    .iter()
                    .flat_map(column_major)
                    .collect(),
            )
        },
        in_trait: InTrait::ParameterDerivatives,
    },
    Method {
        name: "forcing_parameter_jacobian",
        doc: &[
            "`∂f/∂p`, `N × P`: how the forcing at `(t, q, q̇)` responds to each",
            "parameter scalar, in the order of `PARAMETER_SCALARS`.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ParameterMatrix,
        roots: |model, eq| {
            Some(column_major_of(
                &eq.parameter_derivatives.as_ref()?.forcing,
                model.parameters.len(),
            ))
        },
        in_trait: InTrait::ParameterDerivatives,
    },
    Method {
        name: "residual_parameter_jacobian",
        doc: &[
            "`∂r/∂p = (∂M/∂p) q̈ − ∂f/∂p`, `N × P`, of the residual",
            "`r = M(t, q) q̈ − f(t, q, q̇)`: what a forward sensitivity adds to",
            "the residual's Jacobians.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot, Arg::Qddot],
        returns: Returns::ParameterMatrix,
        roots: |model, eq| {
            Some(column_major_of(
                &eq.parameter_derivatives.as_ref()?.residual,
                model.parameters.len(),
            ))
        },
        in_trait: InTrait::ParameterDerivatives,
    },
    // Only a model with `#[lagrange(regressor(..))]` has these.
    Method {
        name: "regressor",
        doc: &[
            "The regressor `Y`, `N × K`: `M q̈ − f = Y π + r₀` at `(t, q, q̇, q̈)`,",
            "`π` the lumped parameters (`regressor_parameters`, named by",
            "`REGRESSOR_PARAMETERS`), `r₀` the terms free of them",
            "(`regressor_offset`).",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot, Arg::Qddot],
        returns: Returns::RegressorMatrix,
        roots: |_, eq| {
            let r = eq.regressor.as_ref()?;
            Some(column_major_of(&r.columns, r.names.len()))
        },
        in_trait: InTrait::Regressor,
    },
    Method {
        name: "regressor_offset",
        doc: &[
            "`r₀`, the terms of `M q̈ − f` free of the regressor's parameters",
            "(a given force, a known mass), at `(t, q, q̇, q̈)`.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot, Arg::Qddot],
        returns: Returns::Vector,
        roots: |_, eq| Some(eq.regressor.as_ref()?.offset.clone()),
        in_trait: InTrait::Regressor,
    },
    Method {
        name: "regressor_parameters",
        doc: &[
            "The lumped parameters `π` at the model's parameter values, in the",
            "order of `REGRESSOR_PARAMETERS`.",
        ],
        args: &[],
        returns: Returns::RegressorVector,
        roots: |_, eq| Some(eq.regressor.as_ref()?.parameters.clone()),
        in_trait: InTrait::Regressor,
    },
    // Only a constrained model with `#[lagrange(parameter_derivatives)]`.
    Method {
        name: "constraint_parameter_jacobian",
        doc: &[
            "`∂φ/∂p`, `C × P`: how the constraints at `(t, q)` move with each",
            "parameter scalar (a zero row for a velocity constraint).",
        ],
        args: &[Arg::T, Arg::Q],
        returns: Returns::ConstraintParameterMatrix,
        roots: |model, eq| constraint_parameter_roots(model, eq, 0),
        in_trait: InTrait::ParameterDerivatives,
    },
    Method {
        name: "constraint_velocity_parameter_jacobian",
        doc: &["`∂φ̇/∂p`, `C × P`, of the constraint velocities `φ̇` at `(t, q, q̇)`."],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::ConstraintParameterMatrix,
        roots: |model, eq| constraint_parameter_roots(model, eq, 1),
        in_trait: InTrait::ParameterDerivatives,
    },
    Method {
        name: "constraint_acceleration_parameter_jacobian",
        doc: &[
            "`∂(G q̈ + γ)/∂p`, `C × P`: the constraints at the level of",
            "accelerations, `φ̈ = G q̈ + γ`, differentiated by each parameter.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot, Arg::Qddot],
        returns: Returns::ConstraintParameterMatrix,
        roots: |model, eq| constraint_parameter_roots(model, eq, 2),
        in_trait: InTrait::ParameterDerivatives,
    },
    // Only a model whose masses hang on a tree of increments has this.
    Method {
        name: "articulated_parts",
        doc: &[
            "The joints' axes, bends, masses and inertias, and the forces other",
            "than the kinetic energy's, at `(t, q, q̇)`: what",
            "`lagrange::linalg::articulated::accelerations` solves `M q̈ = f`",
            "from in `O(N)`, without `M`.",
        ],
        args: &[Arg::T, Arg::Q, Arg::Qdot],
        returns: Returns::Articulated,
        roots: |_, eq| Some(eq.articulated.as_ref()?.roots.clone()),
        in_trait: InTrait::Articulated,
    },
];

/// One of a constrained model's parameter derivatives (`which`: `∂φ/∂p`,
/// `∂φ̇/∂p`, `∂(G q̈ + γ)/∂p`), column by column.
fn constraint_parameter_roots(model: &Model, eq: &Equations, which: usize) -> Option<Vec<ExprId>> {
    let by = eq.parameter_derivatives.as_ref()?.constraints.as_ref()?;
    Some(column_major_of(&by[which], model.parameters.len()))
}

/// The entries of a square matrix, column by column.
fn column_major(m: &ExprMatrix) -> Vec<ExprId> {
    column_major_of(m, m.len())
}

/// The entries of a matrix with `columns` columns, column by column.
fn column_major_of(m: &ExprMatrix, columns: usize) -> Vec<ExprId> {
    (0..columns)
        .flat_map(|j| m.iter().map(move |row| row[j]))
        .collect()
}

impl Method {
    /// The method's name as an identifier.
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
            InTrait::Required
            | InTrait::Provided
            | InTrait::Holonomic { .. }
            | InTrait::Contacts
            | InTrait::Actuated
            | InTrait::ParameterDerivatives
            | InTrait::Regressor
            | InTrait::Inherent
            | InTrait::Articulated => self.signature_returning(ty, returns),
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
