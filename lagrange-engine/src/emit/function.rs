//! One generated function's body: the symbols it reads destructured once,
//! the constants converted to `S` once, every shared node bound to a `let`
//! (see [`cse`](crate::expr::cse)), and the roots' expressions.
//!
//! A sum's product terms after the first are written as multiply-adds
//! through a local `fma(a, b, c)`: `a.mul_add(b, c)` where the target has
//! fused multiply-add in hardware (`cfg(target_feature = "fma")`, e.g.
//! `-C target-cpu=native` on a recent x86-64), `a * b + c` otherwise, which
//! rounds exactly as the sum written out (`c + a * b`) would; never a
//! software fma.
//!
//! Sines and cosines are lanes of the runtime's kernel (`lagrange::trig`):
//! where the first of them is due, one `sin_cos_array([x, y, ..])` computes
//! every one whose argument is known by then, side by side; an argument
//! computed from a sine waits for a later call.

use super::names::Namer;
use super::outline::{nalgebra, trig};
use crate::expr::cse::{Schedule, expands_to_product, fused_term, schedule};
use crate::expr::{ExprId, Func, Node, Pool};
use crate::model::Model;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::{HashMap, HashSet};

/// Operator precedence of an emitted expression, for parenthesization.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum,
    Product,
    Atom,
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
    /// The local multiply-add, once a sum needs it.
    fma: Option<Ident>,
}

/// The most terms written in one chain `a + b + …` (see `inline`).
const SUM_PIECE: usize = 128;

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
            fma: None,
        };
        let order = e.sched.order.clone();
        // Which lane of the trigonometric kernel each sine and cosine is.
        let mut lane_of: HashMap<ExprId, usize> = HashMap::new();
        for (k, t) in e.sched.trig.iter().enumerate() {
            for &id in t.sin.iter().chain(&t.cos) {
                lane_of.insert(id, k);
            }
        }
        // What each lane's argument reads that a `let` binds: the lane can
        // be computed once all of those are written.
        let needs: Vec<Vec<ExprId>> = e.sched.trig.iter().map(|t| e.bound_reads(t.arg)).collect();
        let mut written = vec![false; e.sched.trig.len()];
        for id in order {
            if e.names.contains_key(&id) {
                continue;
            }
            if let Some(&k) = lane_of.get(&id) {
                // The first sine or cosine reached: one call for its lane and
                // every other whose argument can be written here already.
                let batch: Vec<usize> = (0..written.len())
                    .filter(|&j| {
                        !written[j] && (j == k || needs[j].iter().all(|n| e.names.contains_key(n)))
                    })
                    .collect();
                for &j in &batch {
                    written[j] = true;
                }
                e.trig_call(&batch);
                continue;
            }
            if e.sched.bound[id.index()] {
                let (value, _) = e.inline(id);
                let name = e.namer.fresh("e", true);
                e.stmts.push(quote!(let #name = #value;));
                e.names.insert(id, name);
            }
        }
        e
    }

    /// The nodes bound to a `let` that writing `id` reads: `id` itself if
    /// bound, else those its operands read (symbols and constants need none).
    fn bound_reads(&self, id: ExprId) -> Vec<ExprId> {
        let mut out = Vec::new();
        let mut seen = HashSet::new();
        let mut stack = vec![id];
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            match self.pool.node(id) {
                Node::Num(_) | Node::Sym(_) => {}
                _ if self.sched.bound[id.index()] => out.push(id),
                _ => stack.extend(self.pool.children(id)),
            }
        }
        out
    }

    /// One call of the runtime's kernel for the given lanes of
    /// `sched.trig`: `sin_cos(x)` for one, `sin_cos_array([x, y, ..])` for
    /// more, so that the angles' arithmetic runs side by side (vectorized);
    /// a sine or cosine the function does not write is `_`.
    fn trig_call(&mut self, lanes: &[usize]) {
        let mut args = Vec::new();
        let mut sines = Vec::new();
        let mut cosines = Vec::new();
        for &k in lanes {
            let (arg, sin, cos) = {
                let t = &self.sched.trig[k];
                (t.arg, t.sin, t.cos)
            };
            args.push(self.operand(arg, Prec::Sum));
            for (id, out) in [(sin, &mut sines), (cos, &mut cosines)] {
                out.push(match id {
                    Some(id) => {
                        let name = self.namer.fresh("e", true);
                        self.names.insert(id, name.clone());
                        quote!(#name)
                    }
                    None => quote!(_),
                });
            }
        }
        let trig = trig();
        self.stmts.push(if let [a] = &args[..] {
            let (s, c) = (&sines[0], &cosines[0]);
            quote!(let (#s, #c) = #trig::sin_cos(#a);)
        } else {
            quote!(let ([#(#sines),*], [#(#cosines),*]) = #trig::sin_cos_array([#(#args),*]);)
        });
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
                // A long sum is written in pieces of at most `SUM_PIECE`
                // terms, each added to the previous ones' partial sum bound
                // to a local: rustc parses `a + b + …` into a tree as deep as
                // the sum is long and overflows its stack on some ten
                // thousand terms (a `sum` over a long range). The order of
                // the additions, and so every rounding, is the same.
                let partial = (xs.len() > SUM_PIECE).then(|| self.namer.fresh("partial", true));
                let mut pieces = TokenStream::new();
                let mut out = TokenStream::new();
                let mut fused = false;
                for (k, &x) in xs.iter().enumerate() {
                    if let Some(partial) = partial.as_ref().filter(|_| k > 0 && k % SUM_PIECE == 0)
                    {
                        pieces.extend(quote!(let #partial = #out;));
                        out = quote!(#partial);
                    }
                    if k > 0 {
                        if let Some((c, factors)) = fused_term(self.pool, x) {
                            let (head, last) = factors.split_at(factors.len() - 1);
                            let a = self.product(c.abs(), head);
                            let a = if c < 0.0 { quote!(-#a) } else { a };
                            let b = self.operand(last[0], Prec::Sum);
                            let fma = self.fma();
                            out = quote!(#fma(#a, #b, #out));
                            fused = true;
                            continue;
                        }
                    }
                    if let Some(name) = self.names.get(&x) {
                        let name = name.clone();
                        out.extend(if k == 0 {
                            quote!(#name)
                        } else {
                            quote!(+ #name)
                        });
                        fused = false;
                        continue;
                    }
                    let (c, factors) = self.split(x);
                    let term = self.product(c.abs(), &factors);
                    // Extended in place: a sum of many terms is written in
                    // time linear in its length.
                    out.extend(match (k, c < 0.0) {
                        (0, false) => term,
                        (0, true) => quote!(-#term),
                        (_, false) => quote!(+ #term),
                        (_, true) => quote!(- #term),
                    });
                    fused = false;
                }
                if partial.is_some() {
                    return (quote!({ #pieces #out }), Prec::Atom);
                }
                (out, if fused { Prec::Atom } else { Prec::Sum })
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
                    (quote!(#na::SimdComplexField::simd_powf(#b, #e)), Prec::Atom)
                }
            },
            Node::Func(f, a) => {
                let a = self.operand(a, Prec::Sum);
                // Sines and cosines through the runtime's inline kernel
                // (`lagrange::trig`), the rest through nalgebra's SIMD
                // traits: the scalar's own function for a scalar, lane by
                // lane for SIMD lanes.
                let call = match f {
                    Func::Sin | Func::Cos => {
                        let (path, name) = (trig(), format_ident!("{}", f.name()));
                        quote!(#path::#name)
                    }
                    _ => {
                        let (na, name) = (nalgebra(), format_ident!("simd_{}", f.name()));
                        quote!(#na::SimdComplexField::#name)
                    }
                };
                (quote!(#call(#a)), Prec::Atom)
            }
            Node::Atan2(y, x) => {
                let y = self.operand(y, Prec::Sum);
                let x = self.operand(x, Prec::Sum);
                let na = nalgebra();
                (quote!(#na::SimdRealField::simd_atan2(#y, #x)), Prec::Atom)
            }
        }
    }

    /// The name of the local multiply-add, declared in the prelude.
    fn fma(&mut self) -> Ident {
        if self.fma.is_none() {
            self.fma = Some(self.namer.fresh("fma", false));
        }
        self.fma.clone().expect("named above")
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
            out.extend(quote!(* #n));
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
                    d.extend(quote!(* #n));
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
            return (quote!(#na::SimdComplexField::simd_sqrt(#x)), Prec::Atom);
        }
        if v.fract() == 0.0 && v <= i32::MAX as f64 {
            let n = Literal::i32_unsuffixed(v as i32);
            return (quote!(#na::SimdComplexField::simd_powi(#x, #n)), Prec::Atom);
        }
        let e = self.constant(v);
        (quote!(#na::SimdComplexField::simd_powf(#x, #e)), Prec::Atom)
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
        // Parameters and inputs: one destructuring of `self`, scalar fields
        // by name, array fields by element pattern (`m: [m_0, _, m_2]`).
        let mut params: Vec<TokenStream> = Vec::new();
        // Each field with its symbols: the parameters' fields hold the
        // parameter symbols in order, the inputs' fields the input symbols.
        let mut fields: Vec<(&crate::model::Field, &[crate::expr::SymId])> = Vec::new();
        for (group, syms) in [
            (&model.fields, &s.parameters),
            (&model.input_fields, &s.inputs),
        ] {
            let mut k = 0;
            for field in group {
                let len = field.len.unwrap_or(1);
                fields.push((field, &syms[k..k + len]));
                k += len;
            }
        }
        for (field, syms) in fields {
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
        if let Some(fma) = &self.fma {
            out.extend(quote! {
                #[inline(always)]
                fn #fma<S: #na::SimdRealField + ::core::marker::Copy>(a: S, b: S, c: S) -> S {
                    #[cfg(target_feature = "fma")]
                    {
                        #na::SimdComplexField::simd_mul_add(a, b, c)
                    }
                    #[cfg(not(target_feature = "fma"))]
                    {
                        a * b + c
                    }
                }
            });
        }
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
pub(super) fn body(
    model: &Model,
    namer: &Namer,
    roots: &[ExprId],
) -> (TokenStream, Vec<TokenStream>) {
    let mut e = FnEmitter::new(&model.pool, namer, roots);
    let outs: Vec<TokenStream> = roots.iter().map(|&r| e.root(r)).collect();
    (e.prelude(model), outs)
}
