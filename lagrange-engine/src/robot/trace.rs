//! Straight-line code written by running the algorithms on traced scalars.
//!
//! A [`Val`] is either a number known at compile time or a variable of the
//! code being written. The arithmetic folds what is known (a product by
//! zero, by one, a sum of numbers), so that running RNEA, CRBA or ABA on
//! the robot's constants writes only the operations its joints and bodies
//! need: the axis-aligned joints, the zero offsets and the symmetric
//! inertias fold away, as RobCoGen's generated C++ does. Equal operations
//! on equal operands are written once (hash-consed), and only the
//! operations an output reads are emitted.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;

/// A traced scalar: a number known now, or a variable (possibly negated).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Val {
    /// A number known at compile time.
    K(f64),
    /// Variable `id` of the trace, negated when `neg`.
    V {
        /// The variable.
        id: u32,
        /// Whether the value is its negation.
        neg: bool,
    },
}

/// What one variable of the trace is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Op {
    /// An input, named by the caller.
    Input(u32),
    /// `a + b`, `a - b` (`sub`), each operand possibly negated.
    Add(u32, bool, u32, bool),
    /// `a * b`.
    Mul(u32, u32),
    /// `k * a`, `k` a constant by its bits (positive).
    Scale(u64, u32),
    /// `k + a`, `k` by its bits (any sign), `a` possibly negated.
    Offset(u64, u32, bool),
    /// `1 / a`.
    Recip(u32),
    /// The sine and the cosine of an input: `Sin(i)`, `Cos(i)`.
    Sin(u32),
    /// See `Sin`.
    Cos(u32),
}

/// The trace: every variable's operation, in the order they were made.
#[derive(Default)]
pub struct Trace {
    ops: Vec<Op>,
    seen: HashMap<Op, u32>,
    inputs: Vec<TokenStream>,
    /// [`Self::input_once`]'s inputs by their tokens.
    named: HashMap<String, Val>,
}

/// The zero and the one.
pub const ZERO: Val = Val::K(0.0);
/// See [`ZERO`].
pub const ONE: Val = Val::K(1.0);

impl Val {
    /// The value negated.
    pub fn negated(self) -> Val {
        match self {
            Val::K(k) => Val::K(-k),
            Val::V { id, neg } => Val::V { id, neg: !neg },
        }
    }

    /// Whether the value is the number zero.
    pub fn is_zero(self) -> bool {
        self == Val::K(0.0) || self == Val::K(-0.0)
    }
}

impl Trace {
    /// Operations written so far.
    pub fn len(&self) -> usize {
        self.ops.len()
    }

    /// Whether nothing has been written.
    pub fn is_empty(&self) -> bool {
        self.ops.is_empty()
    }

    fn push(&mut self, op: Op) -> u32 {
        if let Some(&id) = self.seen.get(&op) {
            return id;
        }
        let id = self.ops.len() as u32;
        self.ops.push(op);
        self.seen.insert(op, id);
        id
    }

    /// A new input, read as `tokens` (a scalar expression) where used.
    pub fn input(&mut self, tokens: TokenStream) -> Val {
        let n = self.inputs.len() as u32;
        self.inputs.push(tokens);
        Val::V {
            id: self.push(Op::Input(n)),
            neg: false,
        }
    }

    /// The input read as `tokens`, made on the first call and the same
    /// variable after (a parameter read by several bodies' terms).
    pub fn input_once(&mut self, tokens: TokenStream) -> Val {
        let key = tokens.to_string();
        if let Some(&v) = self.named.get(&key) {
            return v;
        }
        let v = self.input(tokens);
        self.named.insert(key, v);
        v
    }

    /// The sine and cosine of an input variable.
    pub fn sin_cos(&mut self, x: Val) -> (Val, Val) {
        match x {
            Val::K(k) => (Val::K(k.sin()), Val::K(k.cos())),
            Val::V { id, neg } => {
                let s = Val::V {
                    id: self.push(Op::Sin(id)),
                    neg,
                };
                let c = Val::V {
                    id: self.push(Op::Cos(id)),
                    neg: false,
                };
                (s, c)
            }
        }
    }

    /// `a + b`.
    pub fn add(&mut self, a: Val, b: Val) -> Val {
        match (a, b) {
            (Val::K(x), Val::K(y)) => Val::K(x + y),
            (k, v) | (v, k) if k.is_zero() => v,
            (Val::K(k), Val::V { id, neg }) | (Val::V { id, neg }, Val::K(k)) => {
                // k + (±a): the sign of the whole kept positive on `a`.
                if neg {
                    Val::V {
                        id: self.push(Op::Offset((-k).to_bits(), id, false)),
                        neg: true,
                    }
                } else {
                    Val::V {
                        id: self.push(Op::Offset(k.to_bits(), id, false)),
                        neg: false,
                    }
                }
            }
            (Val::V { id: i, neg: ni }, Val::V { id: j, neg: nj }) => {
                if i == j && ni != nj {
                    return ZERO;
                }
                // (-a) + (-b) = -(a + b); (-a) + b = b - a.
                let (i, ni, j, nj) = if i <= j {
                    (i, ni, j, nj)
                } else {
                    (j, nj, i, ni)
                };
                if ni && nj {
                    Val::V {
                        id: self.push(Op::Add(i, false, j, false)),
                        neg: true,
                    }
                } else {
                    Val::V {
                        id: self.push(Op::Add(i, ni, j, nj)),
                        neg: false,
                    }
                }
            }
        }
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Val, b: Val) -> Val {
        self.add(a, b.negated())
    }

    /// `a * b`.
    pub fn mul(&mut self, a: Val, b: Val) -> Val {
        match (a, b) {
            (Val::K(x), Val::K(y)) => Val::K(x * y),
            (k, _) | (_, k) if k.is_zero() => ZERO,
            (Val::K(k), Val::V { id, neg }) | (Val::V { id, neg }, Val::K(k)) => {
                if k == 1.0 {
                    return Val::V { id, neg };
                }
                if k == -1.0 {
                    return Val::V { id, neg: !neg };
                }
                Val::V {
                    id: self.push(Op::Scale(k.abs().to_bits(), id)),
                    neg: neg != (k < 0.0),
                }
            }
            (Val::V { id: i, neg: ni }, Val::V { id: j, neg: nj }) => {
                let (i, j) = if i <= j { (i, j) } else { (j, i) };
                Val::V {
                    id: self.push(Op::Mul(i, j)),
                    neg: ni != nj,
                }
            }
        }
    }

    /// `1 / a`.
    pub fn recip(&mut self, a: Val) -> Val {
        match a {
            Val::K(k) => Val::K(1.0 / k),
            Val::V { id, neg } => Val::V {
                id: self.push(Op::Recip(id)),
                neg,
            },
        }
    }

    /// `Σ a_i b_i`.
    pub fn dot(&mut self, a: &[Val], b: &[Val]) -> Val {
        let mut acc = ZERO;
        for (&x, &y) in a.iter().zip(b) {
            let p = self.mul(x, y);
            acc = self.add(acc, p);
        }
        acc
    }

    /// The value of every variable given the inputs' values (for the
    /// engine's own checks of what it is about to write, and its tests).
    pub fn eval(&self, inputs: &[f64]) -> Vec<f64> {
        let mut v: Vec<f64> = Vec::with_capacity(self.ops.len());
        for op in &self.ops {
            let s = |v: &Vec<f64>, id: u32, neg: bool| {
                let x = v[id as usize];
                if neg { -x } else { x }
            };
            let x = match *op {
                Op::Input(n) => inputs.get(n as usize).copied().unwrap_or(0.0),
                Op::Add(i, ni, j, nj) => s(&v, i, ni) + s(&v, j, nj),
                Op::Mul(i, j) => v[i as usize] * v[j as usize],
                Op::Scale(k, i) => f64::from_bits(k) * v[i as usize],
                Op::Offset(k, i, ni) => f64::from_bits(k) + s(&v, i, ni),
                Op::Recip(i) => 1.0 / v[i as usize],
                Op::Sin(i) => v[i as usize].sin(),
                Op::Cos(i) => v[i as usize].cos(),
            };
            v.push(x);
        }
        v
    }

    /// A value at the inputs' values, from [`eval`](Self::eval)'s result.
    pub fn value(values: &[f64], x: Val) -> f64 {
        match x {
            Val::K(k) => k,
            Val::V { id, neg } => {
                let y = values[id as usize];
                if neg { -y } else { y }
            }
        }
    }

    /// The statements computing `outputs`, only those they read, and the
    /// expression of each output. Sines and cosines of the inputs are
    /// computed together, one `sin_cos_array` call.
    pub fn emit(&self, outputs: &[Val]) -> (TokenStream, Vec<TokenStream>) {
        let mut live = vec![false; self.ops.len()];
        for o in outputs {
            if let Val::V { id, .. } = o {
                live[*id as usize] = true;
            }
        }
        for i in (0..self.ops.len()).rev() {
            if !live[i] {
                continue;
            }
            let mut mark = |j: u32| live[j as usize] = true;
            match self.ops[i] {
                Op::Input(_) => {}
                Op::Add(a, _, b, _) | Op::Mul(a, b) => {
                    mark(a);
                    mark(b);
                }
                Op::Scale(_, a) | Op::Offset(_, a, _) | Op::Recip(a) | Op::Sin(a) | Op::Cos(a) => {
                    mark(a)
                }
            }
        }
        // Sines and cosines wanted, by their argument, in trace order.
        let mut angles: Vec<u32> = Vec::new();
        for (i, op) in self.ops.iter().enumerate() {
            if let (true, Op::Sin(a) | Op::Cos(a)) = (live[i], op) {
                if !angles.contains(a) {
                    angles.push(*a);
                }
            }
        }
        let name = |id: u32| format_ident!("v{}", id);
        let mut consts: Vec<(u64, Ident)> = Vec::new();
        let mut konst = |bits: u64| -> Ident {
            if let Some((_, n)) = consts.iter().find(|(b, _)| *b == bits) {
                return n.clone();
            }
            let n = format_ident!("k{}", consts.len());
            consts.push((bits, n.clone()));
            n
        };
        let operand = |id: u32, neg: bool| {
            let n = name(id);
            if neg { quote!((-#n)) } else { quote!(#n) }
        };
        let mut body = TokenStream::new();
        let sin_name = |a: u32| format_ident!("s{}", a);
        let cos_name = |a: u32| format_ident!("c{}", a);
        let mut trig_done = false;
        for (i, op) in self.ops.iter().enumerate() {
            if !live[i] {
                continue;
            }
            let v = name(i as u32);
            let rhs = match *op {
                Op::Input(n) => self.inputs[n as usize].clone(),
                Op::Add(a, na, b, nb) => {
                    let x = operand(a, na);
                    let nb_name = name(b);
                    if nb {
                        quote!(#x - #nb_name)
                    } else {
                        quote!(#x + #nb_name)
                    }
                }
                Op::Mul(a, b) => {
                    let (x, y) = (name(a), name(b));
                    quote!(#x * #y)
                }
                Op::Scale(k, a) => {
                    let (k, x) = (konst(k), name(a));
                    quote!(#k * #x)
                }
                Op::Offset(k, a, na) => {
                    let (kv, x) = (f64::from_bits(k), operand(a, na));
                    let kn = konst(kv.abs().to_bits());
                    if kv < 0.0 {
                        quote!(#x - #kn)
                    } else {
                        quote!(#kn + #x)
                    }
                }
                Op::Recip(a) => {
                    let x = name(a);
                    quote!(::lagrange::nalgebra::SimdComplexField::simd_recip(#x))
                }
                // Every angle's sine and cosine in one call, written where
                // the first of them is used.
                Op::Sin(a) | Op::Cos(a) => {
                    if !trig_done {
                        trig_done = true;
                        let args: Vec<Ident> = angles.iter().map(|&a| name(a)).collect();
                        let s: Vec<Ident> = angles.iter().map(|&a| sin_name(a)).collect();
                        let c: Vec<Ident> = angles.iter().map(|&a| cos_name(a)).collect();
                        body.extend(quote!(
                            let ([#(#s),*], [#(#c),*]) = ::lagrange::trig::sin_cos_array([#(#args),*]);
                        ));
                    }
                    let x = if matches!(op, Op::Sin(_)) {
                        sin_name(a)
                    } else {
                        cos_name(a)
                    };
                    quote!(#x)
                }
            };
            body.extend(quote!(let #v: S = #rhs;));
        }
        let outs = outputs
            .iter()
            .map(|&o| match o {
                z if z.is_zero() => quote!(::lagrange::nalgebra::zero::<S>()),
                Val::K(k) => {
                    let n = konst(k.abs().to_bits());
                    if k < 0.0 { quote!((-#n)) } else { quote!(#n) }
                }
                Val::V { id, neg } => operand(id, neg),
            })
            .collect();
        let mut head = TokenStream::new();
        for (bits, n) in &consts {
            let lit = Literal::f64_suffixed(f64::from_bits(*bits));
            head.extend(quote!(let #n: S = ::lagrange::nalgebra::convert::<f64, S>(#lit);));
        }
        head.extend(body);
        (head, outs)
    }
}
