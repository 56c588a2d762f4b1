//! A parameter's domain after its name: `m > 0`, `c >= 0`, `u < 1`,
//! `u <= 1`, `e in [0, 1]` (closed), `x in (0, 1)` (open). The bounds are
//! number literals, optionally negative; the lower below the upper. A
//! half-open interval cannot be written as brackets (`(0, 1]` is not a
//! token tree): `x > 0` with `x <= 1` would need two bounds on one name,
//! which the language does not take.

use crate::ast::Domain;
use proc_macro2::{Delimiter, Span, TokenTree};
use syn::parse::ParseStream;
use syn::{Ident, Token};

/// The domain after `name`, the input at its `>`, `<` or `in`.
pub(super) fn parse_domain(input: ParseStream, name: &Ident) -> syn::Result<Domain> {
    let inf = f64::INFINITY;
    if input.peek(Token![in]) {
        let keyword = input.parse::<Token![in]>()?;
        let group = match input.parse::<TokenTree>() {
            Ok(TokenTree::Group(g))
                if matches!(g.delimiter(), Delimiter::Bracket | Delimiter::Parenthesis) =>
            {
                g
            }
            Ok(other) => {
                return Err(syn::Error::new(
                    other.span(),
                    format!(
                        "expected an interval after `in`: `{name} in [0, 1]` (closed) or \
                         `{name} in (0, 1)` (open)"
                    ),
                ));
            }
            Err(_) => {
                return Err(syn::Error::new(
                    keyword.span,
                    format!("expected an interval after `in`: `{name} in [0, 1]`"),
                ));
            }
        };
        let closed = group.delimiter() == Delimiter::Bracket;
        let (lower, upper) = syn::parse::Parser::parse2(
            |inner: ParseStream| {
                let lower = bound(inner, group.span_open(), "the interval's lower end")?;
                if !inner.peek(Token![,]) {
                    return Err(inner.error("expected `,` between the interval's two ends"));
                }
                inner.parse::<Token![,]>()?;
                let upper = bound(inner, group.span_close(), "the interval's upper end")?;
                if !inner.is_empty() {
                    return Err(inner.error("expected `]` or `)`: an interval has two ends"));
                }
                Ok((lower, upper))
            },
            group.stream(),
        )?;
        if lower > upper {
            return Err(syn::Error::new(
                group.span(),
                format!(
                    "the domain of `{name}` is empty: its lower end {lower} must lie below its \
                     upper end {upper}"
                ),
            ));
        }
        if lower == upper {
            return Err(syn::Error::new(
                group.span(),
                format!(
                    "the domain of `{name}` holds the one value {lower}: a parameter fixed at \
                     one value is a constant (`constants: {name} = {lower};`)"
                ),
            ));
        }
        return Ok(Domain {
            lower,
            lower_closed: closed,
            upper,
            upper_closed: closed,
        });
    }
    let (op, span) = if input.peek(Token![>=]) {
        (">=", input.parse::<Token![>=]>()?.spans[0])
    } else if input.peek(Token![<=]) {
        ("<=", input.parse::<Token![<=]>()?.spans[0])
    } else if input.peek(Token![>]) {
        (">", input.parse::<Token![>]>()?.span)
    } else {
        ("<", input.parse::<Token![<]>()?.span)
    };
    let value = bound(input, span, &format!("the bound after `{op}`"))?;
    Ok(match op {
        ">" | ">=" => Domain {
            lower: value,
            lower_closed: op == ">=",
            upper: inf,
            upper_closed: false,
        },
        _ => Domain {
            lower: -inf,
            lower_closed: false,
            upper: value,
            upper_closed: op == "<=",
        },
    })
}

/// A finite number literal, optionally negative; `after` is the span of
/// what it follows, for an error where nothing does.
fn bound(input: ParseStream, after: Span, what: &str) -> syn::Result<f64> {
    let negative = if input.peek(Token![-]) {
        input.parse::<Token![-]>()?;
        true
    } else {
        false
    };
    let (value, span) = if input.peek(syn::LitInt) {
        let lit: syn::LitInt = input.parse()?;
        (lit.base10_parse::<f64>().ok(), lit.span())
    } else if input.peek(syn::LitFloat) {
        let lit: syn::LitFloat = input.parse()?;
        (lit.base10_parse::<f64>().ok(), lit.span())
    } else if input.is_empty() || input.peek(Token![,]) || input.peek(Token![;]) {
        return Err(syn::Error::new(
            after,
            format!("expected a number: {what} is missing (a domain is written `l > 0`)"),
        ));
    } else {
        let span = input.span();
        return Err(syn::Error::new(
            span,
            format!(
                "{what} must be a number literal (`0`, `-1.5`, `1e-3`): a domain's bounds \
                 are not expressions, names or constants"
            ),
        ));
    };
    match value {
        Some(v) if v.is_finite() => {
            let v = if negative { -v } else { v };
            // `-0` is `0`: the bound is written the same either way.
            Ok(if v == 0.0 { 0.0 } else { v })
        }
        _ => Err(syn::Error::new(
            span,
            format!("{what} is not a finite number"),
        )),
    }
}

/// Past a malformed domain: to the next `,` or `;` of the section (not
/// consumed), so that the parse goes on at the next name.
pub(super) fn skip_to_separator(input: ParseStream) -> syn::Result<()> {
    input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tt, next)) = rest.token_tree() {
            if let TokenTree::Punct(p) = &tt {
                if p.as_char() == ',' || p.as_char() == ';' {
                    return Ok(((), rest));
                }
            }
            rest = next;
        }
        Ok(((), rest))
    })
}
