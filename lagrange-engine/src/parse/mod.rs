//! Tokens → [`ast::ModelDef`](crate::ast::ModelDef).
//!
//! Expressions use mathematical precedence, not Rust's: `^` is power and binds
//! tighter than unary minus (`-x^2 = -(x²)`), which binds tighter than `*` and
//! `/` (`a*b^2 = a·b²`); `^` is right-associative and its exponent may carry a
//! sign (`x^-1`). Rust method syntax (`x.sin()`, `x.powi(2)`) means the same as
//! the function form. The expression grammar is in [`expression`]; this
//! module reads the model's header and its sections.
//!
//! A malformed section does not stop the parse: the parser records the first
//! error, skips to the next `;` and goes on, so the fallback can still emit a
//! stub with the coordinates and parameters that were declared (one mistake,
//! one error).

mod domain;
pub mod expression;

pub use expression::parse_expr;

use crate::ast::{
    ConstraintDef, ContactDef, Decl, Expr, IndexRange, Item, MAX_BUDGET, ModelDef, Options,
    SpanRange,
};
use crate::emit::{DEFAULT_MAX_CODE, MAX_CODE};
use crate::expr::DEFAULT_BUDGET;
use expression::{drain_on_error, parse_bracket, parse_index_range};
use proc_macro2::{TokenStream, TokenTree};
use syn::parse::{ParseStream, Parser};
use syn::{Attribute, Ident, LitInt, Token, Visibility, braced, bracketed};

/// The sections a model may contain, for error messages.
pub const SECTIONS: &str = "`const`, `coordinates:`, `parameters:`, `inputs:`, `constants:`, `let`, `kinetic:`, \
     `potential:`, `dissipation:`, `forces:`, `constraints:` or `contacts:`";

/// A parsed model and the first error met inside its body, if any.
pub struct Parsed {
    /// The model, with every item that parsed (one in error is skipped).
    pub model: ModelDef,
    /// The first error met inside the body or in `#[lagrange(...)]`.
    pub error: Option<syn::Error>,
}

/// Parses the macro input. `Err` only when not even the `struct Name { .. }`
/// header could be read.
pub fn parse(tokens: TokenStream) -> syn::Result<Parsed> {
    let parser = |input: ParseStream| -> syn::Result<Parsed> {
        let mut attrs = input.call(Attribute::parse_outer)?;
        let (options, options_error) = take_options(&mut attrs);
        let vis: Visibility = input.parse()?;
        if !input.peek(Token![struct]) {
            return Err(input.error(
                "expected `struct Name { ... }`: a model is written as a struct holding its sections",
            ));
        }
        input.parse::<Token![struct]>()?;
        let name: Ident = input.parse()?;
        if input.peek(Token![<]) {
            return Err(input.error(
                "a model takes no generic parameters: the generated struct is generic over its scalar `S` already",
            ));
        }
        let body;
        braced!(body in input);
        let mut items = Vec::new();
        let mut error: Option<syn::Error> = options_error;
        while !body.is_empty() {
            match parse_item(&body, &mut error) {
                Ok(item) => items.push(item),
                Err(e) => {
                    error.get_or_insert(e);
                    skip_past_semicolon(&body)?;
                }
            }
        }
        if !input.is_empty() {
            error.get_or_insert(input.error("unexpected tokens after the model's closing brace"));
        }
        Ok(Parsed {
            model: ModelDef {
                attrs,
                options,
                vis,
                name,
                items,
            },
            error,
        })
    };
    groups_nest_within_the_limit(&tokens)?;
    parser.parse2(tokens)
}

/// The brackets of `tokens` nested no deeper than an expression may nest
/// (a few levels more, for the model's braces and a law's), checked
/// without recursion before syn reads them: syn's token buffer recurses
/// into every group, at every depth, before the parser can stop at its
/// limit, and at opt-level 0 (as rustc's proc-macro builds compile syn by
/// default) thousands of nested parentheses took more than 4 MiB of stack.
/// The error is the parser's own, on the first bracket past the limit.
pub(crate) fn groups_nest_within_the_limit(tokens: &TokenStream) -> syn::Result<()> {
    // The model's braces, a section's, a contact law's, an index: levels
    // the expression parser does not count.
    const ENCLOSING: usize = 4;
    let mut open = vec![tokens.clone().into_iter()];
    while let Some(level) = open.last_mut() {
        match level.next() {
            Some(proc_macro2::TokenTree::Group(group)) => {
                if open.len() > expression::MAX_NESTING + ENCLOSING {
                    return Err(expression::too_deep(group.span_open()));
                }
                open.push(group.stream().into_iter());
            }
            Some(_) => {}
            None => {
                open.pop();
            }
        }
    }
    Ok(())
}

/// Removes the `#[lagrange(...)]` attributes and reads their options, with
/// the first error met (the model is still parsed, for the stub).
fn take_options(attrs: &mut Vec<Attribute>) -> (Options, Option<syn::Error>) {
    let mut options = Options::default();
    let mut result = Ok(());
    attrs.retain(|attr| {
        if !attr.path().is_ident("lagrange") {
            return true;
        }
        let parsed = attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("jacobians") {
                options.jacobians = true;
                Ok(())
            } else if meta.path.is_ident("serde") {
                options.serde = true;
                Ok(())
            } else if meta.path.is_ident("parameter_derivatives") {
                options.parameter_derivatives = true;
                Ok(())
            } else if meta.path.is_ident("regressor") {
                let mut names = Vec::new();
                meta.parse_nested_meta(|inner| {
                    let name = inner.path.require_ident()?.clone();
                    if names.contains(&name) {
                        return Err(inner.error(format!(
                            "`{name}` is listed twice in `regressor(...)`"
                        )));
                    }
                    names.push(name);
                    Ok(())
                })?;
                if names.is_empty() {
                    return Err(meta.error(
                        "`regressor(...)` lists the parameters the equations are to be \
                         written linearly in, e.g. `regressor(m1, m2, c1)`",
                    ));
                }
                options.regressor = Some(names);
                Ok(())
            } else if meta.path.is_ident("articulated") {
                options.articulated = Some(if meta.input.peek(syn::Token![=]) {
                    meta.value()?.parse::<syn::LitBool>()?.value
                } else {
                    true
                });
                Ok(())
            } else if meta.path.is_ident("budget") {
                let lit: LitInt = meta.value()?.parse()?;
                match lit.base10_parse::<u64>() {
                    Ok(n) if (1..=MAX_BUDGET).contains(&n) => {
                        options.budget = Some(n);
                        Ok(())
                    }
                    _ => Err(syn::Error::new(
                        lit.span(),
                        format!("the budget is a number of steps from 1 to {MAX_BUDGET} (the default is {DEFAULT_BUDGET})"),
                    )),
                }
            } else if meta.path.is_ident("max_code") {
                let lit: LitInt = meta.value()?.parse()?;
                match lit.base10_parse::<u64>() {
                    Ok(n) if (1..=MAX_CODE).contains(&n) => {
                        options.max_code = Some(n);
                        Ok(())
                    }
                    _ => Err(syn::Error::new(
                        lit.span(),
                        format!(
                            "the code limit is a number of bytes from 1 to {MAX_CODE} (the default is {DEFAULT_MAX_CODE})"
                        ),
                    )),
                }
            } else {
                Err(meta.error(
                    "unknown option: `#[lagrange(...)]` takes `jacobians` (exact residual Jacobians for implicit integrators), \
                     `parameter_derivatives` (the derivatives of M, f and the residual by the parameters), \
                     `regressor(p1, p2, ..)` (M q̈ − f written linearly in the products of those parameters), \
                     `serde` (the struct serializable, with lagrange's `serde` feature), \
                     `articulated` or `articulated = false` (M q̈ = f solved by the recursion over a tree of \
                     links, required or refused), `budget = N` (the engine's work budget, in steps) and `max_code = N` \
                     (the most bytes of generated code)",
                ))
            }
        });
        if let Err(e) = parsed {
            if result.is_ok() {
                result = Err(e);
            }
        }
        false
    });
    (options, result.err())
}

/// A name of the model: an identifier, not a raw one (`r#type`), since every
/// name becomes a local variable of the generated code.
fn plain_name(input: ParseStream) -> syn::Result<Ident> {
    let name: Ident = input.parse()?;
    if name.to_string().starts_with("r#") {
        return Err(syn::Error::new(
            name.span(),
            format!(
                "raw identifier `{name}`: model names become local variables, choose a name that is not a Rust keyword"
            ),
        ));
    }
    Ok(name)
}

fn skip_past_semicolon(input: ParseStream) -> syn::Result<()> {
    input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tt, next)) = rest.token_tree() {
            rest = next;
            if let TokenTree::Punct(p) = &tt {
                if p.as_char() == ';' {
                    break;
                }
            }
        }
        Ok(((), rest))
    })
}

/// `error` takes a mistake the parser recovered from (a missing `;` before
/// the next section), so that the section is kept and the stub complete.
fn parse_item(input: ParseStream, error: &mut Option<syn::Error>) -> syn::Result<Item> {
    if input.peek(Token![let]) {
        input.parse::<Token![let]>()?;
        let name: Ident = plain_name(input)?;
        let index = optional_index_range(input)?;
        if !input.peek(Token![=]) {
            return Err(input.error(
                "expected `=`: a `let` is written `let x = expression;` or `let x[i in 0..N] = expression;`",
            ));
        }
        input.parse::<Token![=]>()?;
        let value = parse_expr(input)?;
        expect_semicolon(input, error)?;
        return Ok(Item::Let { name, index, value });
    }
    if input.peek(Token![const]) {
        input.parse::<Token![const]>()?;
        let name: Ident = plain_name(input)?;
        if !input.peek(Token![=]) {
            return Err(input.error("expected `=`: a compile-time size is written `const N = 6;`"));
        }
        input.parse::<Token![=]>()?;
        let value = parse_expr(input)?;
        expect_semicolon(input, error)?;
        return Ok(Item::Const { name, value });
    }
    if !input.peek(syn::Ident) {
        return Err(input.error(format!("expected a section: {SECTIONS}")));
    }
    let keyword: Ident = input.parse()?;
    let section = keyword.to_string();
    let known = [
        "coordinates",
        "parameters",
        "inputs",
        "constants",
        "kinetic",
        "potential",
        "dissipation",
        "forces",
        "constraints",
        "contacts",
    ];
    if !known.contains(&section.as_str()) {
        return Err(syn::Error::new(
            keyword.span(),
            format!("unknown section `{section}`: expected {SECTIONS}"),
        ));
    }
    input.parse::<Token![:]>()?;
    Ok(match section.as_str() {
        "coordinates" => Item::Coordinates {
            names: parse_names(input, error, false)?,
            keyword,
        },
        "parameters" => Item::Parameters {
            names: parse_names(input, error, true)?,
            keyword,
        },
        "inputs" => Item::Inputs {
            names: parse_names(input, error, false)?,
            keyword,
        },
        "forces" => Item::Forces {
            entries: parse_entries(input, error, true)?
                .into_iter()
                .map(|(target, index, value)| {
                    let target = match index {
                        None => Expr::Name(target),
                        Some((index, close)) => Expr::Index {
                            range: SpanRange::single(target.span()).to(SpanRange::single(close)),
                            base: target,
                            index: Box::new(index),
                        },
                    };
                    (target, value)
                })
                .collect(),
            keyword,
        },
        "constraints" => Item::Constraints {
            entries: parse_constraints(input, error)?,
            keyword,
        },
        "contacts" => Item::Contacts {
            entries: parse_contacts(input, error)?,
            keyword,
        },
        "constants" => Item::Constants {
            entries: parse_entries(input, error, false)?
                .into_iter()
                .map(|(name, _, value)| (name, value))
                .collect(),
            keyword,
        },
        _ => {
            let value = parse_expr(input)?;
            expect_semicolon(input, error)?;
            match section.as_str() {
                "kinetic" => Item::Kinetic { keyword, value },
                "potential" => Item::Potential { keyword, value },
                _ => Item::Dissipation { keyword, value },
            }
        }
    })
}

/// A missing `;` right before the next section: recorded in `error`, and the
/// parse goes on as if it were there.
fn recover_missing_semicolon(input: ParseStream, error: &mut Option<syn::Error>) -> bool {
    let next = if input.peek(Token![let]) {
        "let".to_string()
    } else if input.peek(Token![const]) {
        "const".to_string()
    } else if input.peek(syn::Ident) && input.peek2(Token![:]) {
        match input.fork().parse::<Ident>() {
            Ok(keyword) => format!("{keyword}:"),
            Err(_) => return false,
        }
    } else {
        return false;
    };
    error.get_or_insert(input.error(format!(
        "expected `;` before `{next}`: each section ends with `;`"
    )));
    true
}

fn expect_semicolon(input: ParseStream, error: &mut Option<syn::Error>) -> syn::Result<()> {
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
        Ok(())
    } else if recover_missing_semicolon(input, error) {
        Ok(())
    } else if input.is_empty() {
        Err(input.error("expected `;` at the end of this section"))
    } else {
        Err(input.error("expected an operator or `;`"))
    }
}

fn parse_names(
    input: ParseStream,
    error: &mut Option<syn::Error>,
    parameters: bool,
) -> syn::Result<Vec<Decl>> {
    let mut names = Vec::new();
    loop {
        if input.peek(Token![;]) && !names.is_empty() {
            input.parse::<Token![;]>()?;
            return Ok(names);
        }
        let name = plain_name(input)?;
        let len = parse_bracket(input)?.map(|(len, _)| len);
        let domain = if starts_domain(input) {
            if !parameters {
                return Err(input.error(
                    "only a parameter has a domain (`parameters: l > 0;`): coordinates and \
                     inputs take any value",
                ));
            }
            // A malformed domain is recorded and the name kept without
            // it, so that the stub still has every parameter (one
            // mistake, one error).
            match domain::parse_domain(input, &name) {
                Ok(domain) => Some(domain),
                Err(e) => {
                    error.get_or_insert(e);
                    domain::skip_to_separator(input)?;
                    None
                }
            }
        } else {
            None
        };
        names.push(Decl { name, len, domain });
        if input.peek(Token![,]) {
            input.parse::<Token![,]>()?;
        } else if input.peek(Token![;]) {
            input.parse::<Token![;]>()?;
            return Ok(names);
        } else if recover_missing_semicolon(input, error) {
            return Ok(names);
        } else {
            return Err(input.error("expected `,` or `;` after a name"));
        }
    }
}

/// Whether a domain follows a parameter's name: `>`, `>=`, `<`, `<=` or `in`.
fn starts_domain(input: ParseStream) -> bool {
    input.peek(Token![>]) || input.peek(Token![<]) || input.peek(Token![in])
}

/// One entry of `forces:` or `constants:`.
type Entry = (Ident, Option<(Expr, proc_macro2::Span)>, Expr);

/// `name = expr, ...;` (`forces:` targets may be indexed: `x[N-1] = ...`).
fn parse_entries(
    input: ParseStream,
    error: &mut Option<syn::Error>,
    forces: bool,
) -> syn::Result<Vec<Entry>> {
    let mut entries = Vec::new();
    loop {
        if input.peek(Token![;]) && !entries.is_empty() {
            input.parse::<Token![;]>()?;
            return Ok(entries);
        }
        let target: Ident = plain_name(input)?;
        let index = if forces { parse_bracket(input)? } else { None };
        if !input.peek(Token![=]) {
            return Err(input.error(if forces {
                "expected `=`: a force is written `position = expression`, e.g. `x1 = -c*dot(x1)`"
            } else {
                "expected `=`: a constant is written `name = value`, e.g. `g = 9.81`"
            }));
        }
        input.parse::<Token![=]>()?;
        let value = parse_expr(input)?;
        entries.push((target, index, value));
        if input.peek(Token![,]) {
            input.parse::<Token![,]>()?;
        } else if input.peek(Token![;]) {
            input.parse::<Token![;]>()?;
            return Ok(entries);
        } else if recover_missing_semicolon(input, error) {
            return Ok(entries);
        } else {
            return Err(input.error("expected an operator, `,` or `;`"));
        }
    }
}

/// `name: lhs [= rhs], name[i in a..b]: lhs [= rhs], ...;`.
fn parse_constraints(
    input: ParseStream,
    error: &mut Option<syn::Error>,
) -> syn::Result<Vec<ConstraintDef>> {
    let mut entries = Vec::new();
    loop {
        if input.peek(Token![;]) && !entries.is_empty() {
            input.parse::<Token![;]>()?;
            return Ok(entries);
        }
        let name: Ident = plain_name(input)?;
        let index = optional_index_range(input)?;
        if !input.peek(Token![:]) || input.peek(Token![::]) {
            return Err(input.error(
                "expected `:` after the constraint's name: each constraint is named, as in \
                 `rod: x^2 + y^2 = l^2` (or `rod: expression`, meaning expression = 0)",
            ));
        }
        input.parse::<Token![:]>()?;
        let lhs = parse_expr(input)?;
        let rhs = if input.peek(Token![=]) {
            input.parse::<Token![=]>()?;
            Some(parse_expr(input)?)
        } else {
            None
        };
        entries.push(ConstraintDef {
            name,
            index,
            lhs,
            rhs,
        });
        if section_ends(input, error, "expected an operator, `=`, `,` or `;`")? {
            return Ok(entries);
        }
    }
}

/// `name: lhs >= rhs { key: value, ... }, ...;` (or `<=`; the braces
/// optional).
fn parse_contacts(
    input: ParseStream,
    error: &mut Option<syn::Error>,
) -> syn::Result<Vec<ContactDef>> {
    let mut entries = Vec::new();
    loop {
        if input.peek(Token![;]) && !entries.is_empty() {
            input.parse::<Token![;]>()?;
            return Ok(entries);
        }
        let name: Ident = plain_name(input)?;
        if !input.peek(Token![:]) || input.peek(Token![::]) {
            return Err(input.error(
                "expected `:` after the contact's name: each contact is named, as in `floor: y >= 0`",
            ));
        }
        input.parse::<Token![:]>()?;
        // Without a gap, friction against a given normal force:
        // `brake: { normal: F, friction: mu, slip: r*dot(theta) }`.
        let has_gap = !input.peek(syn::token::Brace);
        let zero = || Expr::Num {
            value: 0.0,
            span: name.span(),
        };
        let (lhs, at_least, rhs) = if has_gap {
            let lhs = parse_expr(input)?;
            let at_least = if input.peek(Token![>=]) {
                input.parse::<Token![>=]>()?;
                true
            } else if input.peek(Token![<=]) {
                input.parse::<Token![<=]>()?;
                false
            } else {
                return Err(input.error(
                    "expected `>=` or `<=`: a contact is a gap that stays non-negative, as in `floor: y >= 0` \
                     (an equation `=` is a constraint, in `constraints:`)",
                ));
            };
            (lhs, at_least, parse_expr(input)?)
        } else {
            (zero(), true, zero())
        };
        let mut fields = Vec::new();
        if input.peek(syn::token::Brace) {
            let inner;
            braced!(inner in input);
            drain_on_error(&inner, |inner| {
                while !inner.is_empty() {
                    let key: Ident = inner.parse()?;
                    if !inner.peek(Token![:]) || inner.peek(Token![::]) {
                        return Err(inner.error(
                            "expected `:` after the law's entry, as in `{ restitution: e, friction: mu, slip: dot(x) }`",
                        ));
                    }
                    inner.parse::<Token![:]>()?;
                    fields.push((key, parse_expr(inner)?));
                    if inner.peek(Token![,]) {
                        inner.parse::<Token![,]>()?;
                    } else if !inner.is_empty() {
                        return Err(inner.error("expected an operator, `,` or `}`"));
                    }
                }
                Ok(())
            })?;
        }
        entries.push(ContactDef {
            name,
            lhs,
            at_least,
            rhs,
            has_gap,
            fields,
        });
        if section_ends(input, error, "expected an operator, `{`, `,` or `;`")? {
            return Ok(entries);
        }
    }
}

/// After an entry of a comma-separated section: `false` where a `,` says
/// another entry follows, `true` where the section ends (its `;`, or a
/// missing one recovered); else the error `expected`.
fn section_ends(
    input: ParseStream,
    error: &mut Option<syn::Error>,
    expected: &str,
) -> syn::Result<bool> {
    if input.peek(Token![,]) {
        input.parse::<Token![,]>()?;
        Ok(false)
    } else if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
        Ok(true)
    } else if recover_missing_semicolon(input, error) {
        Ok(true)
    } else {
        Err(input.error(expected))
    }
}

/// `[i in a..b]` after an indexed `let`'s or constraint's name, if there.
fn optional_index_range(input: ParseStream) -> syn::Result<Option<IndexRange>> {
    if !input.peek(syn::token::Bracket) {
        return Ok(None);
    }
    let inner;
    bracketed!(inner in input);
    let range = drain_on_error(&inner, |inner| {
        let range = parse_index_range(inner)?;
        if !inner.is_empty() {
            return Err(inner.error("expected `]` after the range"));
        }
        Ok(range)
    })?;
    Ok(Some(range))
}
