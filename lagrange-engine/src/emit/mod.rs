//! Model + equations → Rust items.
//!
//! Each generated function is straight-line code: the symbols it reads are
//! destructured once, the constants converted to `S` once, every shared node
//! bound to a `let` (see [`cse`](crate::cse)), and the result built on the
//! stack. No heap allocation, no branch, no symbolic work at run time.

use crate::derive::Equations;
use crate::expr::cse::{expands_to_product, schedule, Schedule};
use crate::expr::{ExprId, Node, Pool, SymId};
use crate::model::{Field, Model, Scalar, SymKind};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::{HashMap, HashSet};

/// Operator precedence of an emitted expression, for parenthesization.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum,
    Product,
    Atom,
}

/// Local names: the user's names for coordinates and parameters, `<q>_dot`
/// for velocities, fresh `e<k>`/`k<k>` for intermediates and constants, none
/// of which can collide with a user name or the function's arguments.
#[derive(Clone)]
struct Namer {
    taken: HashSet<String>,
    symbol: Vec<Ident>,
}

impl Namer {
    fn new(model: &Model) -> Self {
        let mut taken: HashSet<String> = ["t", "q", "qdot", "qddot", "S", "self", "Self"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        // The user's scalar names are kept as they are; elements of indexed
        // names become `theta_0`, `theta_1`, ... (renamed if that is taken).
        for n in model.coordinates.iter().chain(&model.parameters) {
            taken.insert(n.name.to_string());
        }
        let mut namer = Namer {
            taken,
            symbol: Vec::new(),
        };
        let s = &model.symbols;
        let mut symbol = Vec::with_capacity(s.count());
        let local = |namer: &mut Namer, x: &Scalar| match x.index {
            None => x.name.clone(),
            Some(k) => namer.fresh(&format!("{}_{k}", x.name), false),
        };
        let coordinates: Vec<Ident> = model
            .coordinates
            .iter()
            .map(|c| local(&mut namer, c))
            .collect();
        let parameters: Vec<Ident> = model
            .parameters
            .iter()
            .map(|p| local(&mut namer, p))
            .collect();
        for k in 0..s.count() {
            symbol.push(match s.kind(SymId(k as u32)) {
                SymKind::Time => format_ident!("t"),
                SymKind::Coordinate(i) => coordinates[i].clone(),
                SymKind::Parameter(p) => parameters[p].clone(),
                SymKind::Acceleration(i) => namer.fresh(&format!("{}_ddot", coordinates[i]), false),
                SymKind::Velocity(i) => namer.fresh(&format!("{}_dot", coordinates[i]), false),
            });
        }
        namer.symbol = symbol;
        namer
    }

    /// `base` if free (and `numbered` is false), else `base<k>` or `base_`.
    fn fresh(&mut self, base: &str, numbered: bool) -> Ident {
        let mut k = 0usize;
        let mut name = if numbered {
            format!("{base}{k}")
        } else {
            base.to_string()
        };
        while self.taken.contains(&name) {
            k += 1;
            name = if numbered {
                format!("{base}{k}")
            } else {
                format!("{base}{}", "_".repeat(k))
            };
        }
        self.taken.insert(name.clone());
        Ident::new(&name, Span::call_site())
    }
}

/// Emits one function body: the bindings and the expressions of its roots.
struct FnEmitter<'a> {
    pool: &'a Pool,
    sched: Schedule,
    namer: Namer,
    names: HashMap<ExprId, Ident>,
    consts: Vec<(Ident, f64)>,
    const_names: HashMap<u64, Ident>,
    stmts: Vec<TokenStream>,
}

fn nalgebra() -> TokenStream {
    quote!(::lagrange::nalgebra)
}

impl<'a> FnEmitter<'a> {
    fn new(pool: &'a Pool, namer: &Namer, roots: &[ExprId]) -> Self {
        let sched = schedule(pool, roots);
        let mut e = FnEmitter {
            pool,
            sched,
            namer: namer.clone(),
            names: HashMap::new(),
            consts: Vec::new(),
            const_names: HashMap::new(),
            stmts: Vec::new(),
        };
        let order = e.sched.order.clone();
        for id in order {
            if e.sched.bound[id.index()] {
                let (value, _) = e.inline(id);
                let name = e.namer.fresh("e", true);
                e.stmts.push(quote!(let #name = #value;));
                e.names.insert(id, name);
            }
        }
        e
    }

    fn constant(&mut self, v: f64) -> TokenStream {
        let bits = v.to_bits();
        if let Some(name) = self.const_names.get(&bits) {
            return quote!(#name);
        }
        let name = self.namer.fresh("k", true);
        self.consts.push((name.clone(), v));
        self.const_names.insert(bits, name.clone());
        quote!(#name)
    }

    /// The tokens naming `id` in a context of precedence `ctx`.
    fn operand(&mut self, id: ExprId, ctx: Prec) -> TokenStream {
        if let Some(name) = self.names.get(&id) {
            return quote!(#name);
        }
        match self.pool.node(id) {
            Node::Sym(s) => {
                let name = &self.namer.symbol[s.0 as usize];
                return quote!(#name);
            }
            Node::Num(bits) => {
                let v = f64::from_bits(*bits);
                if v < 0.0 && ctx > Prec::Sum {
                    let c = self.constant(-v);
                    return quote!((-#c));
                }
                if v < 0.0 {
                    let c = self.constant(-v);
                    return quote!(-#c);
                }
                return self.constant(v);
            }
            _ => {}
        }
        let (tokens, prec) = self.inline(id);
        if prec < ctx {
            quote!((#tokens))
        } else {
            tokens
        }
    }

    fn split(&self, id: ExprId) -> (f64, Vec<ExprId>) {
        match self.pool.node(id) {
            Node::Mul(xs) => match self.pool.as_num(xs[0]) {
                Some(c) => (c, xs[1..].to_vec()),
                None => (1.0, xs.to_vec()),
            },
            Node::Num(bits) => (f64::from_bits(*bits), Vec::new()),
            _ => (1.0, vec![id]),
        }
    }

    /// The expression of a node, one level deep (operands by name or inline).
    fn inline(&mut self, id: ExprId) -> (TokenStream, Prec) {
        match self.pool.node(id).clone() {
            Node::Num(_) | Node::Sym(_) => (self.operand(id, Prec::Sum), Prec::Atom),
            Node::Add(xs) => {
                let mut out = TokenStream::new();
                for (k, &x) in xs.iter().enumerate() {
                    let (c, factors) = self.split(x);
                    let term = self.product(c.abs(), &factors);
                    out = match (k, c < 0.0) {
                        (0, false) => term,
                        (0, true) => quote!(-#term),
                        (_, false) => quote!(#out + #term),
                        (_, true) => quote!(#out - #term),
                    };
                }
                (out, Prec::Sum)
            }
            Node::Mul(_) => {
                let (c, factors) = self.split(id);
                let term = self.product(c.abs(), &factors);
                if c < 0.0 {
                    (quote!(-#term), Prec::Sum)
                } else {
                    (term, Prec::Product)
                }
            }
            Node::Pow(b, e) => match self.pool.as_num(e) {
                Some(v) if v > 0.0 => self.power(b, v),
                Some(v) => {
                    let (d, prec) = self.power(b, -v);
                    let d = if prec < Prec::Atom { quote!((#d)) } else { d };
                    let one = self.constant(1.0);
                    (quote!(#one / #d), Prec::Product)
                }
                None => {
                    let b = self.operand(b, Prec::Sum);
                    let e = self.operand(e, Prec::Sum);
                    let na = nalgebra();
                    (quote!(#na::ComplexField::powf(#b, #e)), Prec::Atom)
                }
            },
            Node::Func(f, a) => {
                let a = self.operand(a, Prec::Sum);
                let name = format_ident!("{}", f.name());
                let na = nalgebra();
                (quote!(#na::ComplexField::#name(#a)), Prec::Atom)
            }
            Node::Atan2(y, x) => {
                let y = self.operand(y, Prec::Sum);
                let x = self.operand(x, Prec::Sum);
                let na = nalgebra();
                (quote!(#na::RealField::atan2(#y, #x)), Prec::Atom)
            }
        }
    }

    /// `mag * f1 * f2 / (d1 * d2)`, with negative constant powers as divisors.
    fn product(&mut self, mag: f64, factors: &[ExprId]) -> TokenStream {
        let mut numer: Vec<TokenStream> = Vec::new();
        let mut denom: Vec<(TokenStream, Prec)> = Vec::new();
        if mag != 1.0 || factors.is_empty() {
            numer.push(self.constant(mag));
        }
        // A square written `x * x` is parenthesized inside a longer product,
        // so that it rounds as one factor whether it is inlined here or bound
        // to a `let` elsewhere: `M` and `f` computed together or apart agree
        // to the last bit.
        let ctx = if numer.len() + factors.len() > 1 {
            Prec::Atom
        } else {
            Prec::Product
        };
        for &f in factors {
            if !self.names.contains_key(&f) {
                if let Node::Pow(b, e) = *self.pool.node(f) {
                    if let Some(v) = self.pool.as_num(e).filter(|v| *v < 0.0) {
                        denom.push(self.power(b, -v));
                        continue;
                    }
                }
            }
            numer.push(self.operand(f, ctx));
        }
        if numer.is_empty() {
            numer.push(self.constant(1.0));
        }
        let mut out = numer[0].clone();
        for n in &numer[1..] {
            out = quote!(#out * #n);
        }
        match denom.len() {
            0 => out,
            1 => {
                let (d, prec) = &denom[0];
                if *prec < Prec::Atom {
                    quote!(#out / (#d))
                } else {
                    quote!(#out / #d)
                }
            }
            _ => {
                let mut d = denom[0].0.clone();
                for (n, _) in &denom[1..] {
                    d = quote!(#d * #n);
                }
                quote!(#out / (#d))
            }
        }
    }

    /// `b^v` for a positive constant `v`.
    fn power(&mut self, b: ExprId, v: f64) -> (TokenStream, Prec) {
        let na = nalgebra();
        if v == 1.0 {
            return (self.operand(b, Prec::Atom), Prec::Atom);
        }
        if expands_to_product(v) {
            let x = self.operand(b, Prec::Atom);
            return if v == 2.0 {
                (quote!(#x * #x), Prec::Product)
            } else {
                (quote!(#x * #x * #x), Prec::Product)
            };
        }
        let x = self.operand(b, Prec::Sum);
        if v == 0.5 {
            return (quote!(#na::ComplexField::sqrt(#x)), Prec::Atom);
        }
        if v.fract() == 0.0 && v <= i32::MAX as f64 {
            let n = Literal::i32_unsuffixed(v as i32);
            return (quote!(#na::ComplexField::powi(#x, #n)), Prec::Atom);
        }
        let e = self.constant(v);
        (quote!(#na::ComplexField::powf(#x, #e)), Prec::Atom)
    }

    /// The bindings this function needs, in order: symbols, constants, lets.
    fn prelude(&self, model: &Model) -> TokenStream {
        let mut used = vec![false; model.symbols.count()];
        for &id in &self.sched.order {
            if let Node::Sym(s) = self.pool.node(id) {
                used[s.0 as usize] = true;
            }
        }
        let s = &model.symbols;
        // Coordinates, velocities and accelerations are read from their
        // vectors in one destructuring, so a coordinate may be named `q`.
        let mut patterns: Vec<TokenStream> = Vec::new();
        let mut sources: Vec<TokenStream> = Vec::new();
        let idx: Vec<Literal> = (0..s.coordinates.len())
            .map(Literal::usize_unsuffixed)
            .collect();
        for (syms, source) in [
            (&s.coordinates, quote!(q)),
            (&s.velocities, quote!(qdot)),
            (&s.accelerations, quote!(qddot)),
        ] {
            if !syms.iter().any(|x| used[x.0 as usize]) {
                continue;
            }
            let names = syms.iter().map(|x| {
                if used[x.0 as usize] {
                    let n = &self.namer.symbol[x.0 as usize];
                    quote!(#n)
                } else {
                    quote!(_)
                }
            });
            patterns.push(quote!([#(#names),*]));
            sources.push(quote!([#(#source[#idx]),*]));
        }
        let mut out = TokenStream::new();
        match patterns.len() {
            0 => {}
            1 => {
                let (p, v) = (&patterns[0], &sources[0]);
                out.extend(quote!(let #p = #v;));
            }
            _ => out.extend(quote!(let (#(#patterns),*) = (#(#sources),*);)),
        }
        // Parameters: one destructuring of `self`, scalar fields by name,
        // array fields by element pattern (`m: [m_0, _, m_2]`).
        let mut params: Vec<TokenStream> = Vec::new();
        let mut k = 0;
        for field in &model.fields {
            let len = field.len.unwrap_or(1);
            let syms = &s.parameters[k..k + len];
            k += len;
            if !syms.iter().any(|x| used[x.0 as usize]) {
                continue;
            }
            let names: Vec<TokenStream> = syms
                .iter()
                .map(|x| {
                    if used[x.0 as usize] {
                        let n = &self.namer.symbol[x.0 as usize];
                        quote!(#n)
                    } else {
                        quote!(_)
                    }
                })
                .collect();
            let f = &field.name;
            params.push(match field.len {
                None => quote!(#f),
                Some(_) => quote!(#f: [#(#names),*]),
            });
        }
        if !params.is_empty() {
            out.extend(quote!(let Self { #(#params,)* .. } = *self;));
        }
        let na = nalgebra();
        for (name, v) in &self.consts {
            let lit = float_tokens(*v);
            out.extend(quote!(let #name: S = #na::convert::<f64, S>(#lit);));
        }
        for st in &self.stmts {
            out.extend(st.clone());
        }
        out
    }

    fn root(&mut self, id: ExprId) -> TokenStream {
        self.operand(id, Prec::Sum)
    }
}

fn float_tokens(v: f64) -> TokenStream {
    if v.is_finite() {
        let lit = Literal::f64_suffixed(v);
        quote!(#lit)
    } else if v.is_nan() {
        quote!(::core::f64::NAN)
    } else if v > 0.0 {
        quote!(::core::f64::INFINITY)
    } else {
        quote!(::core::f64::NEG_INFINITY)
    }
}

/// A function's statements and its root expressions.
fn body(model: &Model, namer: &Namer, roots: &[ExprId]) -> (TokenStream, Vec<TokenStream>) {
    let mut e = FnEmitter::new(&model.pool, namer, roots);
    let outs: Vec<TokenStream> = roots.iter().map(|&r| e.root(r)).collect();
    (e.prelude(model), outs)
}

/// The generated items of a derived model.
pub fn emit(model: &Model, eq: &Equations, equations_text: &str) -> TokenStream {
    let n = model.dof();
    let namer = Namer::new(model);
    let na = nalgebra();
    let name = &model.name;
    let vis = &model.vis;
    let attrs = &model.attrs;
    let fields = &model.fields;
    let params: Vec<&Ident> = fields.iter().map(|f| &f.name).collect();
    let param_types: Vec<TokenStream> = fields.iter().map(Field::rust_type).collect();
    let n_lit = Literal::usize_unsuffixed(n);
    let vector = quote!(#na::SVector<S, #n_lit>);
    let matrix = quote!(#na::SMatrix<S, #n_lit, #n_lit>);
    let new_vector = quote!(#na::SVector::<S, #n_lit>::from_column_slice);
    let new_matrix = quote!(#na::SMatrix::<S, #n_lit, #n_lit>::from_column_slice);

    // Column-major entries of M; symmetric pairs are one node, used twice.
    let mass_roots: Vec<ExprId> = (0..n)
        .flat_map(|j| (0..n).map(move |i| (i, j)))
        .map(|(i, j)| eq.mass[i][j])
        .collect();

    let (m_body, m_out) = body(model, &namer, &mass_roots);
    let (f_body, f_out) = body(model, &namer, &eq.forcing);
    let both_roots: Vec<ExprId> = mass_roots.iter().chain(&eq.forcing).copied().collect();
    let (mf_body, mf_out) = body(model, &namer, &both_roots);
    let (mf_m, mf_f) = mf_out.split_at(n * n);
    let (t_body, t_out) = body(model, &namer, &[model.kinetic.value]);
    let (v_body, v_out) = body(model, &namer, &[model.potential.value]);
    let (e_body, e_out) = body(model, &namer, &[eq.energy]);
    let (t_out, v_out, e_out) = (&t_out[0], &v_out[0], &e_out[0]);
    let (p_body, p_out) = body(model, &namer, &eq.momenta);
    let (g_body, g_out) = body(model, &namer, &eq.lagrangian_gradient);
    // Only a model with forces or dissipation has non-conservative forces;
    // a conservative one says so and emits no code for them.
    let conservative = model.forces.is_empty() && model.dissipation.is_none();
    let (nonconservative_fn, nonconservative_impl) = if conservative {
        (
            TokenStream::new(),
            quote! {
                const CONSERVATIVE: bool = true;
            },
        )
    } else {
        let (nc_body, nc_out) = body(model, &namer, &eq.nonconservative);
        (
            quote! {
                /// The non-conservative generalized forces `Q − ∂R/∂q̇`.
                #[inline]
                pub fn nonconservative_forces(&self, t: S, q: &#vector, qdot: &#vector) -> #vector {
                    #nc_body
                    #new_vector(&[#(#nc_out),*])
                }
            },
            quote! {
                #[inline]
                fn nonconservative_forces(&self, t: S, q: &#vector, qdot: &#vector) -> ::core::option::Option<#vector> {
                    ::core::option::Option::Some(#name::nonconservative_forces(self, t, q, qdot))
                }
            },
        )
    };

    // Opt-in: the residual Jacobians, column-major, ∂r/∂q then ∂r/∂q̇.
    let (jacobian_fn, jacobian_impl) = match &eq.jacobians {
        None => (TokenStream::new(), TokenStream::new()),
        Some((jq, jv)) => {
            let roots: Vec<ExprId> = [jq, jv]
                .iter()
                .flat_map(|b| (0..n).flat_map(move |k| (0..n).map(move |i| b[i][k])))
                .collect();
            let (j_body, j_out) = body(model, &namer, &roots);
            let (jq_out, jv_out) = j_out.split_at(n * n);
            (
                quote! {
                    /// The exact Jacobians `(∂r/∂q, ∂r/∂q̇)` of the residual
                    /// `r = M(t, q) q̈ − f(t, q, q̇)`, for implicit integrators.
                    #[inline]
                    pub fn residual_jacobians(&self, t: S, q: &#vector, qdot: &#vector, qddot: &#vector) -> (#matrix, #matrix) {
                        #j_body
                        (#new_matrix(&[#(#jq_out),*]), #new_matrix(&[#(#jv_out),*]))
                    }
                },
                quote! {
                    #[inline]
                    fn residual_jacobians(&self, t: S, q: &#vector, qdot: &#vector, qddot: &#vector) -> ::core::option::Option<(#matrix, #matrix)> {
                        ::core::option::Option::Some(#name::residual_jacobians(self, t, q, qdot, qddot))
                    }
                },
            )
        }
    };

    let coordinate_names: Vec<String> = model.coordinates.iter().map(|c| c.to_string()).collect();
    let parameter_names: Vec<String> = params.iter().map(|c| c.to_string()).collect();
    let p_lit = Literal::usize_unsuffixed(params.len());
    let parameter_docs: Vec<String> = model
        .fields
        .iter()
        .map(|f| match f.len {
            None => format!("`{}`", f.name),
            Some(len) => format!("`{}: [S; {len}]`", f.name),
        })
        .collect();

    let (fields, constructor) = if params.is_empty() {
        (
            quote!({ _scalar: ::core::marker::PhantomData<S> }),
            quote!(Self {
                _scalar: ::core::marker::PhantomData
            }),
        )
    } else {
        (
            quote!({ #(pub #params: #param_types,)* }),
            quote!(Self { #(#params,)* }),
        )
    };
    let finite = if params.is_empty() {
        quote!(true)
    } else {
        let checks = model.fields.iter().map(|f| {
            let n = &f.name;
            match f.len {
                None => quote!(#na::ComplexField::is_finite(&self.#n)),
                Some(_) => quote!(self.#n.iter().all(#na::ComplexField::is_finite)),
            }
        });
        quote!(#(#checks)&&*)
    };
    let new_doc = format!(
        "A `{name}` with the given parameters ({}).",
        if params.is_empty() {
            "none".to_string()
        } else {
            parameter_docs.join(", ")
        }
    );
    let equations_doc =
        "The derived equations `M q̈ = f`, readable: shared subexpressions first, then each entry.";

    quote! {
        #(#attrs)*
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #name<S = f64> #fields

        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
        impl<S: #na::RealField + ::core::marker::Copy> #name<S> {
            /// Number of degrees of freedom (generalized coordinates).
            pub const DOF: usize = #n_lit;
            /// Names of the generalized coordinates, in the order of `q`.
            pub const COORDINATES: [&'static str; #n_lit] = [#(#coordinate_names),*];
            /// Names of the runtime parameters (the struct's fields; an
            /// indexed parameter `m[N]` is one field `m: [S; N]`), in
            /// declaration order.
            pub const PARAMETERS: [&'static str; #p_lit] = [#(#parameter_names),*];
            #[doc = #equations_doc]
            pub const EQUATIONS: &'static str = #equations_text;

            #[doc = #new_doc]
            #[inline]
            pub const fn new(#(#params: #param_types),*) -> Self {
                #constructor
            }

            /// The mass matrix `M(t, q) = ∂²T/∂q̇²`.
            #[inline]
            pub fn mass_matrix(&self, t: S, q: &#vector) -> #matrix {
                #m_body
                #new_matrix(&[#(#m_out),*])
            }

            /// The forcing `f(t, q, q̇)` of `M q̈ = f`.
            #[inline]
            pub fn forcing(&self, t: S, q: &#vector, qdot: &#vector) -> #vector {
                #f_body
                #new_vector(&[#(#f_out),*])
            }

            /// `M` and `f` together, sharing their common subexpressions.
            #[inline]
            pub fn mass_matrix_and_forcing(&self, t: S, q: &#vector, qdot: &#vector) -> (#matrix, #vector) {
                #mf_body
                (
                    #new_matrix(&[#(#mf_m),*]),
                    #new_vector(&[#(#mf_f),*]),
                )
            }

            /// Kinetic energy `T(t, q, q̇)`.
            #[inline]
            pub fn kinetic_energy(&self, t: S, q: &#vector, qdot: &#vector) -> S {
                #t_body
                #t_out
            }

            /// Potential energy `V(t, q)`.
            #[inline]
            pub fn potential_energy(&self, t: S, q: &#vector) -> S {
                #v_body
                #v_out
            }

            /// Total energy `T + V`.
            #[inline]
            pub fn energy(&self, t: S, q: &#vector, qdot: &#vector) -> S {
                #e_body
                #e_out
            }

            /// The generalized momenta `p = ∂L/∂q̇`.
            #[inline]
            pub fn momentum(&self, t: S, q: &#vector, qdot: &#vector) -> #vector {
                #p_body
                #new_vector(&[#(#p_out),*])
            }

            /// `∂L/∂q`.
            #[inline]
            pub fn lagrangian_gradient(&self, t: S, q: &#vector, qdot: &#vector) -> #vector {
                #g_body
                #new_vector(&[#(#g_out),*])
            }

            #nonconservative_fn

            #jacobian_fn
        }

        impl<S: #na::RealField + ::core::marker::Copy> ::lagrange::Lagrangian<#n_lit> for #name<S> {
            type Scalar = S;
            const COORDINATES: [&'static str; #n_lit] = Self::COORDINATES;
            #[inline]
            fn mass_matrix(&self, t: S, q: &#vector) -> #matrix {
                #name::mass_matrix(self, t, q)
            }
            #[inline]
            fn forcing(&self, t: S, q: &#vector, qdot: &#vector) -> #vector {
                #name::forcing(self, t, q, qdot)
            }
            #[inline]
            fn mass_matrix_and_forcing(&self, t: S, q: &#vector, qdot: &#vector) -> (#matrix, #vector) {
                #name::mass_matrix_and_forcing(self, t, q, qdot)
            }
            #[inline]
            fn kinetic_energy(&self, t: S, q: &#vector, qdot: &#vector) -> S {
                #name::kinetic_energy(self, t, q, qdot)
            }
            #[inline]
            fn potential_energy(&self, t: S, q: &#vector) -> S {
                #name::potential_energy(self, t, q)
            }
            #[inline]
            fn energy(&self, t: S, q: &#vector, qdot: &#vector) -> S {
                #name::energy(self, t, q, qdot)
            }
            #[inline]
            fn momentum(&self, t: S, q: &#vector, qdot: &#vector) -> ::core::option::Option<#vector> {
                ::core::option::Option::Some(#name::momentum(self, t, q, qdot))
            }
            #[inline]
            fn lagrangian_gradient(&self, t: S, q: &#vector, qdot: &#vector) -> ::core::option::Option<#vector> {
                ::core::option::Option::Some(#name::lagrangian_gradient(self, t, q, qdot))
            }
            #nonconservative_impl
            #jacobian_impl
            #[inline]
            fn parameters_are_finite(&self) -> bool {
                #finite
            }
        }
    }
}
