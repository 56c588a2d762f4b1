//! A robot written as bodies and joints in the macro's input: the
//! `bodies:` and `joints:` sections (with `constants:` and `locked:`),
//! read into the same [`Urdf`] a file gives, so that the tree, the
//! recursions, the frames, the Jacobians, the regressor and the floating
//! base are the URDF route's, unchanged.
//!
//! ```text
//! bodies:
//!     upper: mass 1.2, com [0, 0, 0.15], inertia diag(0.01, 0.01, 0.002);
//!     tool;                                   // a frame without mass
//! joints:
//!     shoulder: revolute base -> upper, at translate(0, 0, 0.1), axis [0, 0, 1];
//!     flange:   fixed upper -> tool, at translate(0, 0, 0.3) * rotate_x(PI / 2);
//! ```
//!
//! `base` is the world; a floating base is the joint `floating base ->
//! trunk`. Every value is a constant expression over numbers, `PI`, the
//! `constants:` and the functions below, evaluated here in `f64`: scalars,
//! 3-vectors, 3 × 3 matrices and rigid transforms. Each entry's tokens are
//! remembered, and every refusal is a compile error on the offending ones
//! (the links' and joints' `line` in the [`Urdf`] is the index of their
//! name's span, so that the tree's own refusals land on the name).

use super::urdf::{self, Inertial, Joint, JointKind, Link, Placement, Urdf};
use proc_macro2::{Delimiter, Span, TokenStream, TokenTree};
use quote::ToTokens;
use syn::ext::IdentExt;
use syn::parse::{ParseStream, Parser};
use syn::{Ident, Token};

/// The sections of a robot written in the language.
const SECTIONS: [&str; 4] = ["bodies", "joints", "constants", "locked"];
/// The world's name: the fixed base every tree hangs from.
pub const BASE: &str = "base";
/// The deepest a constant expression nests (parentheses, brackets, calls,
/// unary minuses): the evaluator recurses once per level.
const MAX_DEPTH: usize = 64;

/// Whether the input is a robot written in the language: its struct's
/// braces hold a `bodies:` or `joints:` section. Read without syn (no
/// token buffer over the whole input, whatever its nesting).
pub fn is_inline(input: &TokenStream) -> bool {
    let mut after_struct = 0;
    for tt in input.clone() {
        match (&tt, after_struct) {
            (TokenTree::Ident(i), 0) if i == "struct" => after_struct = 1,
            (TokenTree::Ident(_), 1) => after_struct = 2,
            (TokenTree::Group(g), 2) if g.delimiter() == Delimiter::Brace => {
                return entries(g.stream())
                    .iter()
                    .any(|e| matches!(header(e), Some(s) if s == "bodies" || s == "joints"));
            }
            (_, 1 | 2) => return false,
            _ => {}
        }
    }
    false
}

/// The top-level entries of a section body, split at `;` (empty ones
/// dropped).
fn entries(stream: TokenStream) -> Vec<Vec<TokenTree>> {
    let mut out = vec![Vec::new()];
    for tt in stream {
        match &tt {
            TokenTree::Punct(p) if p.as_char() == ';' => out.push(Vec::new()),
            _ => out.last_mut().map_or((), |e| e.push(tt)),
        }
    }
    out.retain(|e| !e.is_empty());
    out
}

/// The section an entry opens (`bodies :` at its start), if any.
fn header(entry: &[TokenTree]) -> Option<String> {
    match entry {
        [TokenTree::Ident(i), TokenTree::Punct(p), rest @ ..]
            if p.as_char() == ':'
                && SECTIONS.contains(&i.to_string().as_str())
                && !matches!(rest.first(), Some(TokenTree::Punct(q)) if q.as_char() == ':') =>
        {
            Some(i.to_string())
        }
        _ => None,
    }
}

/// A constant value of the language.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A number.
    Scalar(f64),
    /// A 3-vector.
    Vector([f64; 3]),
    /// A 3 × 3 matrix (rows).
    Matrix([[f64; 3]; 3]),
    /// A rigid transform: a rotation, then a translation (`x ↦ R x + p`).
    Transform(Placement),
}

impl Value {
    fn kind(&self) -> &'static str {
        match self {
            Value::Scalar(_) => "a number",
            Value::Vector(_) => "a vector",
            Value::Matrix(_) => "a matrix",
            Value::Transform(_) => "a transform",
        }
    }
    fn finite(&self) -> bool {
        match self {
            Value::Scalar(x) => x.is_finite(),
            Value::Vector(v) => v.iter().all(|x| x.is_finite()),
            Value::Matrix(m) => m.iter().flatten().all(|x| x.is_finite()),
            Value::Transform(t) => {
                t.pos.iter().all(|x| x.is_finite()) && t.rot.iter().flatten().all(|x| x.is_finite())
            }
        }
    }
}

/// A rotation with the entries within [`urdf::SNAP`] of zero set to zero,
/// as the URDF's `rpy` are.
fn rotation(rot: [[f64; 3]; 3]) -> Value {
    Value::Transform(Placement {
        rot: urdf::snapped(rot),
        pos: [0.0; 3],
    })
}

/// The constant-expression evaluator: numbers, `PI`, the constants so far.
struct Eval<'a> {
    constants: &'a [(String, Value)],
}

type Res<T> = syn::Result<T>;

fn err<T>(tokens: impl ToTokens, message: impl std::fmt::Display) -> Res<T> {
    Err(syn::Error::new_spanned(tokens, message))
}

impl Eval<'_> {
    /// A whole value: the tokens of one property or constant.
    fn value(&self, tokens: &TokenStream) -> Res<Value> {
        if tokens.is_empty() {
            return Err(syn::Error::new(
                Span::call_site(),
                "a value is missing here",
            ));
        }
        let v = (|s: ParseStream| {
            let v = self.sum(s, 0)?;
            if !s.is_empty() {
                return Err(s.error("expected an operator (`+ - * /`) or the end of the value"));
            }
            Ok(v)
        })
        .parse2(tokens.clone())?;
        if !v.finite() {
            return err(tokens, format!("this value is not finite: {v:?}"));
        }
        Ok(v)
    }

    fn sum(&self, s: ParseStream, depth: usize) -> Res<Value> {
        let mut acc = self.product(s, depth)?;
        loop {
            let (plus, op) = if s.peek(Token![+]) {
                (true, s.parse::<Token![+]>()?.span)
            } else if s.peek(Token![-]) && !s.peek(Token![->]) {
                (false, s.parse::<Token![-]>()?.span)
            } else {
                return Ok(acc);
            };
            let rhs = self.product(s, depth)?;
            acc = match (acc, rhs) {
                (Value::Scalar(a), Value::Scalar(b)) => {
                    Value::Scalar(if plus { a + b } else { a - b })
                }
                (Value::Vector(a), Value::Vector(b)) => Value::Vector(std::array::from_fn(|i| {
                    if plus { a[i] + b[i] } else { a[i] - b[i] }
                })),
                (Value::Matrix(a), Value::Matrix(b)) => Value::Matrix(std::array::from_fn(|i| {
                    std::array::from_fn(|j| {
                        if plus {
                            a[i][j] + b[i][j]
                        } else {
                            a[i][j] - b[i][j]
                        }
                    })
                })),
                (a, b) => {
                    return Err(syn::Error::new(
                        op,
                        format!(
                            "{} {} {}: a sum takes two numbers, two vectors or two matrices (transforms compose by `*`)",
                            a.kind(),
                            if plus { "plus" } else { "minus" },
                            b.kind()
                        ),
                    ));
                }
            };
        }
    }

    fn product(&self, s: ParseStream, depth: usize) -> Res<Value> {
        let mut acc = self.unary(s, depth)?;
        loop {
            let (times, op) = if s.peek(Token![*]) {
                (true, s.parse::<Token![*]>()?.span)
            } else if s.peek(Token![/]) {
                (false, s.parse::<Token![/]>()?.span)
            } else {
                return Ok(acc);
            };
            let rhs = self.unary(s, depth)?;
            acc = match (times, acc, rhs) {
                (true, Value::Scalar(a), b) => scale(b, a),
                (true, a @ (Value::Vector(_) | Value::Matrix(_)), Value::Scalar(b)) => scale(a, b),
                (true, Value::Transform(a), Value::Transform(b)) => {
                    Value::Transform(compose(&a, &b))
                }
                (true, Value::Transform(a), Value::Vector(v)) if a.pos == [0.0; 3] => {
                    Value::Vector(std::array::from_fn(|i| {
                        (0..3).map(|k| a.rot[i][k] * v[k]).sum()
                    }))
                }
                (false, a, Value::Scalar(b)) if !matches!(a, Value::Transform(_)) => {
                    if b == 0.0 {
                        return Err(syn::Error::new(op, "division by zero"));
                    }
                    scale(a, 1.0 / b)
                }
                (times, a, b) => {
                    return Err(syn::Error::new(
                        op,
                        format!(
                            "{} {} {}: a product takes a number and a value, a transform and a transform \
                         (composed: the right one placed in the left one's frame), or a rotation and a vector; \
                         a quotient divides by a number",
                            a.kind(),
                            if times { "times" } else { "divided by" },
                            b.kind()
                        ),
                    ));
                }
            };
        }
    }

    fn unary(&self, s: ParseStream, depth: usize) -> Res<Value> {
        if depth >= MAX_DEPTH {
            return Err(s.error(format!(
                "this value nests more than {MAX_DEPTH} levels deep"
            )));
        }
        if s.peek(Token![-]) {
            let minus = s.parse::<Token![-]>()?;
            return match self.unary(s, depth + 1)? {
                Value::Transform(_) => err(minus, "a transform cannot be negated"),
                v => Ok(scale(v, -1.0)),
            };
        }
        self.primary(s, depth)
    }

    fn primary(&self, s: ParseStream, depth: usize) -> Res<Value> {
        if s.peek(syn::token::Paren) {
            let inner;
            syn::parenthesized!(inner in s);
            let v = self.sum(&inner, depth + 1)?;
            if !inner.is_empty() {
                return Err(inner.error("expected `)`"));
            }
            return Ok(v);
        }
        if s.peek(syn::token::Bracket) {
            let inner;
            let bracket = syn::bracketed!(inner in s);
            let items = self.list(&inner, depth + 1)?;
            return match items.as_slice() {
                [Value::Scalar(a), Value::Scalar(b), Value::Scalar(c)] => {
                    Ok(Value::Vector([*a, *b, *c]))
                }
                [Value::Vector(a), Value::Vector(b), Value::Vector(c)] => {
                    Ok(Value::Matrix([*a, *b, *c]))
                }
                _ => Err(syn::Error::new(
                    bracket.span.join(),
                    "a vector is `[x, y, z]` and a matrix `[[a, b, c], [d, e, f], [g, h, i]]` (its rows)",
                )),
            };
        }
        if s.peek(syn::Lit) {
            let lit: syn::Lit = s.parse()?;
            return match &lit {
                syn::Lit::Float(f) => Ok(Value::Scalar(f.base10_parse::<f64>()?)),
                syn::Lit::Int(i) => Ok(Value::Scalar(i.base10_parse::<f64>()?)),
                _ => err(lit, "expected a number"),
            };
        }
        let name: Ident = s.call(Ident::parse_any).map_err(|e| {
            syn::Error::new(
                e.span(),
                "expected a value: a number, `PI`, a constant, `[x, y, z]`, or a call (`translate`, `rotate_x`, `diag`, ...)",
            )
        })?;
        if s.peek(syn::token::Paren) {
            let inner;
            syn::parenthesized!(inner in s);
            let args = self.list(&inner, depth + 1)?;
            return call(&name, &args);
        }
        let text = name.to_string();
        if text == "PI" {
            return Ok(Value::Scalar(std::f64::consts::PI));
        }
        match self.constants.iter().rev().find(|(n, _)| *n == text) {
            Some((_, v)) => Ok(*v),
            None => err(
                &name,
                format!(
                    "`{text}` is no constant (declare it under `constants:` before its use; `PI` is π)"
                ),
            ),
        }
    }

    fn list(&self, s: ParseStream, depth: usize) -> Res<Vec<Value>> {
        let mut out = Vec::new();
        while !s.is_empty() {
            out.push(self.sum(s, depth)?);
            if s.is_empty() {
                break;
            }
            s.parse::<Token![,]>()?;
        }
        Ok(out)
    }
}

fn scale(v: Value, k: f64) -> Value {
    match v {
        Value::Scalar(a) => Value::Scalar(k * a),
        Value::Vector(a) => Value::Vector(a.map(|x| k * x)),
        Value::Matrix(a) => Value::Matrix(a.map(|r| r.map(|x| k * x))),
        Value::Transform(t) => Value::Transform(t),
    }
}

/// `a ∘ b`; a translation on the left keeps `b`'s rotation as it is, so
/// that `translate(..) * rotate_rpy(..)` is the URDF `<origin>`'s numbers.
fn compose(a: &Placement, b: &Placement) -> Placement {
    if a.rot == Placement::IDENTITY.rot {
        return Placement {
            rot: b.rot,
            pos: std::array::from_fn(|i| a.pos[i] + b.pos[i]),
        };
    }
    a.then(b)
}

fn numbers(name: &Ident, args: &[Value], n: usize) -> Res<Vec<f64>> {
    let all: Option<Vec<f64>> = args
        .iter()
        .map(|a| match a {
            Value::Scalar(x) => Some(*x),
            _ => None,
        })
        .collect();
    match all {
        Some(v) if v.len() == n => Ok(v),
        _ => err(
            name,
            format!("`{name}` takes {n} number{}", if n == 1 { "" } else { "s" }),
        ),
    }
}

fn call(name: &Ident, args: &[Value]) -> Res<Value> {
    let text = name.to_string();
    let unit = |x: [f64; 3]| {
        let norm = x.iter().map(|a| a * a).sum::<f64>().sqrt();
        (norm.is_finite() && norm >= 1e-12).then(|| x.map(|a| a / norm))
    };
    let function = |f: fn(f64) -> f64| numbers(name, args, 1).map(|x| Value::Scalar(f(x[0])));
    match text.as_str() {
        "translate" => match args {
            [Value::Vector(p)] => Ok(Value::Transform(Placement {
                rot: Placement::IDENTITY.rot,
                pos: *p,
            })),
            _ => {
                let p = numbers(name, args, 3).map_err(|_| {
                    syn::Error::new(name.span(), "`translate` takes three numbers or a vector")
                })?;
                Ok(Value::Transform(Placement {
                    rot: Placement::IDENTITY.rot,
                    pos: [p[0], p[1], p[2]],
                }))
            }
        },
        "rotate_x" | "rotate_y" | "rotate_z" => {
            let a = numbers(name, args, 1)?[0];
            let mut axis = [0.0; 3];
            axis[usize::from(text.as_bytes()[7] - b'x')] = 1.0;
            Ok(rotation(urdf::rotation(axis, a)))
        }
        "rotate" => match args {
            [Value::Vector(axis), Value::Scalar(a)] => match unit(*axis) {
                Some(u) => Ok(rotation(urdf::rotation(u, *a))),
                None => err(
                    name,
                    "`rotate`'s axis is zero: a rotation is about a direction",
                ),
            },
            _ => err(name, "`rotate` takes an axis (a vector) and an angle"),
        },
        "rotate_rpy" => {
            let v = numbers(name, args, 3)?;
            Ok(rotation(urdf::rpy(v[0], v[1], v[2])))
        }
        "diag" => {
            let v = numbers(name, args, 3)?;
            Ok(Value::Matrix([
                [v[0], 0.0, 0.0],
                [0.0, v[1], 0.0],
                [0.0, 0.0, v[2]],
            ]))
        }
        "sqrt" => function(f64::sqrt),
        "sin" => function(f64::sin),
        "cos" => function(f64::cos),
        "tan" => function(f64::tan),
        "asin" => function(f64::asin),
        "acos" => function(f64::acos),
        "atan" => function(f64::atan),
        "atan2" => {
            let v = numbers(name, args, 2)?;
            Ok(Value::Scalar(v[0].atan2(v[1])))
        }
        _ => err(
            name,
            format!(
                "`{text}` is no function of a robot's values: `translate`, `rotate_x`, `rotate_y`, `rotate_z`, \
                 `rotate(axis, angle)`, `rotate_rpy`, `diag`, `sqrt`, `sin`, `cos`, `tan`, `asin`, `acos`, \
                 `atan`, `atan2`"
            ),
        ),
    }
}

/// A robot read from the language: what the robot route loads instead of a
/// file.
pub struct Inline {
    /// The links and joints, as a file would give them.
    pub urdf: Urdf,
    /// The span of each link's and joint's name: `line` `k + 1` is `spans[k]`.
    pub spans: Vec<Span>,
    /// A floating base: the joint `floating base -> root`.
    pub floating: bool,
    /// The locks: the joint's name token and its value.
    pub locks: Vec<(Ident, f64)>,
}

impl Inline {
    /// The span of the link or joint at `line`.
    pub fn span(&self, line: Option<u32>) -> Option<Span> {
        let k = usize::try_from(line?).ok()?.checked_sub(1)?;
        self.spans.get(k).copied()
    }
    /// The span of the moving joint `name`.
    pub fn joint_span(&self, name: &str) -> Option<Span> {
        let j = self.urdf.joints.iter().find(|j| j.name == name)?;
        self.span(Some(j.line))
    }
}

/// The tokens of one property, up to the next top-level `,`.
fn until_comma(s: ParseStream) -> Res<TokenStream> {
    let mut out = TokenStream::new();
    while !s.is_empty() && !s.peek(Token![,]) {
        let tt: TokenTree = s.parse()?;
        out.extend([tt]);
    }
    Ok(out)
}

/// `name: key value, key value, ...`: the name and each key with its
/// value's tokens.
type Props = Vec<(Ident, TokenStream)>;

struct BodyDef {
    name: Ident,
    mass: Option<(f64, TokenStream)>,
    com: [f64; 3],
    inertia: Option<([[f64; 3]; 3], TokenStream)>,
    axes: [[f64; 3]; 3],
}

struct JointDef {
    name: Ident,
    kind: Ident,
    parent: Ident,
    child: Ident,
    at: Placement,
    axis: Option<[f64; 3]>,
}

/// The properties after `:` (or none, for a bare name).
fn properties(s: ParseStream) -> Res<Props> {
    let mut out = Vec::new();
    loop {
        let key: Ident = s.call(Ident::parse_any)?;
        let value = until_comma(s)?;
        if value.is_empty() {
            return err(&key, format!("`{key}` has no value"));
        }
        if out.iter().any(|(k, _): &(Ident, TokenStream)| *k == key) {
            return err(&key, format!("`{key}` is given twice"));
        }
        out.push((key, value));
        if s.is_empty() {
            return Ok(out);
        }
        s.parse::<Token![,]>()?;
        if s.is_empty() {
            return Ok(out);
        }
    }
}

fn vector(tokens: &TokenStream, v: Value, what: &str) -> Res<[f64; 3]> {
    match v {
        Value::Vector(x) => Ok(x),
        other => err(
            tokens,
            format!("{what} is a vector `[x, y, z]`, not {}", other.kind()),
        ),
    }
}

fn scalar(tokens: &TokenStream, v: Value, what: &str) -> Res<f64> {
    match v {
        Value::Scalar(x) => Ok(x),
        other => err(tokens, format!("{what} is a number, not {}", other.kind())),
    }
}

fn body(eval: &Eval, tokens: TokenStream) -> Res<BodyDef> {
    (|s: ParseStream| {
        let name: Ident = s.call(Ident::parse_any)?;
        let mut def = BodyDef {
            name,
            mass: None,
            com: [0.0; 3],
            inertia: None,
            axes: Placement::IDENTITY.rot,
        };
        if s.is_empty() {
            return Ok(def);
        }
        s.parse::<Token![:]>()?;
        for (key, value) in properties(s)? {
            let v = eval.value(&value)?;
            match key.to_string().as_str() {
                "mass" => def.mass = Some((scalar(&value, v, "a mass")?, value)),
                "com" => def.com = vector(&value, v, "the centre of mass")?,
                "inertia" => match v {
                    Value::Matrix(m) => def.inertia = Some((m, value)),
                    other => {
                        return err(
                            &value,
                            format!(
                                "an inertia is a matrix (`[[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]` or \
                                 `diag(ixx, iyy, izz)`), not {}",
                                other.kind()
                            ),
                        );
                    }
                },
                "axes" => match v {
                    Value::Transform(t) if t.pos == [0.0; 3] => def.axes = t.rot,
                    other => {
                        return err(
                            &value,
                            format!(
                                "`axes` is the rotation the inertia is given in (`rotate_rpy(..)`, ...), not {}",
                                if matches!(other, Value::Transform(_)) { "a transform that moves the origin" } else { other.kind() }
                            ),
                        );
                    }
                },
                _ => {
                    return err(
                        &key,
                        format!(
                            "a body takes `mass`, `com` (its centre of mass), `inertia` (about the centre of mass) \
                             and `axes` (the rotation the inertia is given in), not `{key}`"
                        ),
                    );
                }
            }
        }
        Ok(def)
    })
    .parse2(tokens)
}

fn joint(eval: &Eval, tokens: TokenStream) -> Res<JointDef> {
    (|s: ParseStream| {
        let name: Ident = s.call(Ident::parse_any)?;
        s.parse::<Token![:]>()?;
        let kind: Ident = s.call(Ident::parse_any).map_err(|e| {
            syn::Error::new(
                e.span(),
                format!(
                    "a joint reads `{name}: revolute parent -> child, at .., axis ..` (the sections are `bodies:`, \
                     `joints:`, `constants:` and `locked:`)"
                ),
            )
        })?;
        if !["revolute", "continuous", "prismatic", "fixed", "floating"].contains(&kind.to_string().as_str()) {
            return err(
                &kind,
                format!("joint `{name}` is `{kind}`: a joint is `revolute`, `continuous`, `prismatic`, `fixed` or `floating`"),
            );
        }
        let parent: Ident = s.call(Ident::parse_any)?;
        s.parse::<Token![->]>()?;
        let child: Ident = s.call(Ident::parse_any)?;
        let mut def = JointDef {
            name,
            kind,
            parent,
            child,
            at: Placement::IDENTITY,
            axis: None,
        };
        if s.is_empty() {
            return Ok(def);
        }
        s.parse::<Token![,]>()?;
        if s.is_empty() {
            return Ok(def);
        }
        let moving = def.kind != "fixed" && def.kind != "floating";
        for (key, value) in properties(s)? {
            let v = eval.value(&value)?;
            match key.to_string().as_str() {
                "at" if def.kind != "floating" => match v {
                    Value::Transform(t) => def.at = t,
                    other => {
                        return err(
                            &value,
                            format!(
                                "`at` is the joint frame's placement in its parent's (`translate(..) * rotate_rpy(..)`), not {}",
                                other.kind()
                            ),
                        );
                    }
                },
                "axis" if moving => {
                    let a = vector(&value, v, "an axis")?;
                    let norm = a.iter().map(|x| x * x).sum::<f64>().sqrt();
                    if norm.is_nan() || norm < 1e-12 {
                        return err(
                            &value,
                            format!("joint `{}`'s axis is zero: a joint moves about or along a direction", def.name),
                        );
                    }
                    def.axis = Some(a.map(|x| x / norm));
                }
                _ => {
                    let takes = if moving {
                        "`at` (its frame in the parent's) and `axis`"
                    } else if def.kind == "fixed" {
                        "`at` (its frame in the parent's) alone"
                    } else {
                        "nothing: the base's pose is the coordinates'"
                    };
                    return err(&key, format!("a {} joint takes {takes}, not `{key}`", def.kind));
                }
            }
        }
        Ok(def)
    })
    .parse2(tokens)
}

/// The inertia's own checks: finite, symmetric, positive definite, its
/// principal moments within the triangle inequality (each at most the sum
/// of the other two, as `∫ (y² + z²) ≤ ∫ (x² + z²) + ∫ (x² + y²)`).
fn check_inertia(name: &Ident, mass: f64, m: &[[f64; 3]; 3], tokens: &TokenStream) -> Res<()> {
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if m[i][j] != m[j][i] {
            return err(
                tokens,
                format!(
                    "body `{name}`'s inertia is not symmetric: entry ({i}, {j}) is {} and ({j}, {i}) is {}",
                    m[i][j], m[j][i]
                ),
            );
        }
    }
    let [[xx, xy, xz], [_, yy, yz], [_, _, zz]] = *m;
    let d2 = xx * yy - xy * xy;
    let d3 = xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
    if !(xx > 0.0 && d2 > 0.0 && d3 > 0.0) {
        return err(
            tokens,
            format!(
                "body `{name}`'s inertia is not positive definite (ixx = {xx}, leading minors {d2:e} and {d3:e}): \
                 a body of mass {mass} has a positive moment about every axis"
            ),
        );
    }
    let l = eigenvalues(m);
    let trace = l[0] + l[1] + l[2];
    // A flat body meets the inequality with equality; the eigenvalues are
    // found to a few ε of the trace.
    if l[0] + l[1] < l[2] - 1e-12 * trace {
        return err(
            tokens,
            format!(
                "body `{name}`'s principal moments {:.6e}, {:.6e} and {:.6e} break the triangle inequality: \
                 the largest exceeds the sum of the other two, which no distribution of mass gives",
                l[0], l[1], l[2]
            ),
        );
    }
    Ok(())
}

/// The eigenvalues of a symmetric 3 × 3 matrix, ascending (the
/// trigonometric closed form).
pub fn eigenvalues(a: &[[f64; 3]; 3]) -> [f64; 3] {
    let p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    let q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    if p1 == 0.0 {
        let mut d = [a[0][0], a[1][1], a[2][2]];
        d.sort_by(f64::total_cmp);
        return d;
    }
    let p2 = (0..3).map(|i| (a[i][i] - q).powi(2)).sum::<f64>() + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    let b: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| (a[i][j] - if i == j { q } else { 0.0 }) / p)
    });
    let det = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1])
        - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0])
        + b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
    let phi = (det / 2.0).clamp(-1.0, 1.0).acos() / 3.0;
    let big = q + 2.0 * p * phi.cos();
    let small = q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos();
    let mut l = [small, 3.0 * q - big - small, big];
    l.sort_by(f64::total_cmp);
    l
}

/// The robot's sections read from the struct's braces: the links and
/// joints, or the first error on its tokens.
pub fn read(body: TokenStream, name: &Ident) -> Res<Inline> {
    let mut section: Option<String> = None;
    let mut constants: Vec<(String, Value)> = Vec::new();
    let mut bodies: Vec<BodyDef> = Vec::new();
    let mut joints: Vec<JointDef> = Vec::new();
    let mut locks: Vec<(Ident, f64)> = Vec::new();
    for mut entry in entries(body) {
        if let Some(s) = header(&entry) {
            section = Some(s);
            entry.drain(..2);
            if entry.is_empty() {
                continue;
            }
        }
        let tokens: TokenStream = entry.into_iter().collect();
        let eval = Eval {
            constants: &constants,
        };
        match section.as_deref() {
            None => {
                return err(
                    &tokens,
                    "a robot written as bodies and joints takes the sections `bodies:`, `joints:`, `constants:` and `locked:`",
                );
            }
            Some("bodies") => bodies.push(body_def(&eval, tokens)?),
            Some("joints") => joints.push(joint(&eval, tokens)?),
            Some(kind) => {
                let pairs = (|s: ParseStream| {
                    let mut out = Vec::new();
                    while !s.is_empty() {
                        let n: Ident = s.call(Ident::parse_any)?;
                        s.parse::<Token![=]>()?;
                        out.push((n, until_comma(s)?));
                        if !s.is_empty() {
                            s.parse::<Token![,]>()?;
                        }
                    }
                    Ok(out)
                })
                .parse2(tokens)?;
                for (n, value) in pairs {
                    if value.is_empty() {
                        return err(&n, format!("`{n}` has no value"));
                    }
                    let v = Eval {
                        constants: &constants,
                    }
                    .value(&value)?;
                    if kind == "constants" {
                        if n == "PI" || constants.iter().any(|(c, _)| n == c) {
                            return err(&n, format!("constant `{n}` is defined twice (`PI` is π)"));
                        }
                        constants.push((n.to_string(), v));
                    } else {
                        locks.push((n, scalar(&value, v, "a lock's value")?));
                    }
                }
            }
        }
    }
    build(name, bodies, joints, locks)
}

fn body_def(eval: &Eval, tokens: TokenStream) -> Res<BodyDef> {
    let def = body(eval, tokens)?;
    if def.name == BASE {
        return err(
            &def.name,
            "`base` is the world, the tree's root: it is no body of its own (a floating base is the joint `floating base -> trunk`)",
        );
    }
    match &def.mass {
        Some((m, tokens)) if *m < 0.0 => {
            return err(
                tokens,
                format!("body `{}` has a negative mass, {m}", def.name),
            );
        }
        Some((m, _)) if *m > 0.0 => match &def.inertia {
            None => {
                return err(
                    &def.name,
                    format!(
                        "body `{}` has a mass but no `inertia` (about its centre of mass)",
                        def.name
                    ),
                );
            }
            Some((i, tokens)) => check_inertia(&def.name, *m, i, tokens)?,
        },
        _ => {
            if let Some((i, tokens)) = &def.inertia {
                if i.iter().flatten().any(|&v| v != 0.0) {
                    return err(
                        tokens,
                        format!(
                            "body `{}` has no mass but an inertia: a massless body's inertia is zero",
                            def.name
                        ),
                    );
                }
            }
        }
    }
    Ok(def)
}

fn build(
    name: &Ident,
    bodies: Vec<BodyDef>,
    joints: Vec<JointDef>,
    locks: Vec<(Ident, f64)>,
) -> Res<Inline> {
    if bodies.is_empty() {
        return err(name, "the robot has no bodies: `bodies:` lists them");
    }
    for (k, b) in bodies.iter().enumerate() {
        if bodies[..k].iter().any(|o| o.name == b.name) {
            return err(&b.name, format!("body `{}` is defined twice", b.name));
        }
    }
    for (k, j) in joints.iter().enumerate() {
        if joints[..k].iter().any(|o| o.name == j.name) {
            return err(&j.name, format!("joint `{}` is defined twice", j.name));
        }
    }
    let find = |id: &Ident, which: &str, joint: &Ident| -> Res<Option<usize>> {
        if id == BASE {
            return Ok(None);
        }
        match bodies.iter().position(|b| b.name == *id) {
            Some(i) => Ok(Some(i)),
            None => err(
                id,
                format!(
                    "joint `{joint}`'s {which} `{id}` is no body of the robot (declare it under `bodies:`; `base` is the world)"
                ),
            ),
        }
    };
    // parent_of[b]: the joint whose child body b is.
    let mut parent_of: Vec<Option<usize>> = vec![None; bodies.len()];
    let mut ends = Vec::new();
    let mut floating = None;
    for (k, j) in joints.iter().enumerate() {
        let parent = find(&j.parent, "parent", &j.name)?;
        let Some(child) = find(&j.child, "child", &j.name)? else {
            return err(
                &j.child,
                format!(
                    "joint `{}`'s child is `base`: the world is no joint's child",
                    j.name
                ),
            );
        };
        if parent == Some(child) {
            return err(
                &j.child,
                format!("joint `{}` joins body `{}` to itself", j.name, j.child),
            );
        }
        if let Some(first) = parent_of[child] {
            return err(
                &j.child,
                format!(
                    "body `{}` is attached twice: by joint `{}` and by joint `{}` (a body hangs from one joint)",
                    j.child, joints[first].name, j.name
                ),
            );
        }
        parent_of[child] = Some(k);
        let moving = j.kind != "fixed" && j.kind != "floating";
        if moving && j.axis.is_none() {
            return err(
                &j.name,
                format!("joint `{}` is {} and needs an `axis`", j.name, j.kind),
            );
        }
        if j.kind == "floating" {
            if parent.is_some() {
                return err(
                    &j.parent,
                    format!(
                        "joint `{}` is floating: a floating base hangs from `base`, the world",
                        j.name
                    ),
                );
            }
            if floating.is_some() {
                return err(
                    &j.name,
                    format!(
                        "joint `{}` is a second floating joint: a robot has one floating base",
                        j.name
                    ),
                );
            }
            floating = Some(k);
        }
        ends.push((parent, child));
    }
    if let Some(f) = floating {
        if let Some(k) = (0..joints.len()).find(|&k| k != f && ends[k].0.is_none()) {
            return err(
                &joints[k].parent,
                format!(
                    "joint `{}` hangs from `base`, the world, on a floating base: every other joint hangs from the floating body `{}`",
                    joints[k].name, joints[f].child
                ),
            );
        }
    }
    // Every body reached from the base: unattached, or on a loop.
    let mut reached = vec![false; bodies.len()];
    let mut stack: Vec<Option<usize>> = vec![None];
    while let Some(b) = stack.pop() {
        for (k, &(p, c)) in ends.iter().enumerate() {
            if p == b && !reached[c] && parent_of[c] == Some(k) {
                reached[c] = true;
                stack.push(Some(c));
            }
        }
    }
    if let Some(b) = (0..bodies.len()).find(|&b| !reached[b]) {
        let body = &bodies[b].name;
        return err(
            body,
            match parent_of[b] {
                None => format!(
                    "body `{body}` is attached to nothing: no joint has it as its child, and a robot is one tree from `base`"
                ),
                Some(_) => format!(
                    "body `{body}` lies on a loop of joints, not reached from `base`: a robot is a tree"
                ),
            },
        );
    }
    let moving = joints
        .iter()
        .filter(|j| j.kind != "fixed" && j.kind != "floating")
        .count();
    if moving > super::tree::MAX_JOINTS {
        return err(
            name,
            format!(
                "the robot has {moving} moving joints, more than the {} a robot may have",
                super::tree::MAX_JOINTS
            ),
        );
    }
    // The links: the world first (not on a floating base), then the
    // bodies; the joints in their order. `line` is 1 + the index of the
    // name's span.
    let mut spans = Vec::new();
    let mut line = |span: Span| {
        spans.push(span);
        u32::try_from(spans.len()).unwrap_or(u32::MAX)
    };
    let offset = usize::from(floating.is_none());
    let mut links = Vec::new();
    if floating.is_none() {
        links.push(Link {
            name: BASE.to_string(),
            line: line(name.span()),
            inertial: None,
        });
    }
    for b in &bodies {
        let mass = b.mass.as_ref().map_or(0.0, |m| m.0);
        let local = b.inertia.as_ref().map_or([[0.0; 3]; 3], |i| i.0);
        links.push(Link {
            name: b.name.to_string(),
            line: line(b.name.span()),
            inertial: Some(Inertial {
                mass,
                com: b.com,
                inertia: urdf::rotated_inertia(&b.axes, &local),
            }),
        });
    }
    let mut out = Vec::new();
    for (k, j) in joints.iter().enumerate() {
        if Some(k) == floating {
            continue;
        }
        let (parent, child) = ends[k];
        out.push(Joint {
            name: j.name.to_string(),
            line: line(j.name.span()),
            kind: match j.kind.to_string().as_str() {
                "revolute" | "continuous" => JointKind::Revolute,
                "prismatic" => JointKind::Prismatic,
                _ => JointKind::Fixed,
            },
            parent: parent.map_or(0, |p| p + offset),
            child: child + offset,
            origin: j.at,
            axis: j.axis.unwrap_or([1.0, 0.0, 0.0]),
            mimic: None,
        });
    }
    let root = floating.map_or(0, |f| ends[f].1);
    Ok(Inline {
        urdf: Urdf {
            name: name.to_string(),
            links,
            joints: out,
            root,
        },
        spans,
        floating: floating.is_some(),
        locks,
    })
}
