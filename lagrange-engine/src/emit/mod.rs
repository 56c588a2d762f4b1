//! Model + equations → Rust items: the model's struct, an inherent impl with
//! the consts and methods of [`api`], and the `Lagrangian` impl.
//!
//! Each generated function is straight-line code (`function.rs`): the
//! symbols it reads are destructured once, the constants converted to `S`
//! once, every shared node bound to a `let`, and the result built on the
//! stack. No heap allocation, no branch, no symbolic work at run time.

pub mod api;
mod consts;
mod function;
pub(crate) mod inputs;
mod names;
pub mod outline;
pub(crate) mod parameters;

use crate::derive::Equations;
use crate::derive::articulated::Articulated;
use crate::expr::ExprId;
use crate::model::Model;
use api::{CONSTS, Doc, InTrait, METHODS, Method};
use names::Namer;
use outline::{Outline, Types, nalgebra};
use proc_macro2::{Ident, TokenStream};
use quote::quote;

/// What every item of one model is emitted from.
struct Context<'a> {
    model: &'a Model,
    outline: Outline<'a>,
    types: Types,
    namer: Namer,
    /// The roots of each method of [`METHODS`], `None` if the model has no
    /// such method.
    roots: Vec<Option<Vec<ExprId>>>,
    /// The tree of increments the masses hang on, where they do.
    articulated: Option<&'a Articulated>,
}

/// The generated items of a derived model.
pub fn emit(model: &Model, eq: &Equations, texts: (&str, &str)) -> TokenStream {
    let cx = Context {
        model,
        outline: Outline {
            attrs: &model.attrs,
            vis: &model.vis,
            name: &model.name,
            dof: model.dof(),
            fields: &model.fields,
            inputs: &model.input_fields,
            constraints: model.constraints.len(),
            contacts: model.contacts.len(),
            serde: model.options.serde,
            parameter_derivatives: model.options.parameter_derivatives,
            regressor: eq.regressor.as_ref().map(|r| r.names.as_slice()),
            lets: model.lets.len(),
        },
        types: Types::new(
            model.dof(),
            model.constraints.len(),
            model.inputs.len(),
            model.lets.len(),
        )
        .with_contacts(
            &model
                .contacts
                .iter()
                .map(|c| c.normal.is_some())
                .collect::<Vec<_>>(),
        )
        .with_slip_planes(
            &model
                .contacts
                .iter()
                .map(|c| c.second_slip.is_some())
                .collect::<Vec<_>>(),
        )
        .with_parameters(model.parameters.len())
        .with_regressor(eq.regressor.as_ref().map_or(0, |r| r.names.len()))
        .with_articulated(eq.articulated.as_ref().map_or(0, |a| a.axes)),
        namer: Namer::new(model),
        roots: METHODS.iter().map(|m| (m.roots)(model, eq)).collect(),
        articulated: eq.articulated.as_ref(),
    };
    let item = cx.outline.struct_item();
    let by_name = cx.outline.by_name();
    let inherent = inherent_impl(&cx, texts);
    let lagrangian = lagrangian_impl(&cx);
    let singular_mass = eq
        .constraints
        .as_ref()
        .is_some_and(|c| c.mass_regular_on_constraints_only);
    let velocity_rows = eq
        .constraints
        .as_ref()
        .filter(|c| c.velocity_rows.contains(&true))
        .map(|c| c.velocity_rows.clone());
    let holonomic = holonomic_impl(&cx, singular_mass, velocity_rows);
    let actuated = actuated_impl(&cx);
    let contacts = contacts_impl(&cx);
    let lets = lets_impl(cx.outline.name, &cx.types);
    let lanes = lanes_impl(
        &cx.outline,
        &cx.types,
        cx.articulated
            .map(|_| lane_accelerations(&cx.outline, &cx.types)),
    );
    // The constraints' parameter derivatives stay inherent: the trait
    // (and the sensitivities over it) is of models in minimal coordinates.
    let derivatives =
        forwarding(&cx, |t| t == InTrait::ParameterDerivatives)
            .zip(METHODS.iter().zip(&cx.roots).filter(|(m, roots)| {
                m.in_trait == InTrait::ParameterDerivatives && roots.is_some()
            }))
            .filter(|(_, (m, _))| m.returns != api::Returns::ConstraintParameterMatrix)
            .map(|(tokens, _)| tokens)
            .collect();
    let parameters = parameters::parameters_impl(&cx.outline, &cx.types, derivatives);
    quote! {
        #item
        #by_name
        #inherent
        #lagrangian
        #holonomic
        #contacts
        #actuated
        #lets
        #lanes
        #parameters
    }
}

/// `impl LaneModel<N>`: `M` and `f` on SIMD lanes (the inherent
/// `mass_matrix_and_forcing`, whose bound is `SimdRealField`), what an
/// `Ensemble` steps. Only for a model in minimal coordinates with no
/// inputs and no contacts: the ensemble integrates `M q̈ = f` alone, and
/// would leave out a constraint's, an input's or a contact's part in
/// silence. The same for the error stub, whose inherent method it calls.
/// `accelerations`: a model whose masses hang on a tree of links solves
/// for `q̈` on the lanes as its scalar impl does.
pub(crate) fn lanes_impl(
    outline: &Outline,
    types: &Types,
    accelerations: Option<TokenStream>,
) -> TokenStream {
    if outline.constraints > 0 || outline.contacts > 0 || !outline.inputs.is_empty() {
        return TokenStream::new();
    }
    let na = nalgebra();
    let name = outline.name;
    let (n, vector, matrix) = (&types.n, &types.vector, &types.matrix);
    quote! {
        impl<S: #na::SimdRealField + ::core::marker::Copy> ::lagrange::ensemble::LaneModel<#n> for #name<S>
        where
            S::Element: #na::RealField + ::core::marker::Copy,
        {
            type Lanes = S;
            const COORDINATES: [&'static str; #n] = Self::COORDINATES;
            #[inline(always)]
            fn mass_matrix_and_forcing(&self, t: S, q: &#vector, qdot: &#vector) -> (#matrix, #vector) {
                #name::mass_matrix_and_forcing(self, t, q, qdot)
            }
            #accelerations
        }
    }
}

/// The joints of `a` as the runtime's `Tree`: the inherent impl's
/// `ARTICULATED_TREE`, which every method that calls the runtime's
/// recursion hands over.
fn tree(types: &Types, a: &Articulated) -> TokenStream {
    let n = &types.n;
    let joint = |j: &Option<usize>| match j {
        Some(j) => quote!(#j),
        None => quote!(::lagrange::linalg::articulated::NONE),
    };
    let parent = a.parent.iter().map(joint);
    let base = a.base.iter().map(joint);
    let coordinate = &a.coordinate;
    let scale = a
        .scale
        .iter()
        .map(|&c| proc_macro2::Literal::f64_suffixed(c));
    quote! {
        /// The joints the masses hang on, for the runtime's recursion.
        const ARTICULATED_TREE: ::lagrange::linalg::articulated::Tree<#n> = ::lagrange::linalg::articulated::Tree {
            parent: [#(#parent),*],
            base: [#(#base),*],
            coordinate: [#(#coordinate),*],
            scale: [#(#scale),*],
        };
    }
}

/// `LaneModel::accelerations` of a model whose masses hang on a tree of
/// links: the recursion on the lanes, with the lanes it answers for.
fn lane_accelerations(outline: &Outline, types: &Types) -> TokenStream {
    let name = outline.name;
    let na = nalgebra();
    let vector = &types.vector;
    quote! {
        const SOLVES_ACCELERATIONS: bool = true;
        #[inline(always)]
        fn accelerations(
            &self,
            t: S,
            q: &#vector,
            qdot: &#vector,
        ) -> ::core::option::Option<(#vector, <S as #na::SimdValue>::SimdBool)> {
            let parts = #name::articulated_parts(self, t, q, qdot);
            ::core::option::Option::Some(::lagrange::linalg::articulated::lanes(&Self::ARTICULATED_TREE, &parts, qdot))
        }
    }
}

/// Writing a node costs about this many steps of the budget per operand
/// (its tokens, in each function that needs it), measured against the
/// interning of a node; see [`charge`].
const STEPS_PER_EMITTED_OPERAND: u64 = 24;

/// Charges the pool's budget for emitting the model: the nodes and roots of
/// every generated function and of the equations' text. Emitting is linear
/// in these, so a model whose charge fits the budget is emitted within it;
/// emitting itself charges nothing and checks nothing. Returns the
/// estimated size of the generated functions in bytes
/// ([`BYTES_PER_OPERAND`] per operand written), what
/// [`code_limit_error`] is checked against; the `EQUATIONS` and `LATEX`
/// text is not counted there (string constants cost rustc little).
pub fn charge(model: &Model, eq: &Equations) -> u64 {
    let pool = &model.pool;
    let mut operands = 0u64;
    for roots in METHODS.iter().filter_map(|m| (m.roots)(model, eq)) {
        if pool.exhausted() {
            return 0;
        }
        let (cost, written) = emission(model, &roots);
        operands = operands.saturating_add(written);
        pool.charge(cost);
    }
    // The text is written twice: `EQUATIONS` and `LATEX`.
    let text_roots = crate::render::text_roots(model, eq);
    for _ in 0..2 {
        if pool.exhausted() {
            return 0;
        }
        pool.charge(emission_cost(model, &text_roots));
    }
    operands.saturating_mul(BYTES_PER_OPERAND)
}

/// The bytes of generated code (the functions, as the token stream's
/// text) per operand [`charge`] counts: measured from 7 (the chain of
/// `N` links in absolute angles, `N` = 20 to 60) to 10 (the comb in
/// relative angles, 30 coordinates) on the dense expansions of the
/// large models (`lagrange-engine/tests/engine/articulated.rs`,
/// `the_code_size_estimate_follows_the_code`); the larger, so that the
/// estimate errs on the side of the limit.
pub const BYTES_PER_OPERAND: u64 = 10;

/// The most bytes of generated code a model may expand to unless it says
/// otherwise (`#[lagrange(max_code = N)]`): about 4 MB, which rustc builds
/// within about 10 GB of memory; see `docs/language.md`, Limits.
pub const DEFAULT_MAX_CODE: u64 = 4_000_000;

/// The largest `#[lagrange(max_code = N)]`.
pub const MAX_CODE: u64 = 1_000_000_000;

/// The error of a model whose generated code, estimated at `bytes`
/// ([`charge`]), would be over its limit: what to write instead, on the
/// model's name.
pub fn code_limit_error(model: &Model, bytes: u64) -> Option<syn::Error> {
    let limit = model.options.max_code.unwrap_or(DEFAULT_MAX_CODE);
    if bytes <= limit {
        return None;
    }
    let name = &model.name;
    // The limit suggested: the estimate rounded up, to a megabyte from one.
    let step = if bytes >= 1_000_000 { 1_000_000 } else { 1_000 };
    let tree = "if its masses hang on a tree of links (a chain or tree of point masses and rigid links, in \
                absolute or relative angles), the recursion over the tree solves it without generating `M` and `f`";
    let recursion = if !crate::derive::articulated::may_look_first(&model.options)
        && model.options.articulated != Some(false)
    {
        format!(
            "{tree}: ask for `#[lagrange(articulated)]` without `jacobians`, `parameter_derivatives` and \
             `regressor(..)`, which are derived from them"
        )
    } else if model.options.articulated == Some(false) {
        format!("{tree}: write `#[lagrange(articulated)]` instead of `articulated = false`")
    } else {
        format!("{tree}: write it so, and ask for `#[lagrange(articulated)]`")
    };
    Some(syn::Error::new(
        name.span(),
        format!(
            "the code generated for `{name}` would be about {}, over the limit of {}: rustc's time and memory \
             grow faster than the code (about 5 GB to build 4 MB of it); {recursion}; or make the model smaller \
             (fewer coordinates, or split it); or, if the machine building it has the memory, raise the limit \
             with `#[lagrange(max_code = {})]` on the struct",
            in_words(bytes),
            in_words(limit),
            bytes.div_ceil(step).saturating_mul(step).min(MAX_CODE),
        ),
    ))
}

/// What writing one function of `roots` costs the budget ([`charge`]),
/// after the walk over its nodes that measures it (charged as it goes).
pub(crate) fn emission_cost(model: &Model, roots: &[ExprId]) -> u64 {
    emission(model, roots).0
}

/// [`emission_cost`], and the operands the function writes: its nodes'
/// operands and its roots, what its size grows with.
fn emission(model: &Model, roots: &[ExprId]) -> (u64, u64) {
    let pool = &model.pool;
    // A function's prelude may name every symbol (`let [x, _, z] = ...`).
    let symbols = model.symbols.count() as u64;
    let before = pool.spent();
    // The walk's own charge, beside its nodes': see `Pool::post_order`.
    let overhead = 1 + pool.len() as u64 / 64;
    pool.post_order(roots);
    let walked = pool.spent() - before + roots.len() as u64 + symbols;
    let operands = walked.saturating_sub(overhead + symbols);
    (STEPS_PER_EMITTED_OPERAND * walked, operands)
}

/// A size in bytes as a reader takes it in: `8.4 MB`, `23 KB`, `700 bytes`.
fn in_words(bytes: u64) -> String {
    if bytes >= 1_000_000 {
        format!("{:.1} MB", bytes as f64 / 1e6)
    } else if bytes >= 1_000 {
        format!("{} KB", bytes.div_ceil(1_000))
    } else {
        format!("{bytes} bytes")
    }
}

/// `impl Name<S>`: the consts, `new`, and every method the model has.
fn inherent_impl(cx: &Context, texts: (&str, &str)) -> TokenStream {
    let na = nalgebra();
    let name = cx.outline.name;
    let consts = CONSTS.iter().filter_map(|c| {
        let item = c.item(&cx.outline, Some((cx.model, texts)))?;
        let doc = c.doc.attributes();
        Some(quote!(#doc #item))
    });
    let new_doc = cx.outline.constructor_doc();
    let new = cx.outline.constructor();
    let methods = METHODS
        .iter()
        .zip(&cx.roots)
        .filter_map(|(m, roots)| Some(method(cx, m, roots.as_ref()?)));
    let inputs = inputs::inherent_methods(&cx.outline, &cx.types);
    let let_value = api::let_value(&cx.types);
    let tree = cx.articulated.map(|a| tree(&cx.types, a));
    quote! {
        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
        impl<S: #na::SimdRealField + ::core::marker::Copy> #name<S> where
            S::Element: #na::RealField + ::core::marker::Copy,
        {
            #(#consts)*
            #tree

            #[doc = #new_doc]
            #[inline]
            pub #new

            #(#methods)*
            #let_value
            #inputs
        }
    }
}

/// `Lagrangian::visit_lets`, for a model that names `let`s: it hands
/// itself, with their number, to the runtime's visitor.
fn visit_lets(types: &Types) -> Option<TokenStream> {
    if types.let_total == 0 {
        return None;
    }
    let (n, l) = (&types.n, &types.let_count);
    Some(quote! {
        #[inline]
        fn visit_lets<V: ::lagrange::lets::Visitor<S, #n>>(&self, visitor: V) -> ::core::option::Option<V::Output> {
            ::core::option::Option::Some(visitor.visit::<Self, #l>(self))
        }
    })
}

/// `impl Lets<N, L>`, for a model that names `let`s (and its error stub):
/// `LETS` and `lets` are the inherent ones.
pub(crate) fn lets_impl(name: &Ident, types: &Types) -> TokenStream {
    if types.let_total == 0 {
        return TokenStream::new();
    }
    let na = nalgebra();
    let (n, l, vector, lets) = (&types.n, &types.let_count, &types.vector, &types.lets);
    quote! {
        impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::lets::Lets<#n, #l> for #name<S> {
            const LETS: [&'static str; #l] = Self::LETS;
            #[inline]
            fn lets(&self, t: S, q: &#vector, qdot: &#vector) -> #lets {
                #name::lets(self, t, q, qdot)
            }
        }
    }
}

/// `impl Actuated<N, K>`, for a model with inputs only.
fn actuated_impl(cx: &Context) -> TokenStream {
    let jacobian = forwarding(cx, |t| t == InTrait::Actuated).collect();
    inputs::actuated_impl(&cx.outline, &cx.types, jacobian)
}

/// The methods of a capability's impl (`Holonomic`, `Contacts`,
/// `Actuated`) that the model has, each a call of the inherent one.
fn forwarding<'a>(
    cx: &'a Context,
    of: impl Fn(InTrait) -> bool + 'a,
) -> impl Iterator<Item = TokenStream> + 'a {
    let name = cx.outline.name;
    METHODS
        .iter()
        .zip(&cx.roots)
        .filter(move |(m, roots)| of(m.in_trait) && roots.is_some())
        .map(move |(m, _)| {
            let signature = m.trait_signature(&cx.types);
            let method = m.ident();
            let args = m.arg_idents();
            quote! {
                #[inline]
                #signature {
                    #name::#method(self, #(#args),*)
                }
            }
        })
}

/// One inherent method: its docs, signature and straight-line body.
fn method(cx: &Context, m: &Method, roots: &[ExprId]) -> TokenStream {
    let doc = Doc::Lines(m.doc).attributes();
    let signature = m.signature(&cx.types);
    let formed_here = cx.articulated.is_some() && crate::derive::articulated::formed(cx.model);
    if let Some(body) = formed_here.then(|| formed(cx, m)).flatten() {
        return quote! {
            #doc
            ///
            /// Formed at run time from `articulated_parts` (the masses hang on a
            /// tree of links): `M` in `O(N²)`, `f` in `O(N)`, not generated entry
            /// by entry.
            #[inline]
            pub #signature {
                #body
            }
        };
    }
    let (prelude, outs) = function::body(cx.model, &cx.namer, roots);
    let value = m.returns.assemble(&cx.types, &outs);
    quote! {
        #doc
        #[inline]
        pub #signature {
            #prelude
            #value
        }
    }
}

/// The body of `mass_matrix`, `forcing` or `mass_matrix_and_forcing` of a
/// model whose masses hang on a tree of links, from
/// [`FORMED_FROM`](crate::derive::articulated::FORMED_FROM) coordinates or
/// under `#[lagrange(articulated)]`: the runtime forms them from
/// the parts (the same `M` and `f`, exactly so before rounding: the engine
/// proved `T` has the form), so that the model's code holds no `O(N²)`
/// entries of `M` and the build no longer compiles them; `None` for the
/// other methods.
fn formed(cx: &Context, m: &Method) -> Option<TokenStream> {
    let name = cx.outline.name;
    let vector = &cx.types.vector;
    let zeros = quote!(&<#vector>::zeros());
    Some(match m.name {
        "mass_matrix" => quote! {
            let parts = #name::articulated_parts(self, t, q, #zeros);
            ::lagrange::linalg::articulated::mass_matrix(&Self::ARTICULATED_TREE, &parts)
        },
        "forcing" => quote! {
            let parts = #name::articulated_parts(self, t, q, qdot);
            ::lagrange::linalg::articulated::forcing(&Self::ARTICULATED_TREE, &parts, qdot)
        },
        "mass_matrix_and_forcing" => quote! {
            let parts = #name::articulated_parts(self, t, q, qdot);
            ::lagrange::linalg::articulated::mass_matrix_and_forcing(&Self::ARTICULATED_TREE, &parts, qdot)
        },
        _ => return None,
    })
}

/// `impl Lagrangian<N> for Name<S>`: each method calls the inherent one.
fn lagrangian_impl(cx: &Context) -> TokenStream {
    let na = nalgebra();
    let name = cx.outline.name;
    let n = &cx.types.n;
    let methods = METHODS
        .iter()
        .zip(&cx.roots)
        .map(|(m, roots)| trait_method(cx, m, roots.is_some()));
    let finite = parameters_are_finite(cx);
    let visit_inputs = inputs::visit_inputs(&cx.outline, &cx.types);
    let visit_lets = visit_lets(&cx.types);
    let accelerations = cx.articulated.map(|_| accelerations(cx));
    // A constrained model hands itself, with its number of constraints, to
    // the runtime's visitor: how a generic integrator reaches `Holonomic`.
    let visit = (cx.types.constraints > 0).then(|| {
        let c = &cx.types.c;
        quote! {
            #[inline]
            fn visit_constraints<V: ::lagrange::constraints::Visitor<S, #n>>(&self, visitor: V) -> ::core::option::Option<V::Output> {
                ::core::option::Option::Some(visitor.visit::<Self, #c>(self, ::core::default::Default::default()))
            }
        }
    });
    // A model with contacts says so: the runs other than the contact run
    // refuse it.
    let has_contacts = (cx.types.contacts > 0).then(|| {
        quote!(
            const HAS_CONTACTS: bool = true;
        )
    });
    quote! {
        impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::Lagrangian<#n> for #name<S> {
            type Scalar = S;
            const COORDINATES: [&'static str; #n] = Self::COORDINATES;
            #(#methods)*
            #[inline]
            fn parameters_are_finite(&self) -> bool {
                #finite
            }
            #visit_inputs
            #visit_lets
            #visit
            #has_contacts
            #accelerations
        }
    }
}

/// `Lagrangian::accelerations` of a model whose masses hang on a tree of
/// increments: the runtime's `O(N)` recursion over the joints, from the
/// inherent `articulated_parts`; `None` (the dense solve) where it refuses.
fn accelerations(cx: &Context) -> TokenStream {
    let name = cx.outline.name;
    let (n, vector) = (&cx.types.n, &cx.types.vector);
    quote! {
        const SOLVES_ACCELERATIONS: bool = true;
        #[inline]
        fn accelerations(
            &self,
            t: S,
            q: &#vector,
            qdot: &#vector,
        ) -> ::core::option::Option<::core::result::Result<#vector, ::lagrange::error::IntegrationError<S, #n>>> {
            let parts = #name::articulated_parts(self, t, q, qdot);
            ::lagrange::linalg::articulated::accelerations(&Self::ARTICULATED_TREE, &parts, qdot).map(::core::result::Result::Ok)
        }
    }
}

/// `impl Holonomic<N, C> for Name<S>`, for a constrained model only: each
/// method calls the inherent one. `singular_mass`: `M` is regular only on
/// the velocities the constraints allow; `velocity_rows`: which constraints
/// are on the velocities, where some are. The impl says both.
fn holonomic_impl(
    cx: &Context,
    singular_mass: bool,
    velocity_rows: Option<Vec<bool>>,
) -> TokenStream {
    if cx.types.constraints == 0 {
        return TokenStream::new();
    }
    let na = nalgebra();
    let name = cx.outline.name;
    let (n, c) = (&cx.types.n, &cx.types.c);
    let methods = forwarding(cx, |t| matches!(t, InTrait::Holonomic { .. }));
    let regular_on_constraints = singular_mass.then(|| {
        quote! {
            #[inline]
            fn mass_regular_on_constraints_only(&self) -> bool {
                true
            }
        }
    });
    let on_velocities = velocity_rows.map(|rows| {
        quote! {
            #[inline]
            fn velocity_constraint_rows(&self) -> [bool; #c] {
                [#(#rows),*]
            }
        }
    });
    quote! {
        impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::Holonomic<#n, #c> for #name<S> {
            const CONSTRAINTS: [&'static str; #c] = Self::CONSTRAINTS;
            #(#methods)*
            #regular_on_constraints
            #on_velocities
        }
    }
}

/// `impl Contacts<N, K> for Name<S>`, for a model with contacts only: each
/// method calls the inherent one.
fn contacts_impl(cx: &Context) -> TokenStream {
    if cx.types.contacts == 0 {
        return TokenStream::new();
    }
    let na = nalgebra();
    let name = cx.outline.name;
    let (n, k) = (&cx.types.n, &cx.types.kc);
    let methods = forwarding(cx, |t| t == InTrait::Contacts);
    quote! {
        impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::contact::Contacts<#n, #k> for #name<S> {
            const CONTACTS: [&'static str; #k] = Self::CONTACTS;
            #(#methods)*
        }
    }
}

/// A method of the `Lagrangian` impl: a call of the inherent one, or, where
/// the model has none, the trait's flag for its absence.
fn trait_method(cx: &Context, m: &Method, present: bool) -> TokenStream {
    if matches!(
        m.in_trait,
        InTrait::Holonomic { .. }
            | InTrait::Contacts
            | InTrait::Actuated
            | InTrait::ParameterDerivatives
            | InTrait::Regressor
            | InTrait::Inherent
            | InTrait::Articulated
    ) {
        return TokenStream::new();
    }
    let signature = m.trait_signature(&cx.types);
    if !present {
        return match m.in_trait {
            InTrait::Optional {
                zero_if_absent: true,
            } => {
                let args = m.arg_idents();
                let na = nalgebra();
                quote! {
                    #[inline]
                    #signature {
                        let _ = (#(#args),*);
                        ::core::option::Option::Some(#na::SVector::zeros())
                    }
                }
            }
            _ => TokenStream::new(),
        };
    }
    let model = cx.outline.name;
    let method = m.ident();
    let args = m.arg_idents();
    let call = quote!(#model::#method(self, #(#args),*));
    match m.in_trait {
        InTrait::Optional { .. } => quote! {
            #[inline]
            #signature {
                ::core::option::Option::Some(#call)
            }
        },
        InTrait::Required
        | InTrait::Provided
        | InTrait::Holonomic { .. }
        | InTrait::Contacts
        | InTrait::Actuated
        | InTrait::ParameterDerivatives
        | InTrait::Regressor
        | InTrait::Inherent
        | InTrait::Articulated => {
            quote! {
                #[inline]
                #signature {
                    #call
                }
            }
        }
    }
}

/// Whether every parameter field is finite, for the runtime's input checks
/// (not the inputs' fields: unset inputs are NaN, and `visit_inputs`
/// reports them in their own words).
fn parameters_are_finite(cx: &Context) -> TokenStream {
    let fields = cx.outline.fields;
    if fields.is_empty() {
        return quote!(true);
    }
    let na = nalgebra();
    let checks = fields.iter().map(|f| {
        let n = &f.name;
        match f.len {
            None => quote!(#na::ComplexField::is_finite(&self.#n)),
            Some(_) => quote!(self.#n.iter().all(#na::ComplexField::is_finite)),
        }
    });
    quote!(#(#checks)&&*)
}
