//! A robot from a URDF file: `#[lagrange(urdf = "robots/arm.urdf")]` on
//! the struct of a `lagrangian!`.
//!
//! A pipeline of its own beside the energy route, one file per stage:
//! [`urdf`] reads the file (roxmltree) into links and joints, every refusal
//! naming the element and its line; [`tree`] merges what is fixed or
//! locked into the moving bodies; [`algorithms`] runs Featherstone's
//! recursions (RNEA, CRBA, ABA, the energies) on traced scalars
//! ([`trace`]), which write the robot's own unrolled code with its
//! constants folded, as RobCoGen does; this module parses the macro's
//! input and emits the items. The energy route is not taken: its cost
//! grows far faster than the recursions' (issue 46).

// 3 × 3 and N × N index arithmetic reads as the textbook's.
#![allow(clippy::needless_range_loop)]

pub mod algorithms;
pub mod api;
pub mod floating;
pub mod language;
pub mod solve;
pub mod trace;
pub mod tree;
pub mod urdf;

use algorithms::frames::{self, Frame};
use algorithms::regressor;
use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote};
use syn::parse::{ParseStream, Parser};
use syn::{Attribute, Ident, LitStr, Token, Visibility, braced};
use trace::{Trace, Val};
use tree::{Body, Lock, Mass, TreeError};

/// What the macro's input says of a robot.
struct Input {
    attrs: Vec<Attribute>,
    vis: Visibility,
    name: Ident,
    path: LitStr,
    locks: Vec<(Ident, Lock)>,
    /// `floating`: the root link is a free body.
    floating: bool,
    /// `regressor`: also write the inertial-parameter regressor and the
    /// parameters `π` (opt-in, as the energy models' regressor: `10 n`
    /// columns, the largest item of a large robot).
    regressor: bool,
    /// `parameters(field = "link", ..)`: struct fields holding the ten
    /// inertial parameters of the named links' bodies, read by the code
    /// instead of the file's constants (for identification).
    params: Vec<(Ident, LitStr)>,
    /// A robot written as bodies and joints: its links and joints (and
    /// `path` is a string of its name), instead of a file.
    inline: Option<language::Inline>,
}

impl Input {
    /// Where an error about the robot (about joint `joint`, if any) lands,
    /// and the words naming the robot: the file's path, or for a robot
    /// written in the language, the joint's name (else the struct's) and
    /// `robot `Name``.
    fn site(&self, joint: Option<&str>) -> (Span, String) {
        match &self.inline {
            None => (self.path.span(), self.path.value()),
            Some(inline) => (
                joint
                    .and_then(|j| inline.joint_span(j))
                    .unwrap_or_else(|| self.name.span()),
                format!("robot `{}`", self.name),
            ),
        }
    }

    /// The item that rebuilds the crate when the URDF changes (none for a
    /// robot written in the language).
    fn include(&self) -> TokenStream {
        if self.inline.is_some() {
            return TokenStream::new();
        }
        let file = LitStr::new(&self.path.value(), Span::call_site());
        quote! {
            // The URDF read at compile time: rebuilt when it changes.
            const _: &[u8] = include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/", #file));
        }
    }
}

/// Whether the input is a robot: from URDF, the struct carries
/// `#[lagrange(urdf = "...")]`; in the language, its braces hold `bodies:`
/// or `joints:` ([`language::is_inline`]).
pub fn is_robot(input: &TokenStream) -> bool {
    if language::is_inline(input) {
        return true;
    }
    let probe = |stream: ParseStream| -> syn::Result<bool> {
        let attrs = stream.call(Attribute::parse_outer)?;
        let _ = stream.parse::<TokenStream>();
        Ok(attrs.iter().any(|a| {
            a.path().is_ident("lagrange")
                && a.parse_nested_meta(|m| {
                    if m.path.is_ident("urdf") {
                        return Err(m.error("found"));
                    }
                    if m.input.peek(Token![=]) {
                        let _: syn::Expr = m.value()?.parse()?;
                    } else if m.input.peek(syn::token::Paren) {
                        let _ = m.parse_nested_meta(|_| Ok(()));
                    }
                    Ok(())
                })
                .is_err_and(|e| e.to_string() == "found")
        }))
    };
    probe.parse2(input.clone()).unwrap_or(false)
}

/// `regressor` in a robot's `#[lagrange(..)]`: a flag, given once.
fn regressor_flag(m: &syn::meta::ParseNestedMeta, regressor: &mut bool) -> syn::Result<()> {
    if m.input.peek(Token![=]) || m.input.peek(syn::token::Paren) {
        return Err(m.error(
            "a robot's `regressor` takes no value: `#[lagrange(regressor)]` writes the regressor in every inertial \
             parameter of every body",
        ));
    }
    if *regressor {
        return Err(m.error("`regressor` is given twice"));
    }
    *regressor = true;
    Ok(())
}

/// `parameters(field = "link", ..)` in a robot's `#[lagrange(..)]`: given
/// once, each field and each link once.
fn parameters_list(
    m: &syn::meta::ParseNestedMeta,
    params: &mut Option<Vec<(Ident, LitStr)>>,
) -> syn::Result<()> {
    let usage = "`parameters(payload = \"link7\")` makes the struct's field `payload: [S; 10]` hold the ten \
                 inertial parameters of link `link7`'s body, which the code reads instead of the file's";
    if !m.input.peek(syn::token::Paren) {
        return Err(m.error(format!("`parameters` lists fields and links: {usage}")));
    }
    if params.is_some() {
        return Err(m.error("`parameters` is given twice"));
    }
    let list = params.insert(Vec::new());
    let content;
    let paren = syn::parenthesized!(content in m.input);
    if content.is_empty() {
        return Err(syn::Error::new(
            paren.span.join(),
            format!("`parameters()` names no field: {usage}"),
        ));
    }
    while !content.is_empty() {
        let field: Ident = content.parse().map_err(|e| {
            syn::Error::new(
                e.span(),
                format!("a field's name is an identifier: {usage}"),
            )
        })?;
        if !content.peek(Token![=]) {
            return Err(syn::Error::new(
                field.span(),
                format!(
                    "`{field}` names the link (or body) whose parameters it holds: `{field} = \"link\"`"
                ),
            ));
        }
        content.parse::<Token![=]>()?;
        let link: LitStr = content.parse()?;
        if list.iter().any(|(f, _)| *f == field) {
            return Err(syn::Error::new(
                field.span(),
                format!("field `{field}` is given twice"),
            ));
        }
        if let Some((f, _)) = list.iter().find(|(_, l)| l.value() == link.value()) {
            return Err(syn::Error::new(
                link.span(),
                format!("`{}` is given twice (its field is `{f}`)", link.value()),
            ));
        }
        list.push((field, link));
        if !content.is_empty() {
            content.parse::<Token![,]>()?;
        }
    }
    Ok(())
}

fn parse(input: TokenStream) -> syn::Result<Input> {
    let parser = |stream: ParseStream| -> syn::Result<Input> {
        let mut attrs = stream.call(Attribute::parse_outer)?;
        let mut path = None;
        let mut floating = false;
        let mut regressor = false;
        let mut params = None;
        let mut error: Option<syn::Error> = None;
        attrs.retain(|a| {
            if !a.path().is_ident("lagrange") {
                return true;
            }
            let r = a.parse_nested_meta(|m| {
                if m.path.is_ident("urdf") {
                    path = Some(m.value()?.parse::<LitStr>()?);
                    Ok(())
                } else if m.path.is_ident("floating") {
                    if m.input.peek(Token![=]) || m.input.peek(syn::token::Paren) {
                        return Err(m.error(
                            "`floating` takes no value: `#[lagrange(urdf = \"path\", floating)]` sets the root link free",
                        ));
                    }
                    if floating {
                        return Err(m.error("`floating` is given twice"));
                    }
                    floating = true;
                    Ok(())
                } else if m.path.is_ident("regressor") {
                    regressor_flag(&m, &mut regressor)
                } else if m.path.is_ident("parameters") {
                    parameters_list(&m, &mut params)
                } else {
                    Err(m.error(
                        "a robot from URDF takes `#[lagrange(urdf = \"path\")]`, with `floating` for a floating \
                         base, `regressor` for the inertial-parameter regressor and `parameters(field = \"link\")` \
                         for links' inertial parameters as fields, and nothing else: its dynamics are \
                         Featherstone's recursions, not derived from T and V",
                    ))
                }
            });
            if let Err(e) = r {
                error.get_or_insert(e);
            }
            false
        });
        if let Some(e) = error {
            return Err(e);
        }
        let vis: Visibility = stream.parse()?;
        stream.parse::<Token![struct]>()?;
        let name: Ident = stream.parse()?;
        let body;
        braced!(body in stream);
        let mut locks = Vec::new();
        while !body.is_empty() {
            let section: Ident = body.parse()?;
            if section != "locked" {
                return Err(syn::Error::new(
                    section.span(),
                    "a robot from URDF takes one section, `locked: joint = value, ...;` (joints held at a \
                     value: an angle in radians, or a displacement in metres); the rest is in the file",
                ));
            }
            body.parse::<Token![:]>()?;
            loop {
                let joint: Ident = body.call(syn::ext::IdentExt::parse_any)?;
                body.parse::<Token![=]>()?;
                let negative = body.parse::<Option<Token![-]>>()?.is_some();
                let lit: syn::Lit = body.parse()?;
                let value = match &lit {
                    syn::Lit::Float(f) => f.base10_parse::<f64>()?,
                    syn::Lit::Int(i) => i.base10_parse::<f64>()?,
                    _ => return Err(syn::Error::new(lit.span(), "a lock's value is a number")),
                };
                if !value.is_finite() {
                    return Err(syn::Error::new(
                        lit.span(),
                        "a lock's value is a finite number",
                    ));
                }
                let value = if negative { -value } else { value };
                locks.push((
                    joint.clone(),
                    Lock {
                        joint: joint.to_string(),
                        value,
                    },
                ));
                if body.parse::<Option<Token![,]>>()?.is_none() {
                    break;
                }
                if body.peek(Token![;]) {
                    break;
                }
            }
            body.parse::<Token![;]>()?;
        }
        let Some(path) = path else {
            return Err(syn::Error::new(
                name.span(),
                "`#[lagrange(urdf = \"path\")]` names the file",
            ));
        };
        Ok(Input {
            attrs,
            vis,
            name,
            path,
            locks,
            floating,
            regressor,
            params: params.unwrap_or_default(),
            inline: None,
        })
    };
    parser.parse2(input)
}

/// A robot written as bodies and joints: its attributes (`#[lagrange(..)]`
/// refused: the robot's options are its sections), name and sections.
fn parse_inline(input: TokenStream) -> syn::Result<Input> {
    crate::parse::groups_nest_within_the_limit(&input)?;
    let parser = |stream: ParseStream| -> syn::Result<Input> {
        let mut attrs = stream.call(Attribute::parse_outer)?;
        let mut regressor = false;
        let mut params = None;
        let mut error: Option<syn::Error> = None;
        attrs.retain(|a| {
            if !a.path().is_ident("lagrange") {
                return true;
            }
            let r = a.parse_nested_meta(|m| {
                if m.path.is_ident("regressor") {
                    regressor_flag(&m, &mut regressor)
                } else if m.path.is_ident("parameters") {
                    parameters_list(&m, &mut params)
                } else {
                    Err(m.error(
                        "a robot written as bodies and joints takes two `#[lagrange(..)]` options, `regressor` (the \
                         inertial-parameter regressor) and `parameters(field = \"body\")` (bodies' inertial \
                         parameters as fields): a floating base is the joint `floating base -> trunk`, its \
                         dynamics are Featherstone's recursions",
                    ))
                }
            });
            if let Err(e) = r {
                error.get_or_insert(e);
            }
            false
        });
        if let Some(e) = error {
            return Err(e);
        }
        let vis: Visibility = stream.parse()?;
        stream.parse::<Token![struct]>()?;
        let name: Ident = stream.parse()?;
        let body;
        braced!(body in stream);
        let sections: TokenStream = body.parse()?;
        let inline = language::read(sections, &name)?;
        let locks = inline
            .locks
            .iter()
            .map(|(joint, value)| {
                (
                    joint.clone(),
                    Lock {
                        joint: joint.to_string(),
                        value: *value,
                    },
                )
            })
            .collect();
        Ok(Input {
            attrs,
            vis,
            path: LitStr::new(&name.to_string(), name.span()),
            name,
            locks,
            floating: inline.floating,
            regressor,
            params: params.unwrap_or_default(),
            inline: Some(inline),
        })
    };
    parser.parse2(input)
}

/// The bodies and frames of the robot the input names and its root's
/// mass, or the error on its tokens; a URDF's path relative to
/// `manifest_dir`, else to `CARGO_MANIFEST_DIR`.
fn load(
    input: &Input,
    manifest_dir: Option<&std::path::Path>,
) -> syn::Result<(Vec<Body>, Mass, Vec<Frame>)> {
    if let Some(inline) = &input.inline {
        return load_inline(input, inline);
    }
    let rel = input.path.value();
    let span = input.path.span();
    let err = |message: String| syn::Error::new(span, message);
    let dir = match manifest_dir {
        Some(dir) => dir.to_path_buf(),
        None => match std::env::var("CARGO_MANIFEST_DIR") {
            Ok(dir) => std::path::PathBuf::from(dir),
            Err(_) => return Err(err("CARGO_MANIFEST_DIR is not set: the URDF's path is relative to the crate's manifest, which cargo names".into())),
        },
    };
    let full = dir.join(&rel);
    let text = std::fs::metadata(&full)
        .map_err(|e| {
            err(format!(
                "cannot read `{rel}` (relative to the crate's manifest): {e}"
            ))
        })
        .and_then(|meta| {
            if meta.len() > urdf::MAX_FILE {
                Err(err(format!(
                    "`{rel}` has {} bytes, more than a URDF may ({} bytes)",
                    meta.len(),
                    urdf::MAX_FILE
                )))
            } else {
                std::fs::read_to_string(&full)
                    .map_err(|e| err(format!("cannot read `{rel}` as UTF-8 text: {e}")))
            }
        })?;
    let locks: Vec<Lock> = input.locks.iter().map(|(_, l)| l.clone()).collect();
    let at = |r: urdf::Refusal| match r.line {
        Some(line) => err(format!("{rel}, line {line}: {}", r.message)),
        None => err(format!("{rel}: {}", r.message)),
    };
    let robot = urdf::read(&text).map_err(at)?;
    let (mut bodies, mut root) =
        tree::bodies(&robot, &locks, input.floating).map_err(|e| match e {
            TreeError::File(r) => at(r),
            TreeError::Lock(k, message) => {
                syn::Error::new(input.locks[k].0.span(), format!("{message} (in `{rel}`)"))
            }
        })?;
    if input.floating {
        if let Some(b) = bodies
            .iter()
            .find(|b| floating::BASE.contains(&b.name.as_str()))
        {
            return Err(err(format!(
                "{rel}: joint `{}` is named as one of the floating base's coordinates ({})",
                b.name,
                floating::BASE.join(", ")
            )));
        }
    }
    assign_parameters(input, &robot, &mut bodies, &mut root)?;
    let frames = frames::frames(&robot, &locks, &bodies);
    Ok((bodies, root, frames))
}

/// Each link `parameters(..)` names, its field set on the body it is (a
/// moving joint's child, or a floating base's root), or an error on the
/// link's string: a link that is not the robot's, a fixed base, a link
/// welded to another (whose body holds its mass).
fn assign_parameters(
    input: &Input,
    robot: &urdf::Urdf,
    bodies: &mut [Body],
    root: &mut Mass,
) -> syn::Result<()> {
    let whose = match &input.inline {
        None => format!("`{}`", input.path.value()),
        Some(_) => format!("robot `{}`", input.name),
    };
    let (link_word, links_word) = match &input.inline {
        None => ("link", "links"),
        Some(_) => ("body", "bodies"),
    };
    for (field, link) in &input.params {
        let name = link.value();
        let err = |m: String| Err(syn::Error::new(link.span(), m));
        let Some(l) = robot.links.iter().position(|x| x.name == name) else {
            return err(format!("{whose} has no {link_word} `{name}`"));
        };
        let field = field.to_string();
        if l == robot.root {
            if !input.floating {
                return err(format!(
                    "{link_word} `{name}` is the fixed base: it does not move, and its mass enters no dynamics"
                ));
            }
            root.param = Some(field);
            continue;
        }
        let parent_joint = |l: usize| robot.joints.iter().find(|j| j.child == l);
        let Some(joint) = parent_joint(l) else {
            return err(format!("{link_word} `{name}` is attached by no joint"));
        };
        if let Some(b) = bodies.iter_mut().find(|b| b.name == joint.name) {
            b.param = Some(field);
            continue;
        }
        // Welded (fixed, or locked): up to the link whose body it is part of.
        let mut owner = joint.parent;
        for _ in 0..robot.joints.len() {
            match parent_joint(owner) {
                Some(j) if !bodies.iter().any(|b| b.name == j.name) => owner = j.parent,
                _ => break,
            }
        }
        if owner == robot.root && !input.floating {
            return err(format!(
                "{link_word} `{name}` is fixed to the fixed base (through joint `{}`): it does not move, and its \
                 mass enters no dynamics",
                joint.name
            ));
        }
        let owner = &robot.links[owner].name;
        let how = if input.locks.iter().any(|(_, k)| k.joint == joint.name) {
            "locked"
        } else {
            "fixed"
        };
        return err(format!(
            "{link_word} `{name}` is welded to `{owner}` (joint `{}` is {how}): its mass is part of that body's, \
             and `parameters` names the {links_word} that move: `{field} = \"{owner}\"`",
            joint.name
        ));
    }
    Ok(())
}

/// The bodies and frames of a robot written in the language, its tree's
/// refusals on the names they are about.
fn load_inline(
    input: &Input,
    inline: &language::Inline,
) -> syn::Result<(Vec<Body>, Mass, Vec<Frame>)> {
    let locks: Vec<Lock> = input.locks.iter().map(|(_, l)| l.clone()).collect();
    let robot = &inline.urdf;
    let (mut bodies, mut root) =
        tree::bodies(robot, &locks, input.floating).map_err(|e| match e {
            TreeError::File(r) => syn::Error::new(
                inline.span(r.line).unwrap_or_else(|| input.name.span()),
                match r.line {
                    Some(_) => r.message,
                    None => format!("robot `{}`: {}", input.name, r.message),
                },
            ),
            TreeError::Lock(k, message) => syn::Error::new(input.locks[k].0.span(), message),
        })?;
    if input.floating {
        if let Some(b) = bodies
            .iter()
            .find(|b| floating::BASE.contains(&b.name.as_str()))
        {
            return Err(syn::Error::new(
                inline
                    .joint_span(&b.name)
                    .unwrap_or_else(|| input.name.span()),
                format!(
                    "joint `{}` is named as one of the floating base's coordinates ({})",
                    b.name,
                    floating::BASE.join(", ")
                ),
            ));
        }
    }
    assign_parameters(input, robot, &mut bodies, &mut root)?;
    let frames = frames::frames(robot, &locks, &bodies);
    Ok((bodies, root, frames))
}

/// Expands a robot from URDF or written as bodies and joints: the items,
/// or a `compile_error!` and a stub; a URDF's path relative to
/// `manifest_dir`, else to `CARGO_MANIFEST_DIR`.
pub fn expand(input: TokenStream, manifest_dir: Option<&std::path::Path>) -> TokenStream {
    let parsed = if language::is_inline(&input) {
        parse_inline(input)
    } else {
        parse(input)
    };
    let input = match parsed {
        Ok(i) => i,
        Err(e) => return e.to_compile_error(),
    };
    match load(&input, manifest_dir).and_then(|(bodies, root, frames)| {
        check(&input, &bodies, &root).map(|()| (bodies, root, frames))
    }) {
        Ok((bodies, root, frames)) if input.floating => {
            let mut items = floating::emit(&input, &bodies, &root);
            items.extend(api::emit_floating(
                &input.name,
                &bodies,
                &frames,
                &root,
                input.regressor,
            ));
            items
        }
        Ok((bodies, root, frames)) => {
            let mut items = emit(&input, &bodies, &root);
            items.extend(api::emit(&input.name, &bodies, &frames, input.regressor));
            items
        }
        Err(e) => {
            let (vis, name) = (&input.vis, &input.name);
            let error = e.to_compile_error();
            quote! {
                #error
                #[allow(dead_code)]
                #vis struct #name<S = f64>(::core::marker::PhantomData<S>);
            }
        }
    }
}

/// The states at which `M` is checked to be positive definite.
fn check_states(n: usize) -> [Vec<f64>; 3] {
    // Fixed, spread values: deterministic, away from special angles.
    let a: Vec<f64> = (0..n).map(|i| 0.3 + 0.7 * i as f64).collect();
    let b: Vec<f64> = (0..n)
        .map(|i| ((i * 7 + 3) % 11) as f64 * 0.55 - 2.7)
        .collect();
    [vec![0.0; n], a, b]
}

/// `M` positive definite at a few states: every joint moves some mass (on
/// a floating base, `M` in the velocities; the base's pose does not enter it).
fn check(input: &Input, bodies: &[Body], root: &Mass) -> syn::Result<()> {
    // At the file's parameters, the named ones too (`new()`'s).
    let bodies: Vec<Body> = bodies
        .iter()
        .cloned()
        .map(|b| Body { param: None, ..b })
        .collect();
    let root = &Mass {
        param: None,
        ..root.clone()
    };
    let bodies = &bodies[..];
    let n = bodies.len();
    let mut t = Trace::default();
    let q: Vec<Val> = (0..n).map(|i| t.input(quote!(q[#i]))).collect();
    let fb = input.floating.then_some(algorithms::Floating {
        mass: root,
        rot: [
            [trace::ONE, trace::ZERO, trace::ZERO],
            [trace::ZERO, trace::ONE, trace::ZERO],
            [trace::ZERO, trace::ZERO, trace::ONE],
        ],
        pos: [trace::ZERO; 3],
    });
    let m = algorithms::crba(&mut t, bodies, fb.as_ref(), &q);
    let o = if input.floating { 6 } else { 0 };
    let n = n + o;
    for state in check_states(n - o) {
        let values = t.eval(&state);
        let mut a: Vec<Vec<f64>> = m
            .iter()
            .map(|row| row.iter().map(|&x| Trace::value(&values, x)).collect())
            .collect();
        // Cholesky, each pivot against the diagonal's scale.
        for j in 0..n {
            let scale = a[j][j].abs().max(f64::MIN_POSITIVE);
            for k in 0..j {
                a[j][j] -= a[j][k] * a[j][k];
            }
            if (a[j][j].is_nan() || a[j][j] <= 1e-12 * scale) && j < o {
                let (span, robot) = input.site(None);
                return Err(syn::Error::new(
                    span,
                    format!(
                        "{robot}: the mass matrix is singular: the floating base carries no mass or inertia along one of \
                         its six motions (the root link and what is fixed to it, with the joints, are massless there)",
                    ),
                ));
            }
            if a[j][j].is_nan() || a[j][j] <= 1e-12 * scale {
                let (span, robot) = input.site(Some(&bodies[j - o].name));
                return Err(syn::Error::new(
                    span,
                    format!(
                        "{robot}: the mass matrix is singular: joint `{}` moves no mass or inertia about its axis \
                         (what it carries is massless, or it turns a body about its own symmetry line alone)",
                        bodies[j - o].name
                    ),
                ));
            }
            a[j][j] = a[j][j].sqrt();
            for i in j + 1..n {
                for k in 0..j {
                    a[i][j] -= a[i][k] * a[j][k];
                }
                a[i][j] /= a[j][j];
            }
        }
    }
    Ok(())
}

/// One generated function's body: inputs read, the trace written, the
/// outputs returned by `wrap`.
fn function(
    bodies: &[Body],
    reads: &[&str],
    run: impl FnOnce(&mut Trace, &[Vec<Val>]) -> Vec<Val>,
) -> (TokenStream, Vec<TokenStream>) {
    let n = bodies.len();
    let reads: Vec<(&str, usize)> = reads.iter().map(|&r| (r, n)).collect();
    function_of(&reads, run)
}

/// One generated function's body, its inputs (a name, a length) read.
fn function_of(
    reads: &[(&str, usize)],
    run: impl FnOnce(&mut Trace, &[Vec<Val>]) -> Vec<Val>,
) -> (TokenStream, Vec<TokenStream>) {
    let mut t = Trace::default();
    let inputs: Vec<Vec<Val>> = reads
        .iter()
        .map(|&(r, n)| {
            let r = format_ident!("{}", r);
            (0..n).map(|i| t.input(quote!(#r[#i]))).collect()
        })
        .collect();
    let outs = run(&mut t, &inputs);
    t.emit(&outs)
}

/// The robot's struct and its `new()`: a unit of `PhantomData`, or with
/// `parameters(..)` a field of ten inertial parameters per named link,
/// which `new()` sets to the file's.
fn robot_struct(input: &Input, bodies: &[Body], root: &Mass) -> (TokenStream, TokenStream) {
    let (vis, name, attrs) = (&input.vis, &input.name, &input.attrs);
    if input.params.is_empty() {
        return (
            quote! {
                #(#attrs)*
                #[derive(Clone, Copy, Debug, Default, PartialEq)]
                #vis struct #name<S = f64>(::core::marker::PhantomData<S>);
            },
            quote! {
                /// The robot (its constants are in the code).
                #[inline]
                pub const fn new() -> Self {
                    Self(::core::marker::PhantomData)
                }
            },
        );
    }
    let simd = quote! {
        S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy,
        S::Element: ::lagrange::nalgebra::RealField + ::core::marker::Copy,
    };
    let mut fields = Vec::new();
    let mut values = Vec::new();
    for (field, link) in &input.params {
        let key = field.to_string();
        // `assign_parameters` gave every field its body.
        let pi = match bodies.iter().find(|b| b.param.as_deref() == Some(&key)) {
            Some(b) => regressor::parameters(b),
            None => regressor::base_parameters(root),
        };
        let doc = format!(
            "The ten inertial parameters of `{}`'s body (what is fixed or locked to it included), in \
             Pinocchio's order: `m`, the first moment `m c` (3), the inertia about the joint frame `Ixx, Ixy, \
             Iyy, Ixz, Iyz, Izz`, in the body's axes (its ten columns of the regressor). Every method reads \
             them; [`new`](Self::new) sets the file's.",
            link.value()
        );
        fields.push(quote!(#[doc = #doc] #vis #field: [S; 10]));
        let lits = pi.map(proc_macro2::Literal::f64_suffixed);
        values.push(quote!(#field: [#(::lagrange::nalgebra::convert::<f64, S>(#lits)),*]));
    }
    (
        quote! {
            #(#attrs)*
            #[derive(Clone, Copy, Debug, PartialEq)]
            #vis struct #name<S = f64> {
                #(#fields,)*
            }

            impl<S> ::core::default::Default for #name<S> where #simd {
                #[inline]
                fn default() -> Self {
                    Self::new()
                }
            }
        },
        quote! {
            /// The robot, its named inertial parameters the file's.
            #[inline]
            pub fn new() -> Self {
                Self { #(#values,)* }
            }
        },
    )
}

fn emit(input: &Input, bodies: &[Body], root: &Mass) -> TokenStream {
    let n = bodies.len();
    let name = &input.name;
    let rel = input.path.value();
    let (item, new) = robot_struct(input, bodies, root);
    let names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
    let vector = |outs: Vec<TokenStream>| {
        quote!(::lagrange::nalgebra::SVector::<S, #n>::from_array_storage(
            ::lagrange::nalgebra::ArrayStorage([[#(#outs),*]])
        ))
    };
    let (rnea_body, rnea_out) = function(bodies, &["q", "qdot", "qddot"], |t, x| {
        algorithms::rnea(t, bodies, None, &x[0], &x[1], &x[2], true)
    });
    let rnea_out = vector(rnea_out);
    let (nle_body, nle_out) = function(bodies, &["q", "qdot"], |t, x| {
        let zero = vec![trace::ZERO; n];
        algorithms::rnea(t, bodies, None, &x[0], &x[1], &zero, true)
    });
    let nle_out = vector(nle_out);
    let (grav_body, grav_out) = function(bodies, &["q"], |t, x| {
        let zero = vec![trace::ZERO; n];
        algorithms::rnea(t, bodies, None, &x[0], &zero, &zero, true)
    });
    let grav_out = vector(grav_out);
    let (aba_body, aba_out) = function(bodies, &["q", "qdot", "tau"], |t, x| {
        algorithms::aba(t, bodies, None, &x[0], &x[1], &x[2])
    });
    let aba_out = vector(aba_out);
    let (acc_body, acc_out) = function(bodies, &["q", "qdot"], |t, x| {
        let zero = vec![trace::ZERO; n];
        algorithms::aba(t, bodies, None, &x[0], &x[1], &zero)
    });
    let acc_out = vector(acc_out);
    let (crba_body, crba_out) = function(bodies, &["q"], |t, x| {
        algorithms::crba(t, bodies, None, &x[0])
            .into_iter()
            .flatten()
            .collect()
    });
    let columns: Vec<TokenStream> = crba_out.chunks(n).map(|col| quote!([#(#col),*])).collect();
    let (ke_body, ke_out) = function(bodies, &["q", "qdot"], |t, x| {
        vec![algorithms::kinetic(t, bodies, None, &x[0], &x[1])]
    });
    let (pe_body, pe_out) = function(bodies, &["q"], |t, x| {
        vec![algorithms::potential(t, bodies, None, &x[0])]
    });
    let (ke, pe) = (&ke_out[0], &pe_out[0]);
    let parents: Vec<Option<usize>> = bodies.iter().map(|b| b.parent).collect();
    let (solve_body, _) = solve::emit(&solve::parent_table(&parents, 0));
    let doc_n = format!("Number of degrees of freedom: the moving joints of `{rel}`.");
    let simd = quote! {
        S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy,
        S::Element: ::lagrange::nalgebra::RealField + ::core::marker::Copy,
    };
    let sv = quote!(::lagrange::nalgebra::SVector<S, #n>);
    let include = input.include();
    quote! {
        #item

        #include

        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
        impl<S> #name<S> where #simd {
            #[doc = #doc_n]
            pub const DOF: usize = #n;
            /// Names of the coordinates: the moving joints, parents first.
            pub const COORDINATES: [&'static str; #n] = [#(#names),*];
            #new
            /// Inverse dynamics by RNEA: the joint forces `τ(q, q̇, q̈)`
            /// that give the accelerations `q̈`, gravity included.
            #[inline]
            pub fn inverse_dynamics(&self, q: &#sv, qdot: &#sv, qddot: &#sv) -> #sv {
                #rnea_body
                #rnea_out
            }
            /// The nonlinear effects `C(q, q̇) q̇ + g(q)` (RNEA at `q̈ = 0`):
            /// `M q̈ + nle = τ`.
            #[inline]
            pub fn nonlinear_effects(&self, q: &#sv, qdot: &#sv) -> #sv {
                #nle_body
                #nle_out
            }
            /// The gravity torques `g(q)` (RNEA at rest).
            #[inline]
            pub fn gravity_torques(&self, q: &#sv) -> #sv {
                #grav_body
                #grav_out
            }
            /// Forward dynamics by ABA: `q̈(q, q̇, τ)`, without forming `M`.
            #[inline]
            pub fn forward_dynamics(&self, q: &#sv, qdot: &#sv, tau: &#sv) -> #sv {
                #aba_body
                #aba_out
            }
            /// `q̈(q, q̇)` unforced (ABA at `τ = 0`): what a run integrates.
            #[inline]
            pub fn unforced_accelerations(&self, q: &#sv, qdot: &#sv) -> #sv {
                #acc_body
                #acc_out
            }
            /// The mass matrix `M(q)` by CRBA.
            #[inline]
            pub fn mass_matrix(&self, t: S, q: &#sv) -> ::lagrange::nalgebra::SMatrix<S, #n, #n> {
                #crba_body
                ::lagrange::nalgebra::SMatrix::<S, #n, #n>::from_array_storage(
                    ::lagrange::nalgebra::ArrayStorage([#(#columns),*])
                )
            }
            /// The forcing of `M q̈ = f`: `f = −nle(q, q̇)`.
            #[inline]
            pub fn forcing(&self, t: S, q: &#sv, qdot: &#sv) -> #sv {
                -self.nonlinear_effects(q, qdot)
            }
            /// The kinetic energy `½ Σ vᵢᵀ Iᵢ vᵢ`.
            #[inline]
            pub fn kinetic_energy(&self, t: S, q: &#sv, qdot: &#sv) -> S {
                #ke_body
                #ke
            }
            /// The potential energy in gravity `9.81` along `−z`.
            #[inline]
            pub fn potential_energy(&self, t: S, q: &#sv) -> S {
                #pe_body
                #pe
            }
        }

        #[allow(unused_variables, clippy::all)]
        impl<S: ::lagrange::nalgebra::RealField + ::core::marker::Copy> ::lagrange::Lagrangian<#n> for #name<S> {
            type Scalar = S;
            const COORDINATES: [&'static str; #n] = [#(#names),*];
            #[inline]
            fn mass_matrix(&self, t: S, q: &#sv) -> ::lagrange::nalgebra::SMatrix<S, #n, #n> {
                #name::mass_matrix(self, t, q)
            }
            #[inline]
            fn forcing(&self, t: S, q: &#sv, qdot: &#sv) -> #sv {
                #name::forcing(self, t, q, qdot)
            }
            #[inline]
            fn kinetic_energy(&self, t: S, q: &#sv, qdot: &#sv) -> S {
                #name::kinetic_energy(self, t, q, qdot)
            }
            #[inline]
            fn potential_energy(&self, t: S, q: &#sv) -> S {
                #name::potential_energy(self, t, q)
            }
            #[inline]
            fn accelerations(
                &self,
                t: S,
                q: &#sv,
                qdot: &#sv,
            ) -> ::core::option::Option<::core::result::Result<#sv, ::lagrange::error::IntegrationError<S, #n>>> {
                ::core::option::Option::Some(::core::result::Result::Ok(#name::unforced_accelerations(self, q, qdot)))
            }
            const SOLVES_ACCELERATIONS: bool = true;
        }

        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
        impl<S: ::lagrange::nalgebra::RealField + ::core::marker::Copy> #name<S> {
            /// `M⁻¹ b` for the mass matrix `m` of [`mass_matrix`](Self::mass_matrix):
            /// Featherstone's sparse `M = Lᵀ D L`, unrolled over this robot's
            /// tree, then its two substitutions (`Σ depth²` operations, not
            /// a dense Cholesky's `N³ / 6`). Reads only the lower triangle's
            /// entries `(i, j)` with `j` an ancestor of `i` (the others are
            /// zero in any `M` of this tree). `None` where a pivot of `D` is
            /// not finite or not above `N ε` times the largest (`m` not
            /// positive definite, or too ill-conditioned), or `x` is not
            /// finite: never a NaN. `M q̈ = τ − nle` is
            /// `solve_mass_matrix(&m, &(tau - nle))`.
            #[inline]
            pub fn solve_mass_matrix(
                &self,
                m: &::lagrange::nalgebra::SMatrix<S, #n, #n>,
                b: &#sv,
            ) -> ::core::option::Option<#sv> {
                #solve_body
            }
        }
    }
}
