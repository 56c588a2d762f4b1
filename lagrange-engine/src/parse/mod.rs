//! Tokens → [`ast::ModelDef`](crate::ast::ModelDef).
//!
//! Expressions use mathematical precedence, not Rust's: `^` is power and binds
//! tighter than unary minus (`-x^2 = -(x²)`), which binds tighter than `*` and
//! `/` (`a*b^2 = a·b²`); `^` is right-associative and its exponent may carry a
//! sign (`x^-1`). Rust method syntax (`x.sin()`, `x.powi(2)`) means the same as
//! the function form.
//!
//! A malformed section does not stop the parse: the parser records the first
//! error, skips to the next `;` and goes on, so the fallback can still emit a
//! stub with the coordinates and parameters that were declared (one mistake,
//! one error).

use crate::ast::{BinOp, Decl, Expr, IndexRange, Item, ModelDef, Options, SpanRange};
use proc_macro2::{TokenStream, TokenTree};
use syn::parse::{ParseStream, Parser};
use syn::{
    braced, bracketed, parenthesized, Attribute, Ident, LitFloat, LitInt, Token, Visibility,
};

/// The sections a model may contain, for error messages.
pub const SECTIONS: &str =
    "`const`, `coordinates:`, `parameters:`, `constants:`, `let`, `kinetic:`, \
     `potential:`, `dissipation:` or `forces:`";

/// A parsed model and the first error met inside its body, if any.
pub struct Parsed {
    pub model: ModelDef,
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
    parser.parse2(tokens)
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
            } else {
                Err(meta.error(
                    "unknown option: `#[lagrange(...)]` takes `jacobians` (exact residual Jacobians for implicit integrators)",
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
        let index = if input.peek(syn::token::Bracket) {
            let inner;
            bracketed!(inner in input);
            Some(drain_on_error(&inner, |inner| {
                let range = parse_index_range(inner)?;
                if !inner.is_empty() {
                    return Err(inner.error("expected `]` after the range"));
                }
                Ok(range)
            })?)
        } else {
            None
        };
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
        "constants",
        "kinetic",
        "potential",
        "dissipation",
        "forces",
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
            names: parse_names(input, error)?,
            keyword,
        },
        "parameters" => Item::Parameters {
            names: parse_names(input, error)?,
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

fn parse_names(input: ParseStream, error: &mut Option<syn::Error>) -> syn::Result<Vec<Decl>> {
    let mut names = Vec::new();
    loop {
        if input.peek(Token![;]) && !names.is_empty() {
            input.parse::<Token![;]>()?;
            return Ok(names);
        }
        let name = plain_name(input)?;
        let len = parse_bracket(input)?.map(|(len, _)| len);
        names.push(Decl { name, len });
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

/// `[expr]` after a name, if there: the expression and the closing span.
fn parse_bracket(input: ParseStream) -> syn::Result<Option<(Expr, proc_macro2::Span)>> {
    if !input.peek(syn::token::Bracket) {
        return Ok(None);
    }
    let inner;
    let bracket = bracketed!(inner in input);
    if inner.is_empty() {
        return Err(syn::Error::new(
            bracket.span.join(),
            "empty brackets: expected an index or a length inside `[]`",
        ));
    }
    let e = drain_on_error(&inner, |inner| {
        let e = parse_expr(inner)?;
        if !inner.is_empty() {
            return Err(inner.error("expected an operator or `]`"));
        }
        Ok(e)
    })?;
    Ok(Some((e, bracket.span.close())))
}

/// `var in lo..hi` or `var in lo..=hi`.
fn parse_index_range(input: ParseStream) -> syn::Result<IndexRange> {
    let var = plain_name(input)?;
    if !input.peek(Token![in]) {
        return Err(input.error(format!(
            "expected `in`: an index is written `{var} in 0..N` or `{var} in 0..=i`"
        )));
    }
    input.parse::<Token![in]>()?;
    let lo = parse_expr(input)?;
    let inclusive = if input.peek(Token![..=]) {
        input.parse::<Token![..=]>()?;
        true
    } else if input.peek(Token![..]) {
        input.parse::<Token![..]>()?;
        false
    } else {
        return Err(input.error("expected `..` or `..=`: a range is written `0..N` or `0..=i`"));
    };
    let hi = parse_expr(input)?;
    Ok(IndexRange {
        range: SpanRange::single(var.span()).to(hi.range()),
        var,
        lo: Box::new(lo),
        hi: Box::new(hi),
        inclusive,
    })
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

/// `sum := product (('+' | '-') product)*`
pub fn parse_expr(input: ParseStream) -> syn::Result<Expr> {
    let mut lhs = parse_product(input)?;
    loop {
        let op = if input.peek(Token![+]) {
            input.parse::<Token![+]>()?;
            BinOp::Add
        } else if input.peek(Token![-]) {
            input.parse::<Token![-]>()?;
            BinOp::Sub
        } else {
            return Ok(lhs);
        };
        let rhs = parse_product(input)?;
        lhs = binary(op, lhs, rhs);
    }
}

fn binary(op: BinOp, lhs: Expr, rhs: Expr) -> Expr {
    Expr::Binary {
        op,
        range: lhs.range().to(rhs.range()),
        lhs: Box::new(lhs),
        rhs: Box::new(rhs),
    }
}

/// `product := unary (('*' | '/') unary)*`
fn parse_product(input: ParseStream) -> syn::Result<Expr> {
    let mut lhs = parse_unary(input)?;
    loop {
        let op = if input.peek(Token![*]) {
            input.parse::<Token![*]>()?;
            BinOp::Mul
        } else if input.peek(Token![/]) {
            input.parse::<Token![/]>()?;
            BinOp::Div
        } else {
            return Ok(lhs);
        };
        let rhs = parse_unary(input)?;
        lhs = binary(op, lhs, rhs);
    }
}

/// `unary := '-' unary | power`
fn parse_unary(input: ParseStream) -> syn::Result<Expr> {
    if input.peek(Token![-]) {
        let minus = input.parse::<Token![-]>()?;
        let inner = parse_unary(input)?;
        return Ok(Expr::Neg {
            range: SpanRange::single(minus.span).to(inner.range()),
            inner: Box::new(inner),
        });
    }
    parse_power(input)
}

/// `power := postfix ('^' unary)?` — right-associative through `unary`.
fn parse_power(input: ParseStream) -> syn::Result<Expr> {
    let base = parse_postfix(input)?;
    if input.peek(Token![^]) {
        input.parse::<Token![^]>()?;
        let exponent = parse_unary(input)?;
        return Ok(binary(BinOp::Pow, base, exponent));
    }
    Ok(base)
}

/// `postfix := primary ('.' name '(' args ')')*`
fn parse_postfix(input: ParseStream) -> syn::Result<Expr> {
    let mut e = parse_primary(input)?;
    while input.peek(Token![.]) && !input.peek(Token![..]) {
        input.parse::<Token![.]>()?;
        let method: Ident = input.parse()?;
        if !input.peek(syn::token::Paren) {
            return Err(syn::Error::new(
                method.span(),
                format!(
                    "expected `(` after `.{method}`: only method calls such as `x.sin()` or `x.powi(2)` may follow a `.`"
                ),
            ));
        }
        let (mut args, close) = parse_args(input)?;
        args.insert(0, e);
        e = Expr::Call {
            range: args[0].range().to(SpanRange::single(close)),
            func: method,
            args,
        };
    }
    Ok(e)
}

fn parse_args(input: ParseStream) -> syn::Result<(Vec<Expr>, proc_macro2::Span)> {
    let inner;
    let paren = parenthesized!(inner in input);
    let args = drain_on_error(&inner, |inner| {
        let mut args = Vec::new();
        while !inner.is_empty() {
            args.push(parse_expr(inner)?);
            if inner.is_empty() {
                break;
            }
            if !inner.peek(Token![,]) {
                return Err(inner.error("expected an operator, `,` or `)`"));
            }
            inner.parse::<Token![,]>()?;
        }
        Ok(args)
    })?;
    Ok((args, paren.span.close()))
}

/// Parses a delimited group; on error, consumes the rest of it. Tokens left
/// in a group make syn fail the whole macro input with its own "unexpected
/// token", which would replace our error and lose the stub.
fn drain_on_error<T>(
    inner: ParseStream,
    f: impl FnOnce(ParseStream) -> syn::Result<T>,
) -> syn::Result<T> {
    f(inner).inspect_err(|_| {
        let _ = inner.step(|cursor| {
            let mut rest = *cursor;
            while let Some((_, next)) = rest.token_tree() {
                rest = next;
            }
            Ok(((), rest))
        });
    })
}

/// `primary := number | name | name '(' args ')' | '(' sum ')'`
fn parse_primary(input: ParseStream) -> syn::Result<Expr> {
    if input.peek(LitInt) {
        let lit: LitInt = input.parse()?;
        let value = lit
            .base10_digits()
            .parse::<f64>()
            .map_err(|_| syn::Error::new(lit.span(), "this number is not a real number"))?;
        return Ok(Expr::Num {
            value,
            span: lit.span(),
        });
    }
    if input.peek(LitFloat) {
        let lit: LitFloat = input.parse()?;
        let value = lit
            .base10_digits()
            .parse::<f64>()
            .map_err(|_| syn::Error::new(lit.span(), "this number is not a real number"))?;
        return Ok(Expr::Num {
            value,
            span: lit.span(),
        });
    }
    if input.peek(syn::token::Paren) {
        let inner;
        let paren = parenthesized!(inner in input);
        if inner.is_empty() {
            return Err(syn::Error::new(
                paren.span.join(),
                "empty parentheses: expected an expression inside `()`",
            ));
        }
        return drain_on_error(&inner, |inner| {
            let e = parse_expr(inner)?;
            if !inner.is_empty() {
                return Err(inner.error("expected an operator or `)`"));
            }
            Ok(e)
        });
    }
    if input.peek(syn::Ident) {
        let name: Ident = plain_name(input)?;
        if name == "sum" && input.peek(syn::token::Paren) {
            return parse_sum(input, name);
        }
        if let Some((index, close)) = parse_bracket(input)? {
            return Ok(Expr::Index {
                range: SpanRange::single(name.span()).to(SpanRange::single(close)),
                base: name,
                index: Box::new(index),
            });
        }
        if input.peek(syn::token::Paren) {
            let (args, close) = parse_args(input)?;
            return Ok(Expr::Call {
                range: SpanRange::single(name.span()).to(SpanRange::single(close)),
                func: name,
                args,
            });
        }
        return Ok(Expr::Name(name));
    }
    if input.is_empty() || input.peek(Token![;]) || input.peek(Token![,]) {
        return Err(input.error("expected an expression here"));
    }
    Err(input.error("expected an expression: a number, a name, a function call or `(`"))
}

/// `sum(j in a..b, body)`.
fn parse_sum(input: ParseStream, keyword: Ident) -> syn::Result<Expr> {
    let inner;
    let paren = parenthesized!(inner in input);
    let (index, body) = drain_on_error(&inner, |inner| {
        if inner.is_empty() {
            return Err(inner
                .error("expected an index and a term: a sum is written `sum(i in 0..N, term)`"));
        }
        let index = parse_index_range(inner)?;
        if !inner.peek(Token![,]) {
            return Err(
                inner.error("expected `,` and the term: a sum is written `sum(i in 0..N, term)`")
            );
        }
        inner.parse::<Token![,]>()?;
        let body = parse_expr(inner)?;
        if inner.peek(Token![,]) {
            inner.parse::<Token![,]>()?;
        }
        if !inner.is_empty() {
            return Err(inner.error("expected an operator or `)`"));
        }
        Ok((index, body))
    })?;
    Ok(Expr::Sum {
        range: SpanRange::single(keyword.span()).to(SpanRange::single(paren.span.close())),
        index,
        body: Box::new(body),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn expr(src: &str) -> Expr {
        parse_expr.parse_str(src).unwrap()
    }

    fn show(e: &Expr) -> String {
        match e {
            Expr::Num { value, .. } => format!("{value}"),
            Expr::Name(n) => n.to_string(),
            Expr::Neg { inner, .. } => format!("(-{})", show(inner)),
            Expr::Binary { op, lhs, rhs, .. } => {
                let o = match op {
                    BinOp::Add => "+",
                    BinOp::Sub => "-",
                    BinOp::Mul => "*",
                    BinOp::Div => "/",
                    BinOp::Pow => "^",
                };
                format!("({} {o} {})", show(lhs), show(rhs))
            }
            Expr::Call { func, args, .. } => {
                let a: Vec<String> = args.iter().map(show).collect();
                format!("{func}({})", a.join(", "))
            }
            Expr::Index { base, index, .. } => format!("{base}[{}]", show(index)),
            Expr::Sum { index, body, .. } => format!(
                "sum({} in {}{}{}, {})",
                index.var,
                show(&index.lo),
                if index.inclusive { "..=" } else { ".." },
                show(&index.hi),
                show(body)
            ),
        }
    }

    #[test]
    fn power_binds_tighter_than_unary_minus_and_product() {
        assert_eq!(show(&expr("-x^2")), "(-(x ^ 2))");
        assert_eq!(show(&expr("a*b^2")), "(a * (b ^ 2))");
        assert_eq!(show(&expr("x^-1")), "(x ^ (-1))");
        assert_eq!(show(&expr("a^b^c")), "(a ^ (b ^ c))");
        assert_eq!(show(&expr("m1/2*(x + y)")), "((m1 / 2) * (x + y))");
        assert_eq!(show(&expr("a - b - c")), "((a - b) - c)");
    }

    #[test]
    fn indices_and_sums() {
        assert_eq!(show(&expr("x[i-1]^2")), "(x[(i - 1)] ^ 2)");
        assert_eq!(
            show(&expr("sum(j in 0..=i, l[j]*sin(theta[j]))")),
            "sum(j in 0..=i, (l[j] * sin(theta[j])))"
        );
        assert_eq!(
            show(&expr("-sum(j in i+1..N, m[j])")),
            "(-sum(j in (i + 1)..N, m[j]))"
        );
    }

    #[test]
    fn method_syntax_is_a_call_with_the_receiver_first() {
        assert_eq!(show(&expr("x.sin()")), "sin(x)");
        assert_eq!(show(&expr("(a - b).cos()")), "cos((a - b))");
        assert_eq!(show(&expr("x.powi(2) * 2.0")), "(powi(x, 2) * 2)");
        assert_eq!(show(&expr("y.atan2(x)")), "atan2(y, x)");
    }
}
